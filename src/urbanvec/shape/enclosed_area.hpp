// The enclosed-area ratio: how much of the circle spanned by a shape's largest diameter it fills
// (spec wijgerse-boundary.md §7, thesis Eqs. 2.17-2.20).
#pragma once

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shape {

struct EnclosedArea {
  double area = 0.0;      ///< area enclosed by the ring, in squared ring units
  double diameter = 0.0;  ///< largest distance between two vertices, in ring units
  double ratio = 0.0;     ///< area / (pi diameter^2 / 4); 1 for a circle, 0.0635 for 200 m x 4 km
};

/// Measures a closed ring (closing point repeated or not). The thesis only bounded this ratio through
/// the fill ratio; here it is computed per shape (spec §7.3 [INF]).
EnclosedArea enclosedArea(const Ring& ring);

/// Largest distance between two points: rotating calipers on their convex hull.
double diameter(const std::vector<Vec2>& points);

}  // namespace urbanvec::shape
