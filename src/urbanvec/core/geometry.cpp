#include "urbanvec/core/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace urbanvec {

bool ringContains(const Ring& ring, const Vec2& p) {
  bool inside = false;
  for (size_t i = 0, n = ring.size(); i + 1 < n; ++i)
    if (edgeCrossesRayRight(ring[i], ring[i + 1], p)) inside = !inside;
  return inside;
}

namespace {

/// Narrows [lo, hi] to the t with lower <= alpha + beta·t <= upper.
void narrowLinear(double alpha, double beta, double lower, double upper, double& lo, double& hi) {
  if (beta == 0.0) {
    if (alpha < lower || alpha > upper) lo = 1.0, hi = 0.0;
    return;
  }
  double t0 = (lower - alpha) / beta, t1 = (upper - alpha) / beta;
  if (beta < 0.0) std::swap(t0, t1);
  lo = std::max(lo, t0);
  hi = std::min(hi, t1);
}

/// Widens [lo, hi] by the t with |w + t·v| <= d (w = a − centre: the line a + t·v in a disc), v ≠ 0.
/// The discriminant (v·w)² − |v|²(|w|² − d²) is written |v|²d² − (v×w)², without the cancellation.
void widenByDisc(const Vec2& w, const Vec2& v, double d, double& lo, double& hi) {
  const double vv = dot(v, v), c = cross(v, w);
  const double discriminant = vv * d * d - c * c;
  if (discriminant < 0.0) return;
  const double mid = -dot(v, w) / vv, half = std::sqrt(discriminant) / vv;
  lo = std::min(lo, mid - half);
  hi = std::max(hi, mid + half);
}

}  // namespace

std::pair<double, double> withinDistanceInterval(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q,
                                                 double d) {
  const Vec2 v = b - a;
  if (dot(v, v) == 0.0) return distanceToSegment(a, p, q) <= d ? std::pair(0.0, 1.0) : std::pair(1.0, 0.0);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  widenByDisc(a - p, v, d, lo, hi);
  const Vec2 u = q - p;
  const double uu = dot(u, u);
  if (uu > 0.0) {
    widenByDisc(a - q, v, d, lo, hi);
    // The rectangle: the projection on p-q within [0, |u|²] (scaled by |u|), the offset within ±d|u|.
    const Vec2 w = a - p;
    double rectLo = -HUGE_VAL, rectHi = HUGE_VAL;
    narrowLinear(dot(w, u), dot(v, u), 0.0, uu, rectLo, rectHi);
    const double reach = d * std::sqrt(uu);
    narrowLinear(cross(u, w), cross(u, v), -reach, reach, rectLo, rectHi);
    if (rectLo <= rectHi) {
      lo = std::min(lo, rectLo);
      hi = std::max(hi, rectHi);
    }
  }
  return {lo > 0.0 ? lo : 0.0, hi < 1.0 ? hi : 1.0};  // never -0.0
}

double signedArea(const Ring& ring) {
  double twice = 0.0;
  for (size_t i = 0; i + 1 < ring.size(); ++i) twice += cross(ring[i], ring[i + 1]);
  if (!ring.empty() && ring.front() != ring.back()) twice += cross(ring.back(), ring.front());
  return 0.5 * twice;
}

double area(const Polygon& polygon) {
  double a = std::fabs(signedArea(polygon.outer));
  for (const Ring& hole : polygon.holes) a -= std::fabs(signedArea(hole));
  return a;
}

double area(const MultiPolygon& polygons) {
  double a = 0.0;
  for (const Polygon& p : polygons) a += area(p);
  return a;
}

double length(const LineString& line) {
  double l = 0.0;
  for (size_t i = 0; i + 1 < line.size(); ++i) l += distance(line[i], line[i + 1]);
  return l;
}

LineString headOfLength(const LineString& line, double keep) {
  LineString out{line.front()};
  if (!(keep > 0.0)) return out;
  double at = 0.0;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double len = distance(line[i], line[i + 1]);
    if (at + len >= keep) {
      out.push_back(line[i] + (line[i + 1] - line[i]) * ((keep - at) / std::max(len, 1e-300)));
      return out;
    }
    out.push_back(line[i + 1]);
    at += len;
  }
  return out;
}

LineString densified(const LineString& line, double spacing) {
  if (line.size() < 2) return line;
  LineString dense;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const int steps =
        std::max(1, static_cast<int>(std::ceil(distance(line[i], line[i + 1]) / spacing - 1e-9)));
    for (int k = 0; k < steps; ++k) dense.push_back(line[i] + (line[i + 1] - line[i]) * (double(k) / steps));
  }
  dense.push_back(line.back());
  return dense;
}

Ring convexHull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) { return cross(a - o, b - o); };
  Ring hull(2 * points.size());
  size_t k = 0;
  for (const Vec2& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k);  // the upper chain ends on the first point: the ring is closed
  return hull;
}

}  // namespace urbanvec
