// Topology-preserving polygon simplification (issue 21); see the header for the rules.
#include "urbanvec/core/topology_simplify.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace urbanvec {

namespace {

/// Sign of the orientation of abc (+1 left turn, -1 right turn, 0 collinear). Double precision with
/// Shewchuk's error bound; within it, 0 when two of the points are equal, else the determinant again
/// in 113-bit precision, where the
/// differences and products of the coordinates are exact.
int orientationSign(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x - a.x) * (c.y - a.y), right = (b.y - a.y) * (c.x - a.x);
  const double det = left - right;
  const double bound = 3.3306690738754716e-16 * (std::fabs(left) + std::fabs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  // Two equal points make the determinant exactly 0. Segments that share an end (every pair of
  // neighbours along a ring) land here in every test, and the 113-bit path below is software
  // arithmetic: 4 % of a city run before this shortcut (issue 21).
  if (c == a || c == b || a == b) return 0;
  using Wide = __float128;
  const Wide exact =
      (Wide(b.x) - Wide(a.x)) * (Wide(c.y) - Wide(a.y)) - (Wide(b.y) - Wide(a.y)) * (Wide(c.x) - Wide(a.x));
  return exact > 0 ? 1 : exact < 0 ? -1 : 0;
}

struct Box {
  double minX, minY, maxX, maxY;
  Box(const Vec2& a, const Vec2& b)
      : minX(std::min(a.x, b.x)),
        minY(std::min(a.y, b.y)),
        maxX(std::max(a.x, b.x)),
        maxY(std::max(a.y, b.y)) {}
  Box(double x0, double y0, double x1, double y1) : minX(x0), minY(y0), maxX(x1), maxY(y1) {}
  bool meets(const Box& o) const {
    return minX <= o.maxX && o.minX <= maxX && minY <= o.maxY && o.minY <= maxY;
  }
  bool holds(const Vec2& p) const { return minX <= p.x && p.x <= maxX && minY <= p.y && p.y <= maxY; }
};

/// Distance from p to the segment ab, in the order of operations GEOS uses (so the tolerance test
/// decides alike on the boundary).
double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  if (a.x == b.x && a.y == b.y) return std::sqrt((p.x - a.x) * (p.x - a.x) + (p.y - a.y) * (p.y - a.y));
  const double len2 = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
  const double r = ((p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y)) / len2;
  if (r <= 0.0) return std::sqrt((p.x - a.x) * (p.x - a.x) + (p.y - a.y) * (p.y - a.y));
  if (r >= 1.0) return std::sqrt((p.x - b.x) * (p.x - b.x) + (p.y - b.y) * (p.y - b.y));
  const double s = ((a.y - p.y) * (b.x - a.x) - (a.x - p.x) * (b.y - a.y)) / len2;
  return std::fabs(s) * std::sqrt(len2);
}

struct Segment {
  Vec2 a, b;
  Box box;
  std::uint32_t ring;
  std::uint32_t index;  ///< segment index within its ring
  bool alive;           ///< still in the input (not under a chord kept so far)
};

/// The work lists of a Simplifier, kept between calls so their memory is reused.
struct SimplifierLists {
  static constexpr std::uint32_t kRun = 8;
  struct Run {
    Box box;
    std::uint32_t begin, end;  ///< input[begin, end)
  };
  std::vector<Run> runs;
  std::vector<Segment> input, output;
  std::vector<std::uint32_t> ringStart;
};

class Simplifier {
 public:
  Simplifier(const std::vector<const Ring*>& rings, double tolerance, SimplifierLists& lists)
      : runs_(lists.runs),
        rings_(rings),
        tolerance_(tolerance),
        input_(lists.input),
        output_(lists.output),
        ringStart_(lists.ringStart) {
    runs_.clear();
    input_.clear();
    output_.clear();
    ringStart_.clear();
    size_t segments = 0;
    for (const Ring* ring : rings) segments += ring->empty() ? 0 : ring->size() - 1;
    input_.reserve(segments);
    runs_.reserve(segments / kRun + rings.size());
    for (std::uint32_t r = 0; r < rings.size(); ++r) {
      const Ring& ring = *rings[r];
      ringStart_.push_back(static_cast<std::uint32_t>(input_.size()));
      for (std::uint32_t i = 0; i + 1 < ring.size(); ++i) {
        const Box box(ring[i], ring[i + 1]);
        // Runs of up to kRun consecutive segments of one ring share a bounding box, so the test of a
        // chord against the input skips whole runs far from it (issue 21).
        if (i % kRun == 0) runs_.push_back({box, static_cast<std::uint32_t>(input_.size()), 0});
        Box& runBox = runs_.back().box;
        runBox = Box(std::min(runBox.minX, box.minX), std::min(runBox.minY, box.minY),
                     std::max(runBox.maxX, box.maxX), std::max(runBox.maxY, box.maxY));
        input_.push_back({ring[i], ring[i + 1], box, r, i, true});
        runs_.back().end = static_cast<std::uint32_t>(input_.size());
      }
    }
  }

  /// Ring r simplified, into `result` (cleared first).
  void simplifyRing(std::uint32_t r, Ring& result) {
    ring_ = r;
    const Ring& points = *rings_[r];
    result_ = &result;
    result.clear();
    resultSegments_ = 0;
    if (points.empty()) return;
    section(0, points.size() - 1, 0);
    result.push_back(points.back());
  }

 private:
  static constexpr size_t kMinimumRingSize = 4;

  size_t resultSize() const { return resultSegments_ == 0 ? 0 : resultSegments_ + 1; }

  void section(size_t i, size_t j, size_t depth) {
    const Ring& points = *rings_[ring_];
    ++depth;
    if (i + 1 == j) {  // a single input segment stays (and stays in the input)
      keep(points[i]);
      return;
    }
    bool valid = true;
    if (resultSize() < kMinimumRingSize && depth + 1 < kMinimumRingSize) valid = false;
    double farthest = -1.0;
    size_t farthestIndex = i;
    const Vec2 a = points[i], b = points[j];
    if (a.x == b.x && a.y == b.y) {
      for (size_t k = i + 1; k < j; ++k) {
        const double d = pointSegmentDistance(points[k], a, b);
        if (d > farthest) {
          farthest = d;
          farthestIndex = k;
        }
      }
    } else {
      // pointSegmentDistance with the chord's terms and the square root of its length taken once
      // (the same operations on the same values, so the same distances).
      const double dx = b.x - a.x, dy = b.y - a.y;
      const double len2 = dx * dx + dy * dy, chord = std::sqrt(len2);
      for (size_t k = i + 1; k < j; ++k) {
        const Vec2& p = points[k];
        const double r = ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2;
        double d;
        if (r <= 0.0)
          d = std::sqrt((p.x - a.x) * (p.x - a.x) + (p.y - a.y) * (p.y - a.y));
        else if (r >= 1.0)
          d = std::sqrt((p.x - b.x) * (p.x - b.x) + (p.y - b.y) * (p.y - b.y));
        else
          d = std::fabs(((a.y - p.y) * dx - (a.x - p.x) * dy) / len2) * chord;
        if (d > farthest) {
          farthest = d;
          farthestIndex = k;
        }
      }
    }
    if (farthest > tolerance_) valid = false;
    if (valid && badIntersection(points[i], points[j], i, j)) valid = false;
    if (valid) {
      const std::uint32_t start = ringStart_[ring_];
      for (size_t k = i; k < j; ++k) input_[start + k].alive = false;
      output_.push_back({points[i], points[j], Box(points[i], points[j]), ring_, 0, true});
      keep(points[i]);
      return;
    }
    section(i, farthestIndex, depth);
    section(farthestIndex, j, depth);
  }

  void keep(const Vec2& p) {
    result_->push_back(p);
    ++resultSegments_;
  }

  bool badIntersection(const Vec2& a, const Vec2& b, size_t i, size_t j) const {
    const Box box(a, b);
    for (const Segment& s : output_)
      if (s.box.meets(box) && segmentsMeetInside(s.a, s.b, a, b)) return true;
    for (const Run& run : runs_) {
      if (!run.box.meets(box)) continue;  // no segment of the run meets the chord's box
      for (std::uint32_t k = run.begin; k < run.end; ++k) {
        const Segment& s = input_[k];
        if (!s.alive || !s.box.meets(box)) continue;
        if (s.ring == ring_ && s.index >= i && s.index < j) continue;  // part of the section itself
        if (segmentsMeetInside(s.a, s.b, a, b)) return true;
      }
    }
    return false;
  }

  static constexpr std::uint32_t kRun = SimplifierLists::kRun;
  using Run = SimplifierLists::Run;
  std::vector<Run>& runs_;

  const std::vector<const Ring*>& rings_;
  double tolerance_;
  std::vector<Segment>&input_, &output_;
  std::vector<std::uint32_t>& ringStart_;
  std::uint32_t ring_ = 0;
  Ring* result_ = nullptr;
  size_t resultSegments_ = 0;
};

}  // namespace

bool segmentsMeetInside(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  const Box pb(p0, p1), qb(q0, q1);
  if (!pb.meets(qb)) return false;
  const int pq0 = orientationSign(p0, p1, q0), pq1 = orientationSign(p0, p1, q1);
  if (pq0 * pq1 > 0) return false;
  const int qp0 = orientationSign(q0, q1, p0), qp1 = orientationSign(q0, q1, p1);
  if (qp0 * qp1 > 0) return false;
  auto endOfP = [&](const Vec2& v) { return v == p0 || v == p1; };
  auto endOfQ = [&](const Vec2& v) { return v == q0 || v == q1; };
  if (pq0 == 0 && pq1 == 0 && qp0 == 0 && qp1 == 0) {
    // Collinear: the shared points are those ends that lie on the other segment; the contact is
    // inside unless each of them is an end of both segments.
    for (const Vec2& v : {p0, p1})
      if (qb.holds(v) && !endOfQ(v)) return true;
    for (const Vec2& v : {q0, q1})
      if (pb.holds(v) && !endOfP(v)) return true;
    return false;
  }
  // One contact point: inside unless it is a common end.
  return !(endOfQ(p0) || endOfQ(p1));
}

Polygon simplifyPreservingTopology(const Polygon& polygon, double tolerance) {
  Polygon out;
  simplifyPreservingTopology(polygon, tolerance, out);
  return out;
}

void simplifyPreservingTopology(const Polygon& polygon, double tolerance, Polygon& out) {
  // Rings are simplified as closed rings: an open one is closed in a copy, a closed one used as it is.
  thread_local std::vector<Ring> closed;
  thread_local std::vector<const Ring*> rings;
  thread_local SimplifierLists lists;
  closed.resize(1 + polygon.holes.size());
  rings.clear();
  auto add = [&](const Ring& r, Ring& copy) {
    if (r.empty() || r.front() == r.back()) {
      rings.push_back(&r);
      return;
    }
    copy.assign(r.begin(), r.end());
    copy.push_back(r.front());
    rings.push_back(&copy);
  };
  add(polygon.outer, closed[0]);
  for (size_t h = 0; h < polygon.holes.size(); ++h) add(polygon.holes[h], closed[h + 1]);
  Simplifier simplifier(rings, tolerance, lists);
  out.holes.resize(polygon.holes.size());
  for (std::uint32_t r = 0; r < rings.size(); ++r) {
    Ring& s = r == 0 ? out.outer : out.holes[r - 1];
    if (rings[r]->size() < 4)
      s.assign(rings[r]->begin(), rings[r]->end());
    else
      simplifier.simplifyRing(r, s);
  }
}

}  // namespace urbanvec
