// Step 8SC (spec §B.10): seam carving with frozen pixels and the aligned extra-data (index) matrix.
#include "urbanvec/shrink/seam_carving.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace urbanvec::shrink {
namespace {

/// The image being carved, always carved along its rows (vertical seams); horizontal seams run on the
/// transposed image. `transposed` says which orientation the buffers hold.
struct Work {
  std::vector<float> energy;
  std::vector<std::int32_t> index;  ///< original pixel index of each current pixel
  int rows = 0, cols = 0;
  size_t stride = 0;
  bool transposed = false;
  std::vector<float> prev, cur;            ///< two rows of cumulative energy
  std::vector<std::int8_t> back;          ///< predecessor offset (-1, 0, 1) per pixel
  std::vector<int> seam;

  void transpose() {
    const size_t newStride = static_cast<size_t>(rows);
    std::vector<float> e(static_cast<size_t>(cols) * newStride);
    std::vector<std::int32_t> idx(e.size());
    constexpr int B = 32;
    for (int r0 = 0; r0 < rows; r0 += B)
      for (int c0 = 0; c0 < cols; c0 += B)
        for (int r = r0; r < std::min(rows, r0 + B); ++r)
          for (int c = c0; c < std::min(cols, c0 + B); ++c) {
            e[static_cast<size_t>(c) * newStride + static_cast<size_t>(r)] = energy[static_cast<size_t>(r) * stride + static_cast<size_t>(c)];
            idx[static_cast<size_t>(c) * newStride + static_cast<size_t>(r)] = index[static_cast<size_t>(r) * stride + static_cast<size_t>(c)];
          }
    energy.swap(e);
    index.swap(idx);
    std::swap(rows, cols);
    stride = newStride;
    transposed = !transposed;
  }

  /// Minimal vertical seam of the current buffers; false when every seam crosses +infinity.
  bool findSeam() {
    const size_t w = static_cast<size_t>(cols);
    prev.assign(energy.begin(), energy.begin() + static_cast<std::ptrdiff_t>(w));
    cur.resize(w);
    back.resize(static_cast<size_t>(rows) * w);
    for (int r = 1; r < rows; ++r) {
      const float* e = &energy[static_cast<size_t>(r) * stride];
      std::int8_t* b = &back[static_cast<size_t>(r) * w];
      for (size_t c = 0; c < w; ++c) {
        float best = prev[c];
        std::int8_t step = 0;
        if (c > 0 && prev[c - 1] < best) best = prev[c - 1], step = -1;
        if (c + 1 < w && prev[c + 1] < best) best = prev[c + 1], step = 1;
        cur[c] = e[c] + best;
        b[c] = step;
      }
      prev.swap(cur);
    }
    size_t end = 0;
    for (size_t c = 1; c < w; ++c)
      if (prev[c] < prev[end]) end = c;
    if (!std::isfinite(prev[end])) return false;
    seam.resize(static_cast<size_t>(rows));
    int c = static_cast<int>(end);
    for (int r = rows - 1; r >= 0; --r) {
      seam[static_cast<size_t>(r)] = c;
      if (r > 0) c += back[static_cast<size_t>(r) * w + static_cast<size_t>(c)];
    }
    return true;
  }

  /// A row (of the current buffers) frozen from edge to edge: the original index of its first pixel,
  /// else -1.
  int frozenLine() const {
    for (int r = 0; r < rows; ++r) {
      const float* e = &energy[static_cast<size_t>(r) * stride];
      if (std::all_of(e, e + cols, [](float v) { return std::isinf(v); }))
        return index[static_cast<size_t>(r) * stride];
    }
    return -1;
  }
};

}  // namespace

CarveResult carveSeams(const std::vector<float>& energy, int width, int height, int vertical, int horizontal,
                       SeamOrder order, const Progress& progress) {
  CarveResult result;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  Work work;
  work.energy = energy;
  work.index.resize(n);
  for (size_t i = 0; i < n; ++i) work.index[i] = static_cast<std::int32_t>(i);
  work.rows = height;
  work.cols = width;
  work.stride = static_cast<size_t>(width);
  result.mergedInto.assign(n, -1);
  result.mergeSide.assign(n, MergeSide::None);

  ProgressTicker ticker(progress, "seam carving", static_cast<size_t>(vertical + horizontal));
  int leftV = vertical, leftH = horizontal;
  bool blockedV = false, blockedH = false;
  while ((leftV > 0 && !blockedV) || (leftH > 0 && !blockedH)) {
    bool doVertical;
    if (order == SeamOrder::Blocks)
      doVertical = leftV > 0 && !blockedV;
    else  // interleaved: vertical when it has at least as many seams left as horizontal
      doVertical = leftV > 0 && !blockedV && (leftH == 0 || blockedH || leftV >= leftH);
    // Vertical seams in image terms run along the buffer rows when it is not transposed.
    if (work.transposed == doVertical) work.transpose();
    if (work.cols <= 1 || !work.findSeam()) {
      const int line = work.frozenLine();
      (doVertical ? blockedV : blockedH) = true;
      (doVertical ? result.verticalBlockedAt : result.horizontalBlockedAt) = line;
      continue;
    }
    CarvedSeam seam;
    seam.vertical = doVertical;
    seam.pixels.resize(static_cast<size_t>(work.rows));
    for (int r = 0; r < work.rows; ++r) {
      const int c = work.seam[static_cast<size_t>(r)];
      std::int32_t* idx = &work.index[static_cast<size_t>(r) * work.stride];
      float* e = &work.energy[static_cast<size_t>(r) * work.stride];
      const int removed = idx[c];
      seam.pixels[static_cast<size_t>(r)] = removed;
      const bool ontoLower = c > 0;  // collapse onto the previous pixel of the line, else the next
      result.mergedInto[static_cast<size_t>(removed)] = idx[ontoLower ? c - 1 : c + 1];
      result.mergeSide[static_cast<size_t>(removed)] =
          doVertical ? (ontoLower ? MergeSide::OntoLeft : MergeSide::OntoRight)
                     : (ontoLower ? MergeSide::OntoAbove : MergeSide::OntoBelow);
      const size_t tail = static_cast<size_t>(work.cols - 1 - c);
      std::memmove(idx + c, idx + c + 1, tail * sizeof(std::int32_t));
      std::memmove(e + c, e + c + 1, tail * sizeof(float));
    }
    --work.cols;
    result.seams.push_back(std::move(seam));
    if (doVertical) --leftV, ++result.verticalRemoved;
    else --leftH, ++result.horizontalRemoved;
    ticker.tick();
  }
  if (work.transposed) work.transpose();
  ticker.finish();
  result.width = work.cols;
  result.height = work.rows;
  result.finalRow.assign(n, -1);
  result.finalCol.assign(n, -1);
  for (int r = 0; r < work.rows; ++r)
    for (int c = 0; c < work.cols; ++c) {
      const size_t o = static_cast<size_t>(work.index[static_cast<size_t>(r) * work.stride + static_cast<size_t>(c)]);
      result.finalRow[o] = r;
      result.finalCol[o] = c;
    }
  return result;
}

}  // namespace urbanvec::shrink
