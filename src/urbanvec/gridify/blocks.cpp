// Truth blocks (issue 2 §2 `truth.gpkg`: "blocks (faces of the noded road network, minus water)").
#include "urbanvec/gridify/blocks.hpp"

#include <cmath>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/vector_ops.hpp"

namespace urbanvec::gridify {

std::vector<TruthBlock> roadBlocks(const MultiLineString& roads, const Extent& box,
                                   const std::vector<MultiPolygon>& water, double minArea) {
  geos::Context ctx;
  MultiLineString lines = roads;
  lines.push_back(boxPolygon(box).outer);
  geos::GeomPtr all = ctx.multiLineString(lines);
  geos::GeomPtr noded = ctx.own(GEOSUnaryUnion_r(ctx.handle(), all.get()), "node roads");
  const GEOSGeometry* nodedRaw = noded.get();
  geos::GeomPtr faces = ctx.own(GEOSPolygonize_r(ctx.handle(), &nodedRaw, 1), "polygonize roads");
  geos::GeomPtr wet = water.empty() ? nullptr : unionPolygons(ctx, water);
  geos::GeomPtr border = ctx.lineString(boxPolygon(box).outer);
  const double tolerance = 1e-7 * std::fmax(1.0, std::fmax(box.maxX - box.minX, box.maxY - box.minY));

  std::vector<TruthBlock> blocks;
  for (const Polygon& face : ctx.toPolygons(faces.get())) {
    geos::GeomPtr faceGeom = ctx.polygon(face);
    double gap = 0.0;
    GEOSDistance_r(ctx.handle(), faceGeom.get(), border.get(), &gap);
    const bool external = gap <= tolerance;
    MultiPolygon dry{face};
    if (wet) {
      geos::GeomPtr rest = ctx.own(GEOSDifference_r(ctx.handle(), faceGeom.get(), wet.get()), "cut water");
      dry = ctx.toPolygons(rest.get());
    }
    for (Polygon& part : dry)
      if (area(part) >= minArea) blocks.push_back({std::move(part), external});
  }
  return blocks;
}

std::vector<TruthBlock> curbBlocks(const std::vector<TruthBlock>& faces, const MultiLineString& roads,
                                   const std::vector<double>& halfWidths, const Extent& box, double minArea) {
  geos::Context ctx;
  geos::GeomPtr border = ctx.lineString(boxPolygon(box).outer);
  const double tolerance = 1e-7 * std::fmax(1.0, std::fmax(box.maxX - box.minX, box.maxY - box.minY));
  std::vector<MultiPolygon> corridors;
  corridors.reserve(roads.size());
  for (std::size_t i = 0; i < roads.size(); ++i) {
    if (roads[i].size() < 2 || !(halfWidths[i] > 0.0)) continue;
    geos::GeomPtr line = ctx.lineString(roads[i]);
    geos::GeomPtr corridor =
        ctx.own(GEOSBuffer_r(ctx.handle(), line.get(), halfWidths[i], 8), "road corridor");
    corridors.push_back(ctx.toPolygons(corridor.get()));
  }
  geos::GeomPtr roadSurface = corridors.empty() ? nullptr : unionPolygons(ctx, corridors);
  std::vector<TruthBlock> blocks;
  for (const TruthBlock& face : faces) {
    MultiPolygon land{face.shape};
    if (roadSurface) {
      geos::GeomPtr faceGeom = ctx.polygon(face.shape);
      geos::GeomPtr rest =
          ctx.own(GEOSDifference_r(ctx.handle(), faceGeom.get(), roadSurface.get()), "cut road corridors");
      land = ctx.toPolygons(rest.get());
    }
    for (Polygon& part : land) {
      if (area(part) < minArea) continue;
      bool external = face.external;
      if (external) {
        geos::GeomPtr partGeom = ctx.polygon(part);
        double gap = 0.0;
        GEOSDistance_r(ctx.handle(), partGeom.get(), border.get(), &gap);
        external = gap <= tolerance;
      }
      blocks.push_back({std::move(part), external});
    }
  }
  return blocks;
}

}  // namespace urbanvec::gridify
