// Sea side of the coastline (issue 2 §2).
#include "urbanvec/gridify/water.hpp"

#include <cmath>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/vector_ops.hpp"

namespace urbanvec::gridify {

MultiPolygon seaFromCoastline(const std::vector<LineString>& coastlines, const Extent& box) {
  geos::Context ctx;
  MultiLineString pieces;
  for (const LineString& line : coastlines)
    for (LineString& piece : clipLine(ctx, line, box)) pieces.push_back(std::move(piece));
  if (pieces.empty()) return {};
  pieces.push_back(boxPolygon(box).outer);
  geos::GeomPtr lines = ctx.multiLineString(pieces);
  geos::GeomPtr noded = ctx.own(GEOSUnaryUnion_r(ctx.handle(), lines.get()), "node coastline");
  const GEOSGeometry* nodedRaw = noded.get();
  geos::GeomPtr faces = ctx.own(GEOSPolygonize_r(ctx.handle(), &nodedRaw, 1), "polygonize coastline");

  // Original coastline segments keep the OSM direction (clipping and merging may reverse pieces).
  struct Segment {
    Vec2 a, b;
  };
  std::vector<Segment> segments;
  for (const LineString& line : coastlines)
    for (size_t i = 0; i + 1 < line.size(); ++i) segments.push_back({line[i], line[i + 1]});
  const double tolerance = 1e-6 * std::fmax(1.0, std::fmax(box.maxX - box.minX, box.maxY - box.minY));

  MultiPolygon sea;
  for (Polygon& face : ctx.toPolygons(faces.get())) {
    double seaVotes = 0.0, landVotes = 0.0;
    auto vote = [&](const Ring& ring, bool faceOnLeft) {
      for (size_t i = 0; i + 1 < ring.size(); ++i) {
        const Vec2 a = ring[i], b = ring[i + 1];
        const Vec2 mid = (a + b) * 0.5;
        for (const Segment& s : segments) {
          if (distanceToSegment(mid, s.a, s.b) > tolerance) continue;
          // The face lies on the left of this edge; the sea is on the right of the coastline.
          const bool sameDirection = dot(b - a, s.b - s.a) > 0.0;
          const bool faceLeftOfCoast = sameDirection == faceOnLeft;
          (faceLeftOfCoast ? landVotes : seaVotes) += distance(a, b);
          break;
        }
      }
    };
    // The face is on the left of a counter-clockwise shell and on the right of a counter-clockwise hole.
    vote(face.outer, signedArea(face.outer) > 0.0);
    for (const Ring& hole : face.holes) vote(hole, signedArea(hole) < 0.0);
    if (seaVotes > landVotes) sea.push_back(std::move(face));
  }
  return sea;
}

}  // namespace urbanvec::gridify
