// Step 8SC (spec §B.10): seam carving with frozen pixels and the aligned extra-data (index) matrix,
// an incrementally updated cumulative energy, and the crossing guard (no seam makes two ways cross).
#include "urbanvec/shrink/seam_carving.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <thread>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/segment_contact.hpp"

namespace urbanvec::shrink {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// out[c - lo] = e[c] + min(p[c-1], p[c], p[c+1]) for c in [lo, hi] (the neighbours that exist in a
/// row of `w` cells): one row of the dynamic programme, branch-free in the interior so it vectorises
/// (the AVX2 clone is picked at run time; min and + are exact, so every clone gives the same values).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void dpRow(const float* e, const float* p, float* out, int lo, int hi, int w) {
  int c = lo;
  if (c == 0) {
    out[0] = e[0] + (w > 1 ? std::min(p[0], p[1]) : p[0]);
    c = 1;
  }
  const bool last = w > 1 && hi == w - 1;
  const int end = last ? hi - 1 : hi;
  float* o = out - lo;
  for (; c <= end; ++c) o[c] = e[c] + std::min(std::min(p[c - 1], p[c]), p[c + 1]);
  if (last && c == w - 1) o[w - 1] = e[w - 1] + std::min(p[w - 2], p[w - 1]);
}

/// Index of the first / last of `n` cells where a and b differ bytewise (n / -1 when none), by blocks
/// of 16 cells compared with memcmp.
int firstDifference(const float* a, const float* b, int n) {
  constexpr int B = 16;
  int i = 0;
  while (i + B <= n && std::memcmp(a + i, b + i, B * sizeof(float)) == 0) i += B;
  while (i < n && std::memcmp(a + i, b + i, sizeof(float)) == 0) ++i;
  return i;
}

int lastDifference(const float* a, const float* b, int n) {
  constexpr int B = 16;
  int i = n;  // cells [i, n) are equal
  while (i - B >= 0 && std::memcmp(a + i - B, b + i - B, B * sizeof(float)) == 0) i -= B;
  while (i > 0 && std::memcmp(a + i - 1, b + i - 1, sizeof(float)) == 0) --i;
  return i - 1;
}

/// The image being carved, always carved along its rows (vertical seams); horizontal seams run on the
/// transposed image. `transposed` says which orientation the buffers hold. Each row keeps its cells
/// contiguous from `start[r]`: a seam pixel is removed by moving the shorter side of its row by one
/// cell (a memmove), in the energy, the index and the cumulative energy alike.
struct Work {
  std::vector<float> energy;
  std::vector<std::int32_t> index;  ///< original pixel index of each current pixel
  std::vector<float> cumulative;    ///< M of the dynamic programme, same layout
  std::vector<int> start;
  int rows = 0, cols = 0;
  size_t stride = 0;
  bool transposed = false;
  bool cumulativeValid = false;
  std::vector<int> seam;         ///< the seam found last: a column per row
  std::vector<int> removedSeam;  ///< the seam removed since the last update of M
  bool removedPending = false;
  std::vector<int> banLo, banHi;  ///< per row: columns set to +infinity since the last update of M
  std::vector<float> rowScratch;
  size_t cellsUpdated = 0;

  std::vector<float> energyScratch;
  std::vector<std::int32_t> indexScratch;

  size_t at(int r) const {
    return static_cast<size_t>(r) * stride + static_cast<size_t>(start[static_cast<size_t>(r)]);
  }
  float* E(int r) { return &energy[at(r)]; }
  float* M(int r) { return &cumulative[at(r)]; }
  std::int32_t* X(int r) { return &index[at(r)]; }

  void reset(int r, int c) {
    rows = r, cols = c;
    stride = static_cast<size_t>(c);
    start.assign(static_cast<size_t>(r), 0);
    banLo.assign(static_cast<size_t>(r), INT_MAX);
    banHi.assign(static_cast<size_t>(r), INT_MIN);
    cumulativeValid = removedPending = false;
  }

  void transpose() {
    const size_t need = static_cast<size_t>(cols) * static_cast<size_t>(rows);
    if (energyScratch.size() < need) energyScratch.resize(need), indexScratch.resize(need);
    const size_t newStride = static_cast<size_t>(rows);
    constexpr int B = 64;
    for (int r0 = 0; r0 < rows; r0 += B)
      for (int c0 = 0; c0 < cols; c0 += B) {
        const int r1 = std::min(rows, r0 + B), c1 = std::min(cols, c0 + B);
        for (int r = r0; r < r1; ++r) {
          const float* e = E(r);
          const std::int32_t* x = X(r);
          for (int c = c0; c < c1; ++c) {
            energyScratch[static_cast<size_t>(c) * newStride + static_cast<size_t>(r)] = e[c];
            indexScratch[static_cast<size_t>(c) * newStride + static_cast<size_t>(r)] = x[c];
          }
        }
      }
    energy.swap(energyScratch);
    index.swap(indexScratch);
    transposed = !transposed;
    reset(cols, rows);
  }

  void ban(int r, int c) {
    E(r)[c] = kInf;
    banLo[static_cast<size_t>(r)] = std::min(banLo[static_cast<size_t>(r)], c);
    banHi[static_cast<size_t>(r)] = std::max(banHi[static_cast<size_t>(r)], c);
  }

  /// Brings M up to date: all of it the first time (or after a transposition), else only the cells
  /// whose inputs changed: the cells next to the removed seam, the cells below a changed cell (the
  /// cone, cut where the new value equals the old one) and the cells given +infinity.
  void updateCumulative() {
    const int w = cols;
    if (!cumulativeValid) {
      cumulative.resize(energy.size());
      std::copy(E(0), E(0) + w, M(0));
      for (int r = 1; r < rows; ++r) dpRow(E(r), M(r - 1), M(r), 0, w - 1, w);
      cellsUpdated += static_cast<size_t>(rows) * static_cast<size_t>(w);
      cumulativeValid = true;
    } else {
      rowScratch.resize(static_cast<size_t>(w));
      int dlo = 1, dhi = 0;  // cells of the previous row whose M changed
      if (banLo[0] <= banHi[0]) {
        dlo = std::max(banLo[0], 0), dhi = std::min(banHi[0], w - 1);
        std::copy(E(0) + dlo, E(0) + dhi + 1, M(0) + dlo);
      }
      for (int r = 1; r < rows; ++r) {
        int lo = INT_MAX, hi = INT_MIN;
        if (removedPending) {
          const int a = removedSeam[static_cast<size_t>(r - 1)], b = removedSeam[static_cast<size_t>(r)];
          lo = std::min(a, b) - 1, hi = std::max(a, b);
        }
        if (dlo <= dhi) lo = std::min(lo, dlo - 1), hi = std::max(hi, dhi + 1);
        if (banLo[static_cast<size_t>(r)] <= banHi[static_cast<size_t>(r)])
          lo = std::min(lo, banLo[static_cast<size_t>(r)]), hi = std::max(hi, banHi[static_cast<size_t>(r)]);
        lo = std::max(lo, 0), hi = std::min(hi, w - 1);
        dlo = 1, dhi = 0;
        if (lo > hi) continue;
        float* q = M(r);
        dpRow(E(r), M(r - 1), rowScratch.data(), lo, hi, w);
        cellsUpdated += static_cast<size_t>(hi - lo + 1);
        // The values are sums of non-negative floats (no NaN, no -0): equal values are equal bytes.
        const int n = hi - lo + 1;
        const int first = firstDifference(rowScratch.data(), q + lo, n);
        if (first == n) continue;  // nothing changed in this row: the cone ends here
        const int last = lastDifference(rowScratch.data(), q + lo, n);
        dlo = lo + first, dhi = lo + last;
        std::copy(rowScratch.begin() + first, rowScratch.begin() + last + 1, q + dlo);
      }
    }
    removedPending = false;
    std::fill(banLo.begin(), banLo.end(), INT_MAX);
    std::fill(banHi.begin(), banHi.end(), INT_MIN);
  }

  /// Minimal vertical seam of the current buffers into `seam`; false when every seam crosses
  /// +infinity. The seam is traced back by comparing the three cells above.
  bool findSeam() {
    updateCumulative();
    const size_t w = static_cast<size_t>(cols);
    const float* last = M(rows - 1);
    size_t end = 0;
    for (size_t c = 1; c < w; ++c)
      if (last[c] < last[end]) end = c;
    if (!std::isfinite(last[end])) return false;
    seam.resize(static_cast<size_t>(rows));
    size_t c = end;
    for (int r = rows - 1; r >= 0; --r) {
      seam[static_cast<size_t>(r)] = static_cast<int>(c);
      if (r == 0) break;
      const float* p = M(r - 1);
      size_t next = c;  // straight up first, then left, then right
      if (c > 0 && p[c - 1] < p[next]) next = c - 1;
      if (c + 1 < w && p[c + 1] < p[next]) next = c + 1;
      c = next;
    }
    return true;
  }

  /// Removes `seam` from the buffers (M stays valid outside the cells updateCumulative revisits).
  int threads = 1;
  void removeSeam() {
    // Rows are independent: with several threads each moves its own band of rows (same result).
    const int bands =
        static_cast<size_t>(rows) * static_cast<size_t>(cols) >= (size_t{1} << 20) ? threads : 1;
    if (bands <= 1) {
      removeRows(0, rows);
    } else {
      std::vector<std::thread> helpers;
      for (int b = 1; b < bands; ++b)
        helpers.emplace_back([this, b, bands] { removeRows(rows * b / bands, rows * (b + 1) / bands); });
      removeRows(0, rows / bands);
      for (auto& t : helpers) t.join();
    }
    --cols;
    removedSeam = seam;
    removedPending = cumulativeValid;
  }

  void removeRows(int r0, int r1) {
    for (int r = r0; r < r1; ++r) {
      const int c = seam[static_cast<size_t>(r)];
      const size_t o = at(r);
      if (c < cols - 1 - c) {  // the left part is shorter: move it right
        const size_t n = static_cast<size_t>(c);
        std::memmove(&energy[o + 1], &energy[o], n * sizeof(float));
        std::memmove(&index[o + 1], &index[o], n * sizeof(std::int32_t));
        if (cumulativeValid) std::memmove(&cumulative[o + 1], &cumulative[o], n * sizeof(float));
        ++start[static_cast<size_t>(r)];
      } else {
        const size_t n = static_cast<size_t>(cols - 1 - c), from = o + static_cast<size_t>(c);
        std::memmove(&energy[from], &energy[from + 1], n * sizeof(float));
        std::memmove(&index[from], &index[from + 1], n * sizeof(std::int32_t));
        if (cumulativeValid) std::memmove(&cumulative[from], &cumulative[from + 1], n * sizeof(float));
      }
    }
  }

  /// A row (of the current buffers) frozen from edge to edge by pixels other than those with
  /// `unfrozen[original index]` (the guard's): the original index of its first pixel, else -1.
  int frozenLine(const std::vector<char>& unfrozen) {
    for (int r = 0; r < rows; ++r) {
      const float* e = E(r);
      const std::int32_t* x = X(r);
      bool all = true;
      for (int c = 0; c < cols && all; ++c)
        all = std::isinf(e[c]) && (unfrozen.empty() || !unfrozen[static_cast<size_t>(x[c])]);
      if (all) return x[0];
    }
    return -1;
  }

  /// True when a top-to-bottom 8-connected path avoids every +infinity pixel once the pixels with
  /// `unfrozen[original index]` are taken as finite.
  bool pathExistsWithout(const std::vector<char>& unfrozen) {
    std::vector<char> reach(static_cast<size_t>(cols)), next(static_cast<size_t>(cols));
    for (int r = 0; r < rows; ++r) {
      const float* e = E(r);
      const std::int32_t* x = X(r);
      bool any = false;
      for (int c = 0; c < cols; ++c) {
        const bool open = !std::isinf(e[c]) || unfrozen[static_cast<size_t>(x[c])];
        const bool from = r == 0 || reach[static_cast<size_t>(c)] ||
                          (c > 0 && reach[static_cast<size_t>(c - 1)]) ||
                          (c + 1 < cols && reach[static_cast<size_t>(c + 1)]);
        next[static_cast<size_t>(c)] = open && from;
        any = any || next[static_cast<size_t>(c)];
      }
      if (!any) return false;
      reach.swap(next);
    }
    return true;
  }
};

/// The crossing guard: the ways' points in current pixel coordinates (pixel + place inside it), and
/// the test of a seam against them.
class CrossingGuard {
 public:
  explicit CrossingGuard(const SeamWays& w) {
    const size_t n = w.col.size();
    cell_[0] = w.col, cell_[1] = w.row;
    frac_[0] = w.fx, frac_[1] = w.fy;
    newCell_.resize(n), newFrac_.resize(n), distance_.resize(n);
    ways_ = w.ways;
    places_ = w.places;
    for (int axis = 0; axis < 2; ++axis) {  // the original order of every pair of places
      const std::vector<double> c = centroids(axis, false);
      for (size_t i = 0; i < c.size(); ++i)
        for (size_t j = i + 1; j < c.size(); ++j)
          originalOrder_[axis].push_back(c[j] - c[i] > kEps ? 1 : c[j] - c[i] < -kEps ? -1 : 0);
    }
    pointWay_.assign(n, -1), pointIndex_.assign(n, -1);
    for (size_t k = 0; k < w.ways.size(); ++k)
      for (size_t i = 0; i < w.ways[k].size(); ++i) {
        const size_t p = static_cast<size_t>(w.ways[k][i]);
        if (pointWay_[p] < 0) pointWay_[p] = static_cast<int>(k), pointIndex_[p] = static_cast<int>(i);
      }
    for (const auto& way : w.ways)
      for (size_t i = 1; i < way.size(); ++i)
        if (way[i - 1] != way[i])
          segs_.push_back({std::min(way[i - 1], way[i]), std::max(way[i - 1], way[i])});
    std::sort(segs_.begin(), segs_.end());
    segs_.erase(std::unique(segs_.begin(), segs_.end()), segs_.end());
  }

  /// Moves every point by `seam` (one position along `axis` per line of the other axis: axis 0 for a
  /// vertical seam) into the scratch positions; true when no segment then crosses or touches a segment
  /// it did not before, and no two places change order. Otherwise `banLines` gets the lines of the points
  /// of every offending segment pair, `orderLines` those of the places the seam would move past another.
  bool check(const std::vector<int>& seam, int axis, std::vector<int>& banLines,
             std::vector<int>& orderLines) {
    const int lineAxis = 1 - axis;
    const std::vector<int>& along = cell_[static_cast<size_t>(axis)];
    const std::vector<int>& line = cell_[static_cast<size_t>(lineAxis)];
    const std::vector<double>& frac = frac_[static_cast<size_t>(axis)];
    for (size_t i = 0; i < along.size(); ++i) {
      const int s = seam[static_cast<size_t>(line[i])], c = along[i];
      distance_[i] = std::abs(c - s);
      if (c < s)
        newCell_[i] = c, newFrac_[i] = frac[i];
      else if (c > s)
        newCell_[i] = c - 1, newFrac_[i] = frac[i];
      else if (s > 0)  // collapses onto the right edge of its left neighbour
        newCell_[i] = s - 1, newFrac_[i] = 1.0;
      else  // the first pixel collapses onto the left edge of its right neighbour, now the first
        newCell_[i] = 0, newFrac_[i] = 0.0;
    }
    // Segments can grow along the axis (their ends on two lines move differently): the reach covers
    // the longest one, so a segment beyond it (on lines next to each other) stays apart from every
    // candidate. A segment spanning more than two lines may pass the seam between its ends: always a
    // candidate.
    int longest = 0;
    for (const auto& [a, b] : segs_)
      longest = std::max(longest, std::abs(along[static_cast<size_t>(a)] - along[static_cast<size_t>(b)]));
    const int reach = kNear + longest;
    cand_.clear();
    for (const auto& [a, b] : segs_) {
      const size_t ia = static_cast<size_t>(a), ib = static_cast<size_t>(b);
      if (std::min(distance_[ia], distance_[ib]) <= reach || std::abs(line[ia] - line[ib]) >= 2)
        cand_.push_back({std::min(line[ia], line[ib]), std::max(line[ia], line[ib]), a, b});
    }
    std::sort(cand_.begin(), cand_.end(), [](const Cand& x, const Cand& y) {
      return x.lo != y.lo ? x.lo < y.lo : x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    auto before = [&](int p) {
      const size_t i = static_cast<size_t>(p);
      return Vec2{cell_[0][i] + frac_[0][i], cell_[1][i] + frac_[1][i]};
    };
    auto after = [&](int p) {
      const size_t i = static_cast<size_t>(p);
      Vec2 v = before(p);
      (axis == 0 ? v.x : v.y) = newCell_[i] + newFrac_[i];
      return v;
    };
    banLines.clear(), orderLines.clear();
    for (size_t i = 0; i < cand_.size(); ++i) {
      const Cand& s = cand_[i];
      const Vec2 s1 = after(s.a), s2 = after(s.b);
      for (size_t j = i + 1; j < cand_.size() && cand_[j].lo <= s.hi + 1; ++j) {
        const Cand& t = cand_[j];
        const Vec2 t1 = after(t.a), t2 = after(t.b);
        if (std::min(s1.x, s2.x) > std::max(t1.x, t2.x) + kEps ||
            std::min(t1.x, t2.x) > std::max(s1.x, s2.x) + kEps ||
            std::min(s1.y, s2.y) > std::max(t1.y, t2.y) + kEps ||
            std::min(t1.y, t2.y) > std::max(s1.y, s2.y) + kEps)
          continue;
        // Points of one way between which every point landed on the same spot: the way runs through
        // that spot without a gap, so its segments there meet as if they shared a point.
        auto joined = [&](int p, int q) {
          const size_t ip = static_cast<size_t>(p), iq = static_cast<size_t>(q);
          if (pointWay_[ip] < 0 || pointWay_[ip] != pointWay_[iq]) return false;
          const std::vector<int>& way = ways_[static_cast<size_t>(pointWay_[ip])];
          const int i0 = std::min(pointIndex_[ip], pointIndex_[iq]),
                    i1 = std::max(pointIndex_[ip], pointIndex_[iq]);
          const Vec2 at = after(p);
          for (int i = i0; i <= i1; ++i)
            if (!(after(way[static_cast<size_t>(i)]) == at)) return false;
          return true;
        };
        const Contact now = contact(s.a, s.b, t.a, t.b, s1, s2, t1, t2, joined);
        if (now == Contact::None) continue;
        const Contact was = contact(s.a, s.b, t.a, t.b, before(s.a), before(s.b), before(t.a), before(t.b),
                                    [](int, int) { return false; });
        if (was == Contact::Crossing || (was == Contact::Touching && now == Contact::Touching)) continue;
        for (int p : {s.a, s.b, t.a, t.b}) banLines.push_back(line[static_cast<size_t>(p)]);
      }
    }
    // Landmark arrangement: a pair of places whose order along the axis would flip.
    if (!places_.empty()) {
      const std::vector<double> was = centroids(axis, false), now = centroids(axis, true);
      const std::vector<int>& order = originalOrder_[static_cast<size_t>(axis)];
      size_t k = 0;
      for (size_t i = 0; i < now.size(); ++i)
        for (size_t j = i + 1; j < now.size(); ++j, ++k) {
          const double d = now[j] - now[i];
          if (!((order[k] > 0 && d < -kEps) || (order[k] < 0 && d > kEps))) continue;
          // The place the seam moves (further) is the one it passes before: ban the seam on its lines.
          const size_t moved = (now[i] - was[i]) < (now[j] - was[j]) ? i : j;
          for (int p : places_[moved])
            if (newCell_[static_cast<size_t>(p)] != along[static_cast<size_t>(p)])
              orderLines.push_back(line[static_cast<size_t>(p)]);
        }
    }
    for (std::vector<int>* v : {&banLines, &orderLines}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    return banLines.empty() && orderLines.empty();
  }

  /// Centroid of each place along `axis`, at the current or (`moved`) the checked positions.
  std::vector<double> centroids(int axis, bool moved) const {
    std::vector<double> out;
    for (const auto& place : places_) {
      double sum = 0.0;
      for (int p : place) {
        const size_t i = static_cast<size_t>(p);
        sum += moved ? newCell_[i] + newFrac_[i]
                     : cell_[static_cast<size_t>(axis)][i] + frac_[static_cast<size_t>(axis)][i];
      }
      out.push_back(place.empty() ? 0.0 : sum / static_cast<double>(place.size()));
    }
    return out;
  }

  /// Commits the positions of the last check along `axis`.
  void apply(int axis) {
    cell_[static_cast<size_t>(axis)].swap(newCell_);
    frac_[static_cast<size_t>(axis)].swap(newFrac_);
  }

 private:
  enum class Contact { None, Touching, Crossing };
  struct Cand {
    int lo, hi;  ///< lines spanned
    int a, b;
  };
  /// Closer than this (pixels) counts as touching: the output coordinates are computed differently
  /// (metres), so a near-touch here must not become a crossing there.
  static constexpr double kEps = 1e-6;
  /// A segment with no point within this many pixels (plus the longest segment's extent along the axis)
  /// of the seam on its lines cannot meet a segment it did not meet: the seam moves points by at most one
  /// pixel along the axis, and the seam's place differs by at most one between neighbouring lines.
  static constexpr int kNear = 4;

  /// How segments a1a2 (at p1p2) and b1b2 (at q1q2) meet; `joined(a, b)` says when two distinct points
  /// count as one.
  template <class Joined>
  static Contact contact(int a1, int a2, int b1, int b2, const Vec2& p1, const Vec2& p2, const Vec2& q1,
                         const Vec2& q2, Joined&& joined) {
    const bool a1Shared =
        a1 == b1 || a1 == b2 || (p1 == q1 && joined(a1, b1)) || (p1 == q2 && joined(a1, b2));
    const bool a2Shared =
        a2 == b1 || a2 == b2 || (p2 == q1 && joined(a2, b1)) || (p2 == q2 && joined(a2, b2));
    if (a1Shared || a2Shared) {  // one shared point: only an overlap beyond it is a contact
      const Vec2 s = a1Shared ? p1 : p2;
      const Vec2 m = a1Shared ? p2 : p1;
      const Vec2 o = q1 == s ? q2 : q1;
      if (m == s || o == s) return Contact::None;
      return distanceToSegment(m, s, o) < kEps || distanceToSegment(o, s, m) < kEps ? Contact::Touching
                                                                                    : Contact::None;
    }
    const SegmentContact c = segmentContact(p1, p2, q1, q2);
    if (c == SegmentContact::Crossing) return Contact::Crossing;
    if (c == SegmentContact::Touching) return Contact::Touching;
    const double d = std::min(std::min(distanceToSegment(p1, q1, q2), distanceToSegment(p2, q1, q2)),
                              std::min(distanceToSegment(q1, p1, p2), distanceToSegment(q2, p1, p2)));
    return d < kEps ? Contact::Touching : Contact::None;
  }

  std::vector<std::vector<int>> ways_, places_;
  std::vector<int> originalOrder_[2];       ///< per axis, per pair of places: +1, -1 or 0 (tied)
  std::vector<int> pointWay_, pointIndex_;  ///< the first way holding each point, and its place there
  std::vector<int> cell_[2];
  std::vector<double> frac_[2];
  std::vector<int> newCell_;
  std::vector<double> newFrac_;
  std::vector<int> distance_;  ///< per point: pixels between it and the seam on its line
  std::vector<std::pair<int, int>> segs_;
  std::vector<Cand> cand_;
};

}  // namespace

CarveResult carveSeams(const std::vector<float>& energy, int width, int height, int vertical, int horizontal,
                       SeamOrder order, const Progress& progress, const SeamWays* ways, int threads) {
  CarveResult result;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  Work work;
  work.energy = energy;
  work.index.resize(n);
  for (size_t i = 0; i < n; ++i) work.index[i] = static_cast<std::int32_t>(i);
  work.reset(height, width);
  work.threads = threads > 0 ? threads : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  result.mergedInto.assign(n, -1);
  result.mergeSide.assign(n, MergeSide::None);
  std::unique_ptr<CrossingGuard> guard;
  std::vector<char> guardFrozen;  // per original pixel: frozen by the crossing guard
  if (ways) guard = std::make_unique<CrossingGuard>(*ways), guardFrozen.assign(n, 0);
  std::vector<int> banLines, orderLines;

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
    const int axis = doVertical ? 0 : 1;
    bool found = work.cols > 1;
    while (found) {
      found = work.findSeam();
      if (!found || !guard || guard->check(work.seam, axis, banLines, orderLines)) break;
      for (const std::vector<int>* lines : {&banLines, &orderLines})
        for (int line : *lines) {
          const int c = work.seam[static_cast<size_t>(line)];
          if (std::isinf(work.E(line)[c])) continue;  // a line of both lists
          guardFrozen[static_cast<size_t>(work.X(line)[c])] = 1;
          work.ban(line, c);
          ++(lines == &banLines ? result.crossingFrozen : result.orderFrozen);
        }
      ++result.seamRetries;
    }
    if (!found) {
      (doVertical ? blockedV : blockedH) = true;
      const int line = work.frozenLine(guardFrozen);
      (doVertical ? result.verticalBlockedAt : result.horizontalBlockedAt) = line;
      if (line < 0 && guard && work.cols > 1 && work.pathExistsWithout(guardFrozen))
        (doVertical ? result.verticalBlockedByGuard : result.horizontalBlockedByGuard) = true;
      continue;
    }
    if (guard) guard->apply(axis);
    CarvedSeam seam;
    seam.vertical = doVertical;
    seam.pixels.resize(static_cast<size_t>(work.rows));
    for (int r = 0; r < work.rows; ++r) {
      const int c = work.seam[static_cast<size_t>(r)];
      const std::int32_t* idx = work.X(r);
      const int removed = idx[c];
      seam.pixels[static_cast<size_t>(r)] = removed;
      const bool ontoLower = c > 0;  // collapse onto the previous pixel of the line, else the next
      result.mergedInto[static_cast<size_t>(removed)] = idx[ontoLower ? c - 1 : c + 1];
      result.mergeSide[static_cast<size_t>(removed)] =
          doVertical ? (ontoLower ? MergeSide::OntoLeft : MergeSide::OntoRight)
                     : (ontoLower ? MergeSide::OntoAbove : MergeSide::OntoBelow);
    }
    work.removeSeam();
    result.seams.push_back(std::move(seam));
    if (doVertical)
      --leftV, ++result.verticalRemoved;
    else
      --leftH, ++result.horizontalRemoved;
    ticker.tick();
  }
  if (work.transposed) work.transpose();
  ticker.finish();
  result.cellsUpdated = work.cellsUpdated;
  result.width = work.cols;
  result.height = work.rows;
  result.finalRow.assign(n, -1);
  result.finalCol.assign(n, -1);
  for (int r = 0; r < work.rows; ++r) {
    const std::int32_t* x = work.X(r);
    for (int c = 0; c < work.cols; ++c) {
      const size_t o = static_cast<size_t>(x[c]);
      result.finalRow[o] = r;
      result.finalCol[o] = c;
    }
  }
  return result;
}

}  // namespace urbanvec::shrink
