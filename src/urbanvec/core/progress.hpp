// Progress reporting and cancellation (CONVENTIONS.md "Library shape").
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace urbanvec {

/// Called with a fraction in [0, 1] and the current stage name; returning false cancels.
using Progress = std::function<bool(double fraction, std::string_view stage)>;

/// Reports progress; throws Cancelled when the callback asks to stop. An empty callback is a no-op.
void reportProgress(const Progress& progress, double fraction, std::string_view stage);

/// A callback mapping [0, 1] onto [from, to] of `parent`, for one stage of a pipeline.
Progress subProgress(const Progress& parent, double from, double to);

/// Wraps a callback so that fractions never go backwards and stay within [0, 1].
Progress monotonicProgress(Progress inner);

/// Reports item-by-item progress of a loop without calling the callback more than ~200 times.
class ProgressTicker {
 public:
  ProgressTicker(const Progress& progress, std::string_view stage, size_t total);
  /// Call once per finished item; throws Cancelled when asked to stop.
  void tick(size_t done = 1);
  void finish();

 private:
  const Progress& progress_;
  std::string stage_;
  size_t total_;
  size_t done_ = 0;
  size_t nextReport_ = 0;
};

}  // namespace urbanvec
