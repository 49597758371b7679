// GEOS helpers for the gridify stages (issue 2 §2).
#include "urbanvec/gridify/vector_ops.hpp"

namespace urbanvec::gridify {

Polygon boxPolygon(const Extent& b) {
  return Polygon{{{b.minX, b.minY}, {b.maxX, b.minY}, {b.maxX, b.maxY}, {b.minX, b.maxY}, {b.minX, b.minY}}, {}};
}

geos::GeomPtr validPolygons(const geos::Context& ctx, const MultiPolygon& polygons) {
  MultiPolygon usable;
  for (const Polygon& p : polygons)
    if (p.outer.size() >= 4) usable.push_back(p);
  geos::GeomPtr g = ctx.multiPolygon(usable);
  if (GEOSisValid_r(ctx.handle(), g.get()) == 1) return g;
  return ctx.own(GEOSMakeValid_r(ctx.handle(), g.get()), "make valid");
}

MultiPolygon clipPolygons(const geos::Context& ctx, const MultiPolygon& polygons, const Extent& box,
                          double minArea) {
  geos::GeomPtr g = validPolygons(ctx, polygons);
  geos::GeomPtr boxGeom = ctx.polygon(boxPolygon(box));
  geos::GeomPtr clipped = ctx.own(GEOSIntersection_r(ctx.handle(), g.get(), boxGeom.get()), "clip polygons");
  MultiPolygon out;
  for (Polygon& p : ctx.toPolygons(clipped.get()))
    if (area(p) > minArea) out.push_back(std::move(p));
  return out;
}

MultiLineString clipLine(const geos::Context& ctx, const LineString& line, const Extent& box) {
  if (line.size() < 2) return {};
  geos::GeomPtr g = ctx.lineString(line);
  geos::GeomPtr boxGeom = ctx.polygon(boxPolygon(box));
  geos::GeomPtr clipped = ctx.own(GEOSIntersection_r(ctx.handle(), g.get(), boxGeom.get()), "clip line");
  geos::GeomPtr merged = ctx.own(GEOSLineMerge_r(ctx.handle(), clipped.get()), "merge lines");
  MultiLineString out;
  for (LineString& l : ctx.toLines(merged.get()))
    if (l.size() >= 2 && length(l) > 0.0) out.push_back(std::move(l));
  return out;
}

geos::GeomPtr unionPolygons(const geos::Context& ctx, const std::vector<MultiPolygon>& polygons) {
  std::vector<geos::GeomPtr> parts;
  for (const MultiPolygon& mp : polygons) parts.push_back(validPolygons(ctx, mp));
  geos::GeomPtr all = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
  return ctx.own(GEOSUnaryUnion_r(ctx.handle(), all.get()), "union polygons");
}

}  // namespace urbanvec::gridify
