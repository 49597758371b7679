#include "urbanvec/vectorize/city_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/road_output.hpp"

namespace urbanvec::vectorize {

namespace {

struct Frame {
  const GridSpec& grid;
  Vec2 toWorld(const Vec2& p) const { return vectorize::toWorld(p, grid); }
  Vec2 toCells(const Vec2& w) const {
    const Vec2 px = grid.transform.worldToPixel(w);
    return {px.x, grid.height - px.y};
  }
  LineString toWorld(const LineString& line) const {
    LineString out;
    out.reserve(line.size());
    for (const Vec2& p : line) out.push_back(toWorld(p));
    return out;
  }
  Polygon toWorld(const Polygon& polygon) const {
    Polygon out{toWorld(polygon.outer), {}};
    for (const Ring& hole : polygon.holes) out.holes.push_back(toWorld(hole));
    return out;
  }
  Polygon toCells(const Polygon& polygon) const {
    auto ring = [&](const Ring& r) {
      Ring out;
      for (const Vec2& p : r) out.push_back(toCells(p));
      return out;
    };
    Polygon out{ring(polygon.outer), {}};
    for (const Ring& hole : polygon.holes) out.holes.push_back(ring(hole));
    return out;
  }
};

/// The parts of each block's outline that run along pavement: the road frontage E2 measures.
/// A local union of the pavement pieces near the block (STRtree) keeps this linear in city size.
std::vector<MultiLineString> roadFacingEdges(const BlocksResult& blocks, const Frame& frame, double tolerance) {
  geos::Context ctx;
  GEOSContextHandle_t h = ctx.handle();
  std::vector<geos::GeomPtr> pavement;
  GEOSSTRtree* tree = GEOSSTRtree_create_r(h, 10);
  for (const Feature& f : blocks.pavement.features) {
    MultiPolygon parts;
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) parts.push_back(*p);
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry)) parts = *mp;
    for (const Polygon& p : parts) {
      pavement.push_back(ctx.polygon(frame.toCells(p)));
      GEOSSTRtree_insert_r(h, tree, pavement.back().get(), pavement.back().get());
    }
  }
  std::vector<MultiLineString> out;
  for (const BlockInfo& info : blocks.blockInfo) {
    geos::GeomPtr block = ctx.polygon(info.shape);
    geos::GeomPtr envelope = ctx.own(GEOSBuffer_r(h, block.get(), tolerance * 10, 1), "block envelope");
    std::vector<GEOSGeometry*> near;
    GEOSSTRtree_query_r(
        h, tree, envelope.get(),
        [](void* item, void* userdata) {
          static_cast<std::vector<GEOSGeometry*>*>(userdata)->push_back(static_cast<GEOSGeometry*>(item));
        },
        &near);
    if (near.empty()) {
      out.emplace_back();
      continue;
    }
    std::sort(near.begin(), near.end());  // deterministic union input whatever the tree's order
    std::vector<geos::GeomPtr> parts;
    for (GEOSGeometry* g : near) parts.push_back(ctx.own(GEOSGeom_clone_r(h, g), "clone"));
    geos::GeomPtr local = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
    geos::GeomPtr band = ctx.own(GEOSBuffer_r(h, local.get(), tolerance, 2), "pavement band");
    geos::GeomPtr outline = ctx.own(GEOSBoundary_r(h, block.get()), "block outline");
    geos::GeomPtr facing = ctx.own(GEOSIntersection_r(h, outline.get(), band.get()), "road-facing edges");
    geos::GeomPtr merged = ctx.own(GEOSLineMerge_r(h, facing.get()), "road-facing merge");
    out.push_back(ctx.toLines(merged.get()));
  }
  GEOSSTRtree_destroy_r(h, tree);
  return out;
}

Layer makeLayer(const std::string& name, GeometryType type, std::vector<FieldDef> fields) {
  Layer layer;
  layer.name = name;
  layer.geometryType = type;
  layer.fields = std::move(fields);
  return layer;
}

}  // namespace

parcels::SimBlockSummary summarizeSimulatedBlocks(const std::vector<int>& simBlockIndices,
                                                  const std::vector<SimBlock>& blocks,
                                                  const std::vector<SimParcel>& parcels) {
  parcels::SimBlockSummary summary;
  for (int index : simBlockIndices) {
    const SimBlock& block = blocks.at(static_cast<size_t>(index));
    summary.area += block.area;
    summary.developedArea += block.developedArea;
    summary.undevelopedArea += block.undevelopedArea;
    for (int p : block.parcels) {
      const SimParcel& sim = parcels.at(static_cast<size_t>(p));
      summary.parcels.push_back({sim.id, sim.use, sim.area, sim.population, sim.center});
    }
  }
  return summary;
}

CityResult vectorizeCity(const RoadNetwork& network, const Grid<std::uint8_t>& cells,
                         const std::vector<SimBlock>& blocks, const std::vector<SimParcel>& simParcels,
                         const GridSpec& grid, const CityOptions& options, const Progress& progress) {
  CityResult result;
  const Frame frame{grid};
  const SimulatedCity city = simulatedCity(cells, blocks, simParcels);
  result.blocks = vectorizeBlocks(network, city, grid, options.blocks, subProgress(progress, 0.0, 0.35));

  reportProgress(progress, 0.35, "road frontage");
  const std::vector<MultiLineString> facing =
      roadFacingEdges(result.blocks, frame, options.roadFacingTolerance);
  for (size_t i = 0; i < result.blocks.blockInfo.size(); ++i) {
    const BlockInfo& info = result.blocks.blockInfo[i];
    parcels::ParcelBlock block;
    block.blockId = info.blockId;
    block.polygon = info.shape;
    block.external = !info.internal;
    block.hasCulDeSac = info.hasCulDeSac;
    block.roadFacing = facing[i];
    block.obbAspect = info.obb.aspect;
    block.obbDiagonal = info.obb.diagonal;
    block.sim = summarizeSimulatedBlocks(info.simBlockIndices, blocks, simParcels);
    result.parcelBlocks.push_back(std::move(block));
  }
  result.parcels = parcels::vectorizeParcels(result.parcelBlocks, options.parcels, subProgress(progress, 0.4, 0.97));

  reportProgress(progress, 0.97, "city layers");
  const double cellArea = grid.transform.cellSize() * grid.transform.cellSize();
  Layer spines = makeLayer("spines", GeometryType::MultiLineString,
                           {{"spine_id", FieldType::Integer}, {"block_id", FieldType::Integer}});
  Layer parcelLayer = makeLayer("parcels", GeometryType::Polygon,
                                {{"parcel_id", FieldType::Integer},
                                 {"block_id", FieldType::Integer},
                                 {"land_use", FieldType::String},
                                 {"population", FieldType::Real},
                                 {"density", FieldType::Real},
                                 {"area", FieldType::Real}});
  Layer report = makeLayer("vectorize_report", GeometryType::None,
                           {{"block_id", FieldType::Integer},
                            {"sim_parcels", FieldType::Integer},
                            {"target_parcels", FieldType::Integer},
                            {"parcels", FieldType::Integer},
                            {"tries", FieldType::Integer},
                            {"cost", FieldType::Real},
                            {"cost_use", FieldType::Real},
                            {"cost_distance", FieldType::Real},
                            {"cost_size", FieldType::Real},
                            {"shortfall", FieldType::String},
                            {"sim_population", FieldType::Real},
                            {"ignored_population", FieldType::Real},
                            {"ignored_uses", FieldType::Integer}});
  const int hasSpineField = result.blocks.blocks.fieldIndex("has_spine");
  std::int64_t nextParcelId = 1;
  std::int64_t nextSpineId = 1;
  for (size_t i = 0; i < result.parcels.blocks.size(); ++i) {
    const parcels::BlockParcels& out = result.parcels.blocks[i];
    const std::int64_t blockId = result.parcelBlocks[i].blockId;
    if (!out.spine.empty()) {
      MultiLineString world;
      for (const LineString& line : out.spine) world.push_back(frame.toWorld(line));
      spines.features.push_back({world, {nextSpineId++, blockId}});
    }
    if (hasSpineField >= 0 && i < result.blocks.blocks.features.size())
      result.blocks.blocks.features[i].values[static_cast<size_t>(hasSpineField)] =
          std::int64_t{out.report.hasSpine && !out.spine.empty() ? 1 : 0};
    for (const parcels::VectorParcel& parcel : out.parcels) {
      const double areaM2 = parcel.area * cellArea;
      const std::string use = parcel.undeveloped ? "undeveloped" : std::string(landUseName(parcel.use));
      parcelLayer.features.push_back({frame.toWorld(parcel.polygon),
                                      {nextParcelId++, blockId, use, parcel.population,
                                       areaM2 > 0.0 ? parcel.population / areaM2 : 0.0, areaM2}});
    }
    const parcels::BlockReport& r = out.report;
    report.features.push_back({std::monostate{},
                               {blockId, std::int64_t{r.simParcels}, std::int64_t{r.targetParcels},
                                std::int64_t{r.parcels}, std::int64_t{r.tries}, r.cost, r.costUse, r.costDistance,
                                r.costSize, r.shortfall, r.simPopulation, r.ignoredPopulation,
                                std::int64_t{r.ignoredUses}}});
  }
  result.layers = {result.blocks.pavement, result.blocks.blocks, result.blocks.water, spines, parcelLayer, report};
  reportProgress(progress, 1.0, "city layers");
  return result;
}

}  // namespace urbanvec::vectorize
