#include "urbanvec/core/progress.hpp"

#include <algorithm>
#include <memory>

#include "urbanvec/core/error.hpp"

namespace urbanvec {

void reportProgress(const Progress& progress, double fraction, std::string_view stage) {
  if (progress && !progress(std::clamp(fraction, 0.0, 1.0), stage)) throw Cancelled();
}

Progress subProgress(const Progress& parent, double from, double to) {
  if (!parent) return {};
  return [parent, from, to](double fraction, std::string_view stage) {
    return parent(from + (to - from) * std::clamp(fraction, 0.0, 1.0), stage);
  };
}

Progress monotonicProgress(Progress inner) {
  if (!inner) return {};
  auto last = std::make_shared<double>(0.0);
  return [inner = std::move(inner), last](double fraction, std::string_view stage) {
    *last = std::max(*last, std::clamp(fraction, 0.0, 1.0));
    return inner(*last, stage);
  };
}

ProgressTicker::ProgressTicker(const Progress& progress, std::string_view stage, size_t total)
    : progress_(progress), stage_(stage), total_(total) {
  reportProgress(progress_, 0.0, stage_);
}

void ProgressTicker::tick(size_t done) {
  done_ += done;
  if (done_ >= nextReport_ && total_ > 0) {
    reportProgress(progress_, static_cast<double>(done_) / static_cast<double>(total_), stage_);
    nextReport_ = done_ + std::max<size_t>(1, total_ / 200);
  }
}

void ProgressTicker::finish() { reportProgress(progress_, 1.0, stage_); }

}  // namespace urbanvec
