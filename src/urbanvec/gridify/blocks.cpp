// Truth blocks (issue 2 §2 `truth.gpkg`: "blocks (faces of the noded road network, minus water)").
#include "urbanvec/gridify/blocks.hpp"

#include <cmath>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/vector_ops.hpp"

namespace urbanvec::gridify {

namespace {

/// Whether polygons touch the extent's border, within a tolerance relative to the extent's size.
class ExtentBorder {
 public:
  ExtentBorder(const geos::Context& ctx, const Extent& box)
      : ctx_(ctx),
        border_(ctx.lineString(boxPolygon(box).outer)),
        tolerance_(1e-7 * std::fmax(1.0, std::fmax(box.maxX - box.minX, box.maxY - box.minY))) {}
  bool touches(const Polygon& polygon) const {
    geos::GeomPtr geom = ctx_.polygon(polygon);
    double gap = 0.0;
    GEOSDistance_r(ctx_.handle(), geom.get(), border_.get(), &gap);
    return gap <= tolerance_;
  }

 private:
  const geos::Context& ctx_;
  geos::GeomPtr border_;
  double tolerance_;
};

}  // namespace

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
  const ExtentBorder border(ctx, box);

  std::vector<TruthBlock> blocks;
  for (const Polygon& face : ctx.toPolygons(faces.get())) {
    const bool external = border.touches(face);
    MultiPolygon dry{face};
    if (wet) {
      geos::GeomPtr rest =
          ctx.own(GEOSDifference_r(ctx.handle(), ctx.polygon(face).get(), wet.get()), "cut water");
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
  const ExtentBorder border(ctx, box);
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
      const bool external = face.external && border.touches(part);
      blocks.push_back({std::move(part), external});
    }
  }
  return blocks;
}

}  // namespace urbanvec::gridify
