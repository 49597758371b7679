// Plain geometry types shared by every module (no GDAL/GEOS here). Coordinates are in the unit of the
// frame they belong to: world units (metres of a projected CRS) at the I/O boundary, or cell units
// inside raster-derived algorithms.
#pragma once

#include <cmath>
#include <utility>
#include <variant>
#include <vector>

namespace urbanvec {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  Vec2() = default;
  Vec2(double x_, double y_) : x(x_), y(y_) {}
  Vec2 operator+(const Vec2& o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(const Vec2& o) const { return {x - o.x, y - o.y}; }
  Vec2 operator*(double s) const { return {x * s, y * s}; }
  Vec2 operator/(double s) const { return {x / s, y / s}; }
  Vec2& operator+=(const Vec2& o) {
    x += o.x;
    y += o.y;
    return *this;
  }
  Vec2& operator-=(const Vec2& o) {
    x -= o.x;
    y -= o.y;
    return *this;
  }
  bool operator==(const Vec2& o) const { return x == o.x && y == o.y; }
  bool operator!=(const Vec2& o) const { return !(*this == o); }
};

/// Order by x, then y: for sorting points and searching sorted ones.
inline bool lexicographicLess(const Vec2& a, const Vec2& b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}
inline double dot(const Vec2& a, const Vec2& b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(const Vec2& a, const Vec2& b) {
  return a.x * b.y - a.y * b.x;
}
// Plain sqrt, not std::hypot: coordinates are cells or metres of one city, far from overflow, and
// hypot's scaling made it the top symbol of a vectorize profile (a fifth of the CPU).
inline double length(const Vec2& a) {
  return std::sqrt(a.x * a.x + a.y * a.y);
}
inline double distance(const Vec2& a, const Vec2& b) {
  return length(a - b);
}
/// Distance from p to the segment a-b (to a when the segment has no length).
inline double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::fmax(0.0, std::fmin(1.0, dot(p - a, ab) / len2)) : 0.0;
  return distance(p, a + ab * t);
}

/// The parameters t in [0, 1] for which a + t·(b − a) lies within distance d of the segment p-q, as
/// one closed interval {lo, hi}, empty when lo > hi. The points within d of a segment form a convex
/// stadium (a rectangle 2d wide along p-q and a disc of radius d at each end), which a line meets in
/// one interval: the union of the line's intervals in the rectangle and in the two discs. An edge
/// equal to p-q (either way round) gives exactly {0, 1}. A point a = b gives {0, 1} or nothing.
std::pair<double, double> withinDistanceInterval(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q,
                                                 double d);

/// The even-odd crossing test's step: the edge a-b crosses the ray from p toward +x.
inline bool edgeCrossesRayRight(const Vec2& a, const Vec2& b, const Vec2& p) {
  return (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
}

using LineString = std::vector<Vec2>;
/// A closed ring; the first point is repeated at the end.
using Ring = std::vector<Vec2>;

/// Even-odd crossing test of a point against a closed ring (points on the ring: either answer).
bool ringContains(const Ring& ring, const Vec2& p);

struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

using MultiPolygon = std::vector<Polygon>;
using MultiLineString = std::vector<LineString>;

/// Any geometry a layer can hold; monostate means "no geometry".
using Geometry = std::variant<std::monostate, Vec2, LineString, Polygon, MultiPolygon, MultiLineString>;

/// Signed area of a ring (positive when counter-clockwise in a y-up frame).
double signedArea(const Ring& ring);
/// Area of a polygon: outer minus holes, whatever their orientation.
double area(const Polygon& polygon);
double area(const MultiPolygon& polygons);
/// Length of a line string.
double length(const LineString& line);
/// The line with points added so that no step is longer than `spacing` (a closed ring stays closed).
LineString densified(const LineString& line, double spacing);
/// The first `keep` metres of a line from its start (the whole line when it is shorter, its first
/// point alone when keep <= 0).
LineString headOfLength(const LineString& line, double keep);
/// Convex hull by Andrew's monotone chain: counter-clockwise from the lexicographically smallest
/// point, without collinear points; closed (first point repeated) when the input has 3 or more
/// distinct points (collinear ones give a, b, a), else those distinct points.
Ring convexHull(std::vector<Vec2> points);

}  // namespace urbanvec
