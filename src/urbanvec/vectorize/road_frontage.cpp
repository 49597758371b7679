#include "urbanvec/vectorize/road_frontage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "urbanvec/core/parallel.hpp"

namespace urbanvec::vectorize {

namespace {

/// A closed axis-aligned box.
struct Box {
  Vec2 lo, hi;
  static Box of(const Vec2& a, const Vec2& b) {
    return {{std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)}};
  }
  Box grown(double d) const { return {{lo.x - d, lo.y - d}, {hi.x + d, hi.y + d}}; }
  bool meets(const Box& o) const {
    return o.lo.x <= hi.x && lo.x <= o.hi.x && o.lo.y <= hi.y && lo.y <= o.hi.y;
  }
};

/// Items 0 .. n − 1 with boxes (`boxOf(i)`; an empty box, lo > hi, leaves the item out) bucketed on a
/// uniform grid, stored compactly, one offset per bucket and one index per entry, without the boxes
/// (queries are given a function for them): the pavement has millions of edges at 4096², too many for
/// core's UniformGrid, which keeps a vector (24 bytes and an allocation) per bucket.
class BoxGrid {
 public:
  BoxGrid() = default;
  template <class BoxOf>
  BoxGrid(std::uint32_t n, const BoxOf& boxOf) {
    Box extent{{HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
    double side = 0.0, count = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const Box b = boxOf(i);
      if (b.lo.x > b.hi.x) continue;
      extent = {{std::min(extent.lo.x, b.lo.x), std::min(extent.lo.y, b.lo.y)},
                {std::max(extent.hi.x, b.hi.x), std::max(extent.hi.y, b.hi.y)}};
      side += std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y);
      count += 1.0;
    }
    if (count == 0.0) return;
    const double w = extent.hi.x - extent.lo.x, h = extent.hi.y - extent.lo.y;
    // Buckets about as wide as a box, or with about one box each when the boxes are points; never
    // many more buckets than boxes.
    cell_ = std::max({side / count, std::sqrt(w * h / count), 1e-9});
    while ((w / cell_ + 1.0) * (h / cell_ + 1.0) > 4.0 * count + 16.0) cell_ *= 1.5;
    origin_ = extent.lo;
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    start_.assign(static_cast<size_t>(nx_) * static_cast<size_t>(ny_) + 1, 0);
    for (std::uint32_t i = 0; i < n; ++i) forBuckets(boxOf(i), [&](size_t k) { ++start_[k + 1]; });
    for (size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    items_.resize(start_.back());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i) forBuckets(boxOf(i), [&](size_t k) { items_[fill[k]++] = i; });
  }

  /// Calls fn(item) once for each item whose box (boxOf(item), as when built) meets q: in the bucket
  /// holding the low corner of their common part, so an item that spans several buckets is not
  /// reported twice.
  template <class BoxOf, class Fn>
  void forEach(const Box& q, const BoxOf& boxOf, Fn fn) const {
    if (start_.empty()) return;
    const int i0 = column(q.lo.x), i1 = column(q.hi.x), j0 = row(q.lo.y), j1 = row(q.hi.y);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t k = static_cast<size_t>(j) * nx_ + i;
        for (std::uint32_t e = start_[k]; e < start_[k + 1]; ++e) {
          const Box b = boxOf(items_[e]);
          if (b.meets(q) && column(std::max(b.lo.x, q.lo.x)) == i && row(std::max(b.lo.y, q.lo.y)) == j)
            fn(items_[e]);
        }
      }
  }

 private:
  int column(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - origin_.x) / cell_)), 0, nx_ - 1);
  }
  int row(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - origin_.y) / cell_)), 0, ny_ - 1);
  }
  template <class Fn>
  void forBuckets(const Box& b, Fn fn) const {
    if (b.lo.x > b.hi.x) return;
    for (int j = row(b.lo.y), j1 = row(b.hi.y); j <= j1; ++j)
      for (int i = column(b.lo.x), i1 = column(b.hi.x); i <= i1; ++i) fn(static_cast<size_t>(j) * nx_ + i);
  }

  Vec2 origin_;
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, items_;
};

using Interval = std::pair<double, double>;

/// The pavement, its rings one after the other in one array, with a bucket grid over its edges (an
/// edge is named by the index of its first point) and one over its pieces.
class Pavement {
 public:
  /// Takes the pieces apart as it copies them, so they are not held twice.
  Pavement(std::vector<Polygon>& pieces, double tolerance) : tolerance_(tolerance) {
    pieceRings_.push_back(0);
    ringStarts_.push_back(0);
    pieceBoxes_.reserve(pieces.size());
    size_t points = 0;
    for (const Polygon& piece : pieces) {
      points += piece.outer.size();
      for (const Ring& hole : piece.holes) points += hole.size();
    }
    points_.reserve(points);
    for (Polygon& piece : pieces) {
      Box box{{HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
      for (const Vec2& p : piece.outer)
        box = {{std::min(box.lo.x, p.x), std::min(box.lo.y, p.y)},
               {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y)}};
      pieceBoxes_.push_back(box);
      addRing(piece.outer);
      for (const Ring& hole : piece.holes) addRing(hole);
      pieceRings_.push_back(static_cast<std::uint32_t>(ringStarts_.size() - 1));
      Polygon().outer.swap(piece.outer);
      std::vector<Ring>().swap(piece.holes);
    }
    std::vector<Polygon>().swap(pieces);
    // Point i starts an edge unless it closes its ring.
    edgeGrid_ = BoxGrid(static_cast<std::uint32_t>(points_.size()), [&](std::uint32_t i) {
      if (i + 1 == *std::upper_bound(ringStarts_.begin(), ringStarts_.end(), i))
        return Box{{1.0, 1.0}, {0.0, 0.0}};
      return Box::of(points_[i], points_[i + 1]);
    });
    pieceGrid_ = BoxGrid(static_cast<std::uint32_t>(pieceBoxes_.size()),
                         [&](std::uint32_t k) { return pieceBoxes_[k]; });
  }

  /// The covered parts of the edge a-b (a ≠ b) as parameter intervals along it, increasing and
  /// disjoint, into `cover`; `scratch` is the caller's.
  void coverEdge(const Vec2& a, const Vec2& b, std::vector<Interval>& cover,
                 std::vector<Interval>& scratch) const {
    cover.clear();
    scratch.clear();
    bool whole = false;
    auto edgeBox = [&](std::uint32_t k) { return Box::of(points_[k], points_[k + 1]); };
    edgeGrid_.forEach(Box::of(a, b).grown(tolerance_), edgeBox, [&](std::uint32_t k) {
      if (whole) return;
      const Vec2 &p = points_[k], &q = points_[k + 1];
      if ((p == a && q == b) || (p == b && q == a)) {
        whole = true;
        return;
      }
      const Interval t = withinDistanceInterval(a, b, p, q, tolerance_);
      if (t.first <= t.second) scratch.push_back(t);
    });
    if (whole) {
      cover.emplace_back(0.0, 1.0);
      return;
    }
    std::sort(scratch.begin(), scratch.end());
    // Each stretch between the intervals lies farther than the tolerance from every pavement edge, so
    // it is inside one piece or outside all of them all along: its middle decides.
    double reached = 0.0;  // the end of the covered part so far (0 before the first interval)
    bool open = false;     // whether cover.back() ends at `reached`
    auto extend = [&](double lo, double hi) {
      if (open && lo <= reached)
        cover.back().second = std::max(cover.back().second, hi);
      else
        cover.emplace_back(lo, hi);
      open = true;
      reached = cover.back().second;
    };
    for (const Interval& t : scratch) {
      if (t.first > reached && insidePiece(a + (b - a) * (0.5 * (reached + t.first))))
        extend(reached, t.first);
      extend(t.first, t.second);
    }
    if (reached < 1.0 && insidePiece(a + (b - a) * (0.5 * (reached + 1.0)))) extend(reached, 1.0);
  }

 private:
  void addRing(const Ring& ring) {
    points_.insert(points_.end(), ring.begin(), ring.end());
    ringStarts_.push_back(static_cast<std::uint32_t>(points_.size()));
  }
  /// Even-odd test over the rings [first, last) of ringStarts_.
  bool ringsContain(std::uint32_t first, std::uint32_t last, const Vec2& p) const {
    bool inside = false;
    for (std::uint32_t r = first; r < last; ++r)
      for (std::uint32_t i = ringStarts_[r]; i + 1 < ringStarts_[r + 1]; ++i)
        if (edgeCrossesRayRight(points_[i], points_[i + 1], p)) inside = !inside;
    return inside;
  }
  bool insidePiece(const Vec2& p) const {
    bool inside = false;
    auto pieceBox = [&](std::uint32_t k) { return pieceBoxes_[k]; };
    pieceGrid_.forEach(Box{p, p}, pieceBox, [&](std::uint32_t k) {
      inside = inside || ringsContain(pieceRings_[k], pieceRings_[k + 1], p);
    });
    return inside;
  }

  double tolerance_;
  std::vector<Vec2> points_;               // every ring of every piece, closed, one after the other
  std::vector<std::uint32_t> ringStarts_;  // ring r is points_[ringStarts_[r], ringStarts_[r + 1])
  std::vector<std::uint32_t> pieceRings_;  // piece k has rings [pieceRings_[k], pieceRings_[k + 1])
  std::vector<Box> pieceBoxes_;            // of the outer rings
  BoxGrid edgeGrid_, pieceGrid_;
};

/// Appends the covered parts of one ring to `out`, merged into lines along the ring.
void ringFrontage(const Ring& ring, const Pavement& pavement, MultiLineString& out,
                  std::vector<Interval>& cover, std::vector<Interval>& scratch) {
  const size_t first = out.size();
  bool chained = false;    // out.back() ends at the start of the current edge
  bool fromStart = false;  // out[first] starts at the ring's first point
  bool firstEdge = true;
  for (size_t i = 0; i + 1 < ring.size(); ++i) {
    const Vec2 &a = ring[i], &b = ring[i + 1];
    if (a == b) continue;
    pavement.coverEdge(a, b, cover, scratch);
    bool toEnd = false;
    for (const auto& [lo, hi] : cover) {
      const Vec2 s = lo <= 0.0 ? a : a + (b - a) * lo, e = hi >= 1.0 ? b : a + (b - a) * hi;
      if (chained && lo <= 0.0) {
        if (e != out.back().back()) out.back().push_back(e);
      } else if (s != e) {
        if (firstEdge && lo <= 0.0) fromStart = true;
        out.push_back({s, e});
      }
      toEnd = hi >= 1.0 && s != e;
      chained = toEnd;
    }
    chained = toEnd;
    firstEdge = false;
  }
  // A line that reaches the ring's end continues the one that starts at its start (LineMerge's rule at
  // a point of degree two); a ring covered all round is one closed line.
  if (chained && fromStart && out.size() > first + 1 && ring.front() == ring.back()) {
    LineString& head = out[first];
    LineString joined = std::move(out.back());
    joined.insert(joined.end(), head.begin() + 1, head.end());
    head = std::move(joined);
    out.pop_back();
  }
}

}  // namespace

std::vector<MultiLineString> roadFacingEdges(std::vector<Polygon> pavement,
                                             const std::vector<const Polygon*>& blocks, double tolerance,
                                             int threads) {
  const Pavement index(pavement, tolerance);
  std::vector<MultiLineString> out(blocks.size());
  const size_t workers = workerCount(threads);
  std::vector<std::vector<Interval>> covers(workers), scratches(workers);
  runParallel(workers, blocks.size(), [&](size_t i, size_t w) {
    const Polygon& block = *blocks[i];
    ringFrontage(block.outer, index, out[i], covers[w], scratches[w]);
    for (const Ring& hole : block.holes) ringFrontage(hole, index, out[i], covers[w], scratches[w]);
  });
  return out;
}

}  // namespace urbanvec::vectorize
