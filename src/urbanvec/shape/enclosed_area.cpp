// Enclosed-area ratio, spec wijgerse-boundary.md §7 (thesis §2.2.2, §4.2.4).
#include "urbanvec/shape/enclosed_area.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace urbanvec::shape {

namespace {

double turn(const Vec2& o, const Vec2& a, const Vec2& b) {
  return cross(a - o, b - o);
}

}  // namespace

double diameter(const std::vector<Vec2>& points) {
  Ring hull = convexHull(points);
  if (hull.size() > 2) hull.pop_back();  // the open ring: the antipodal walk wraps by index
  const size_t h = hull.size();
  if (h < 2) return 0.0;
  if (h == 2) return distance(hull[0], hull[1]);
  double best = 0.0;
  size_t j = 1;
  for (size_t i = 0; i < h; ++i) {
    const Vec2& a = hull[i];
    const Vec2& b = hull[(i + 1) % h];
    // Advance the antipodal vertex while it gets farther from edge (a, b).
    while (std::abs(turn(a, b, hull[(j + 1) % h])) > std::abs(turn(a, b, hull[j]))) j = (j + 1) % h;
    best = std::max({best, distance(a, hull[j]), distance(b, hull[j])});
  }
  return best;
}

EnclosedArea enclosedArea(const Ring& ring) {
  EnclosedArea result;
  if (ring.size() < 3) return result;
  Ring closed = ring;
  if (closed.front() != closed.back()) closed.push_back(closed.front());
  result.area = std::abs(signedArea(closed));
  result.diameter = diameter(ring);
  const double circle = M_PI * result.diameter * result.diameter / 4.0;
  result.ratio = circle > 0.0 ? result.area / circle : 0.0;
  return result;
}

}  // namespace urbanvec::shape
