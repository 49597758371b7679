#include "urbanvec/vectorize/roads/curve_drawing.hpp"

#include <cmath>

#include "urbanvec/vectorize/roads/road_checks.hpp"

namespace urbanvec::vectorize {

namespace {

/// Point at parameter u in [0, 1] of the centripetal Catmull-Rom piece from p1 to p2 (Barry and
/// Goldman's pyramid, knot spacing the square root of the chord length).
Vec2 catmullRom(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double u) {
  auto knot = [](double t, const Vec2& a, const Vec2& b) { return t + std::sqrt(distance(a, b)); };
  const double t0 = 0.0, t1 = knot(t0, p0, p1), t2 = knot(t1, p1, p2), t3 = knot(t2, p2, p3);
  const double t = t1 + (t2 - t1) * u;
  auto lerp = [](const Vec2& a, const Vec2& b, double ta, double tb, double t) {
    return a * ((tb - t) / (tb - ta)) + b * ((t - ta) / (tb - ta));
  };
  const Vec2 a1 = lerp(p0, p1, t0, t1, t), a2 = lerp(p1, p2, t1, t2, t), a3 = lerp(p2, p3, t2, t3, t);
  const Vec2 b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
  return lerp(b1, b2, t1, t2, t);
}

/// Signed turn at b of the path a -> b -> c (positive left), 0 where a piece has no length.
double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross(b - a, c - b);
}

/// Appends the spline points strictly inside the piece between parameters u0 (at a) and u1 (at b).
void flatten(const Vec2 (&p)[4], double u0, const Vec2& a, double u1, const Vec2& b, int depth,
             const CurveDrawingOptions& options, LineString& out) {
  const double um = 0.5 * (u0 + u1);
  const Vec2 m = catmullRom(p[0], p[1], p[2], p[3], um);
  if (depth >= options.maxDepth || distanceToSegment(m, a, b) <= options.tolerance) return;
  flatten(p, u0, a, um, m, depth + 1, options, out);
  out.push_back(m);
  flatten(p, um, m, u1, b, depth + 1, options, out);
}

}  // namespace

LineString drawCurve(const LineString& line, const CurveDrawingOptions& options) {
  if (!(options.tolerance > 0.0) || line.size() < 4) return line;
  LineString out{line.front()};
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    // The piece line[i] -> line[i + 1] is curved when both its ends turn, and the same way.
    if (i >= 1 && i + 2 < line.size()) {
      const double before = turn(line[i - 1], line[i], line[i + 1]);
      const double after = turn(line[i], line[i + 1], line[i + 2]);
      const bool apart =
          !(line[i - 1] == line[i]) && !(line[i] == line[i + 1]) && !(line[i + 1] == line[i + 2]);
      if (apart && before * after > 0.0) {
        const Vec2 p[4] = {line[i - 1], line[i], line[i + 1], line[i + 2]};
        flatten(p, 0.0, line[i], 1.0, line[i + 1], 0, options, out);
      }
    }
    out.push_back(line[i + 1]);
  }
  return out;
}

CurveDrawingStats drawCurves(RoadNetwork& network, const Grid<std::uint8_t>& landUse,
                             const Grid<std::uint8_t>& cleaned, const CurveDrawingOptions& options,
                             double coverDistance) {
  CurveDrawingStats stats;
  if (!(options.tolerance > 0.0)) return stats;
  const RoadNetwork polylines = network;
  for (NetworkSegment& s : network.segments) {
    if (s.roadClass == RoadClass::Perimeter) continue;
    LineString drawn = drawCurve(s.points, options);
    if (drawn.size() == s.points.size()) continue;
    stats.points += drawn.size() - s.points.size();
    ++stats.segments;
    s.points = std::move(drawn);
  }
  if (stats.segments == 0) return stats;
  // A tolerance of 0 gives an uncovering segment its polyline back as it is.
  stats.restored += restoreUncoveringSegments(network, polylines, landUse, cleaned, 0.0, coverDistance);
  stats.restored += restoreTouchingSegments(network, polylines);
  return stats;
}

}  // namespace urbanvec::vectorize
