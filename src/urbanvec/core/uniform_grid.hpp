// A uniform grid of square buckets over a box: the one spatial hash of the library for items that
// have a position or a small extent (segments, points, design elements). Items go into every bucket
// their box overlaps; queries visit the buckets a box overlaps, or the ring of buckets at a given
// Chebyshev distance (nearest-item searches). Coordinates outside the grid's box clamp to the border
// buckets, so a query always finds an item whose box it covers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

template <class T>
class UniformGrid {
 public:
  UniformGrid() = default;
  UniformGrid(const Vec2& lo, const Vec2& hi, double cell) { init(lo, hi, cell); }

  /// Buckets of side `cell` covering lo..hi (at least one).
  void init(const Vec2& lo, const Vec2& hi, double cell) {
    origin_ = lo, cell_ = cell;
    nx_ = std::max(1, static_cast<int>((hi.x - lo.x) / cell) + 1);
    ny_ = std::max(1, static_cast<int>((hi.y - lo.y) / cell) + 1);
    buckets_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  }
  bool empty() const { return buckets_.empty(); }
  int columns() const { return nx_; }
  int rows() const { return ny_; }
  double cell() const { return cell_; }
  /// The bucket column / row holding x / y, clamped to the grid.
  int column(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - origin_.x) / cell_)), 0, nx_ - 1);
  }
  int row(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - origin_.y) / cell_)), 0, ny_ - 1);
  }

  /// Adds the item to every bucket the box spanned by a and b overlaps.
  void insert(const Vec2& a, const Vec2& b, const T& item) {
    forCells(a, b, [&](std::size_t k) { buckets_[k].push_back(item); });
  }
  void insert(const Vec2& p, const T& item) { buckets_[index(column(p.x), row(p.y))].push_back(item); }

  /// Calls fn(bucket) for each bucket the box spanned by a and b overlaps.
  template <class Fn>
  void forBox(const Vec2& a, const Vec2& b, Fn fn) const {
    if (buckets_.empty()) return;
    const_cast<UniformGrid*>(this)->forCells(a, b, [&](std::size_t k) { fn(std::as_const(buckets_[k])); });
  }

  /// Calls fn(bucket) for each bucket at Chebyshev distance `ring` from bucket (ci, cj); returns false
  /// when the ring lies wholly outside the grid (no later ring holds anything either).
  template <class Fn>
  bool forRing(int ci, int cj, int ring, Fn fn) const {
    if (ci - ring < 0 && cj - ring < 0 && ci + ring >= nx_ && cj + ring >= ny_) return false;
    for (int j = cj - ring; j <= cj + ring; ++j) {
      if (j < 0 || j >= ny_) continue;
      const bool edgeRow = j == cj - ring || j == cj + ring;
      for (int i = ci - ring; i <= ci + ring; i += edgeRow || ring == 0 ? 1 : 2 * ring)
        if (i >= 0 && i < nx_) fn(buckets_[index(i, j)]);
    }
    return true;
  }

 private:
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx_ + i; }
  template <class Fn>
  void forCells(const Vec2& a, const Vec2& b, Fn fn) {
    const int i0 = column(std::min(a.x, b.x)), i1 = column(std::max(a.x, b.x));
    const int j0 = row(std::min(a.y, b.y)), j1 = row(std::max(a.y, b.y));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) fn(index(i, j));
  }

  Vec2 origin_;
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<T>> buckets_;
};

}  // namespace urbanvec
