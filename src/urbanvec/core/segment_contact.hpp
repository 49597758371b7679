// How two closed line segments meet: the one predicate behind every "does this move create a
// crossing" check (roads B-stage checks and B7, the shrink's crossing-safe simplification and its
// measures, evaluate's crossing count). Exact sign tests on the floating orientations; no tolerance.
#pragma once

#include <algorithm>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

enum class SegmentContact {
  None,      ///< disjoint
  Crossing,  ///< the interiors cross at one point (each segment has the other's ends strictly on both sides)
  Touching,  ///< any other shared point: an end on the other segment, or a collinear overlap
};

/// Twice the signed area of abc: > 0 when c lies left of a->b.
inline double orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross(b - a, c - a);
}

/// True when p lies in the bounding box of ab: for a p collinear with ab, that p is on the segment.
inline bool inSegmentBox(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

/// Contact of the closed segments p1p2 and q1q2.
inline SegmentContact segmentContact(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = orientation(q1, q2, p1), d2 = orientation(q1, q2, p2), d3 = orientation(p1, p2, q1),
               d4 = orientation(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return SegmentContact::Crossing;
  if ((d1 == 0 && inSegmentBox(q1, q2, p1)) || (d2 == 0 && inSegmentBox(q1, q2, p2)) ||
      (d3 == 0 && inSegmentBox(p1, p2, q1)) || (d4 == 0 && inSegmentBox(p1, p2, q2)))
    return SegmentContact::Touching;
  return SegmentContact::None;
}

/// True when the interiors of p1p2 and q1q2 cross properly (touching and overlaps do not count).
inline bool segmentsCross(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  return segmentContact(p1, p2, q1, q2) == SegmentContact::Crossing;
}

}  // namespace urbanvec
