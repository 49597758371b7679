// Step 8SC (spec §B.10): seam carving with frozen pixels and the aligned extra-data (index) matrix.
#include "urbanvec/shrink/seam_carving.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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
  std::vector<float> cumulative;  ///< M of the dynamic programme, rows x cols
  std::vector<int> seam;

  std::vector<float> energyScratch;
  std::vector<std::int32_t> indexScratch;

  void transpose() {
    const size_t newStride = static_cast<size_t>(rows);
    const size_t need = static_cast<size_t>(cols) * newStride;
    if (energyScratch.size() < need) energyScratch.resize(need), indexScratch.resize(need);
    constexpr int B = 64;
    for (int r0 = 0; r0 < rows; r0 += B)
      for (int c0 = 0; c0 < cols; c0 += B) {
        const int r1 = std::min(rows, r0 + B), c1 = std::min(cols, c0 + B);
        for (int r = r0; r < r1; ++r) {
          const float* e = &energy[static_cast<size_t>(r) * stride];
          const std::int32_t* x = &index[static_cast<size_t>(r) * stride];
          float* te = &energyScratch[static_cast<size_t>(r)];
          std::int32_t* tx = &indexScratch[static_cast<size_t>(r)];
          for (int c = c0; c < c1; ++c) {
            te[static_cast<size_t>(c) * newStride] = e[c];
            tx[static_cast<size_t>(c) * newStride] = x[c];
          }
        }
      }
    energy.swap(energyScratch);
    index.swap(indexScratch);
    std::swap(rows, cols);
    stride = newStride;
    transposed = !transposed;
  }

  /// Minimal vertical seam of the current buffers; false when every seam crosses +infinity. The
  /// cumulative energy M is kept for every pixel (a branch-free min of three, which vectorises) and the
  /// seam is traced back by comparing the three cells above.
  bool findSeam() {
    const size_t w = static_cast<size_t>(cols);
    cumulative.resize(static_cast<size_t>(rows) * w);
    std::copy(energy.begin(), energy.begin() + static_cast<std::ptrdiff_t>(w), cumulative.begin());
    for (int r = 1; r < rows; ++r) {
      const float* e = &energy[static_cast<size_t>(r) * stride];
      const float* p = &cumulative[static_cast<size_t>(r - 1) * w];
      float* q = &cumulative[static_cast<size_t>(r) * w];
      if (w == 1) {
        q[0] = e[0] + p[0];
        continue;
      }
      q[0] = e[0] + std::min(p[0], p[1]);
      for (size_t c = 1; c + 1 < w; ++c) q[c] = e[c] + std::min(std::min(p[c - 1], p[c]), p[c + 1]);
      q[w - 1] = e[w - 1] + std::min(p[w - 2], p[w - 1]);
    }
    const float* last = &cumulative[static_cast<size_t>(rows - 1) * w];
    size_t end = 0;
    for (size_t c = 1; c < w; ++c)
      if (last[c] < last[end]) end = c;
    if (!std::isfinite(last[end])) return false;
    seam.resize(static_cast<size_t>(rows));
    size_t c = end;
    for (int r = rows - 1; r >= 0; --r) {
      seam[static_cast<size_t>(r)] = static_cast<int>(c);
      if (r == 0) break;
      const float* p = &cumulative[static_cast<size_t>(r - 1) * w];
      size_t next = c;  // straight up first, then left, then right
      if (c > 0 && p[c - 1] < p[next]) next = c - 1;
      if (c + 1 < w && p[c + 1] < p[next]) next = c + 1;
      c = next;
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
                       SeamOrder order, const Progress& progress, const std::vector<int>* wayLabels,
                       const std::vector<int>* pieceWay) {
  CarveResult result;
  std::vector<int> label;
  if (wayLabels) label = *wayLabels;
  std::vector<int> relabelled;  // per line of the current seam: column of the pixel that took a way, else -1
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
  constexpr float kInf = std::numeric_limits<float>::infinity();
  auto sameWay = [&](int a, int b) {
    return a == b || (a >= 0 && b >= 0 && pieceWay &&
                      (*pieceWay)[static_cast<size_t>(a)] == (*pieceWay)[static_cast<size_t>(b)] &&
                      std::abs(a - b) <= 1);
  };
  // Two ways within one pixel: freeze both pixels (buffer offsets).
  auto separate = [&](size_t p, size_t q) {
    const int lp = label[static_cast<size_t>(work.index[p])], lq = label[static_cast<size_t>(work.index[q])];
    if (lp == -1 || lq == -1 || (lp >= 0 && sameWay(lp, lq))) return;
    for (size_t o : {p, q})
      if (!std::isinf(work.energy[o])) work.energy[o] = kInf, ++result.separationFrozen;
  };
  if (!label.empty()) {
    for (int r = 0; r < height; ++r)
      for (int c = 0; c < width; ++c) {
        const size_t p = static_cast<size_t>(r) * static_cast<size_t>(width) + static_cast<size_t>(c);
        if (label[p] == -1) continue;  // no way here: no pair to separate
        if (label[p] == -2) separate(p, p);
        if (c + 1 < width) separate(p, p + 1);
        if (r + 1 < height) {
          const size_t below = p + static_cast<size_t>(width);
          separate(p, below);
          if (c > 0) separate(p, below - 1);
          if (c + 1 < width) separate(p, below + 1);
        }
      }
  }

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
    if (!label.empty()) relabelled.assign(static_cast<size_t>(work.rows), -1);
    seam.pixels.resize(static_cast<size_t>(work.rows));
    for (int r = 0; r < work.rows; ++r) {
      const int c = work.seam[static_cast<size_t>(r)];
      std::int32_t* idx = &work.index[static_cast<size_t>(r) * work.stride];
      float* e = &work.energy[static_cast<size_t>(r) * work.stride];
      const int removed = idx[c];
      seam.pixels[static_cast<size_t>(r)] = removed;
      const bool ontoLower = c > 0;  // collapse onto the previous pixel of the line, else the next
      result.mergedInto[static_cast<size_t>(removed)] = idx[ontoLower ? c - 1 : c + 1];
      if (!label.empty()) {  // the removed pixel's ways now lie on the edge of the pixel it collapsed onto
        int& onto = label[static_cast<size_t>(idx[ontoLower ? c - 1 : c + 1])];
        const int mine = label[static_cast<size_t>(removed)];
        if (mine != -1 && !sameWay(onto, mine)) {
          // The onto pixel's new way must be kept apart from its other neighbours too (below).
          relabelled[static_cast<size_t>(r)] = ontoLower ? c - 1 : c;
          onto = onto == -1 ? mine : -2;
          if (onto == -2) {
            float& eo = e[ontoLower ? c - 1 : c + 1];
            if (!std::isinf(eo)) eo = kInf, ++result.separationFrozen;
          }
        }
      }
      result.mergeSide[static_cast<size_t>(removed)] =
          doVertical ? (ontoLower ? MergeSide::OntoLeft : MergeSide::OntoRight)
                     : (ontoLower ? MergeSide::OntoAbove : MergeSide::OntoBelow);
      const size_t tail = static_cast<size_t>(work.cols - 1 - c);
      std::memmove(idx + c, idx + c + 1, tail * sizeof(std::int32_t));
      std::memmove(e + c, e + c + 1, tail * sizeof(float));
    }
    --work.cols;
    if (!label.empty()) {  // new neighbours across the seam
      for (int r = 0; r < work.rows; ++r) {
        const int c = std::min(work.seam[static_cast<size_t>(r)], work.cols - 1);
        const size_t row = static_cast<size_t>(r) * work.stride;
        for (int left = std::max(c - 1, 0); left <= c && left + 1 < work.cols; ++left) {
          const size_t p = row + static_cast<size_t>(left);
          separate(p, p + 1);
          if (r + 1 < work.rows) separate(p, p + work.stride + 1), separate(p + 1, p + work.stride);
          if (r > 0) separate(p, p - work.stride + 1), separate(p + 1, p - work.stride);
        }
        // A pixel that took over a removed pixel's way (new column after the shift) against its 8
        // neighbours: without this, a way carried along by successive seams meets another way unseen.
        const int o = relabelled[static_cast<size_t>(r)];
        if (o < 0) continue;
        const size_t q = row + static_cast<size_t>(o);
        for (int dr = -1; dr <= 1; ++dr)
          for (int dc = -1; dc <= 1; ++dc) {
            const int rr = r + dr, cc = o + dc;
            if ((dr == 0 && dc == 0) || rr < 0 || rr >= work.rows || cc < 0 || cc >= work.cols) continue;
            separate(q, static_cast<size_t>(rr) * work.stride + static_cast<size_t>(cc));
          }
      }
    }
    result.seams.push_back(std::move(seam));
    if (doVertical)
      --leftV, ++result.verticalRemoved;
    else
      --leftH, ++result.horizontalRemoved;
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
      const size_t o =
          static_cast<size_t>(work.index[static_cast<size_t>(r) * work.stride + static_cast<size_t>(c)]);
      result.finalRow[o] = r;
      result.finalCol[o] = c;
    }
  return result;
}

}  // namespace urbanvec::shrink
