// Building-based tessellation of blocks (issue 2 §2 parcels; momepy's morphological tessellation with
// a reach limit, using one point per building).
#include "urbanvec/gridify/parcels.hpp"

#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/vector_ops.hpp"

namespace urbanvec::gridify {

namespace {

struct TreeQuery {
  std::vector<std::size_t> hits;
};

void collectHit(void* item, void* userdata) {
  static_cast<TreeQuery*>(userdata)->hits.push_back(reinterpret_cast<std::size_t>(item));
}

}  // namespace

Tessellation tessellateBlocks(const std::vector<TruthBlock>& blocks, const std::vector<MultiPolygon>& footprints,
                              double reach) {
  geos::Context ctx;
  GEOSContextHandle_t h = ctx.handle();
  Tessellation out;
  out.blockBuilt.assign(blocks.size(), false);

  std::vector<geos::GeomPtr> blockGeoms;
  GEOSSTRtree* tree = GEOSSTRtree_create_r(h, 10);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    blockGeoms.push_back(ctx.polygon(blocks[i].shape));
    GEOSSTRtree_insert_r(h, tree, blockGeoms.back().get(), reinterpret_cast<void*>(i));
  }

  std::vector<geos::GeomPtr> shapes;
  std::vector<geos::GeomPtr> points;
  std::vector<std::vector<std::size_t>> byBlock(blocks.size());
  for (std::size_t b = 0; b < footprints.size(); ++b) {
    shapes.push_back(validPolygons(ctx, footprints[b]));
    points.push_back(GEOSisEmpty_r(h, shapes.back().get()) == 1
                         ? nullptr
                         : ctx.own(GEOSPointOnSurface_r(h, shapes.back().get()), "point on building"));
    if (!points.back()) continue;
    TreeQuery query;
    GEOSSTRtree_query_r(h, tree, points.back().get(), collectHit, &query);
    std::size_t best = blocks.size();
    for (std::size_t i : query.hits)
      if (GEOSContains_r(h, blockGeoms[i].get(), points.back().get()) == 1 && i < best) best = i;
    if (best < blocks.size()) byBlock[best].push_back(b);
  }
  GEOSSTRtree_destroy_r(h, tree);

  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::vector<std::size_t>& members = byBlock[i];
    if (members.empty()) continue;
    out.blockBuilt[i] = true;
    // One cell per building: the whole block for a lone building, else the Voronoi cell of its point.
    std::vector<geos::GeomPtr> cells(members.size());
    if (members.size() == 1) {
      cells[0] = ctx.own(GEOSGeom_clone_r(h, blockGeoms[i].get()), "clone block");
    } else {
      std::vector<geos::GeomPtr> pts;
      for (std::size_t b : members) pts.push_back(ctx.own(GEOSGeom_clone_r(h, points[b].get()), "clone point"));
      geos::GeomPtr multipoint = ctx.collection(GEOS_MULTIPOINT, std::move(pts));
      geos::GeomPtr diagram =
          ctx.own(GEOSVoronoiDiagram_r(h, multipoint.get(), blockGeoms[i].get(), 0.0, 0), "voronoi");
      const int n = GEOSGetNumGeometries_r(h, diagram.get());
      for (int k = 0; k < n; ++k) {
        const GEOSGeometry* cell = GEOSGetGeometryN_r(h, diagram.get(), k);
        for (std::size_t m = 0; m < members.size(); ++m) {
          if (!cells[m] && GEOSIntersects_r(h, cell, points[members[m]].get()) == 1) {
            cells[m] = ctx.own(GEOSGeom_clone_r(h, cell), "clone cell");
            break;
          }
        }
      }
    }
    for (std::size_t m = 0; m < members.size(); ++m) {
      if (!cells[m]) continue;  // a point repeated within the block: the first building takes the cell
      geos::GeomPtr inBlock = ctx.own(GEOSIntersection_r(h, cells[m].get(), blockGeoms[i].get()), "cell in block");
      geos::GeomPtr near = ctx.own(GEOSBuffer_r(h, shapes[members[m]].get(), reach, 4), "reach buffer");
      geos::GeomPtr parcel = ctx.own(GEOSIntersection_r(h, inBlock.get(), near.get()), "parcel");
      MultiPolygon shape = ctx.toPolygons(parcel.get());
      if (shape.empty()) continue;
      out.parcels.push_back({std::move(shape), members[m], i});
    }
  }
  return out;
}

}  // namespace urbanvec::gridify
