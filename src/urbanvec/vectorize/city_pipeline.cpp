#include "urbanvec/vectorize/city_pipeline.hpp"

#include <algorithm>
#include <utility>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/memory.hpp"
#include "urbanvec/vectorize/road_frontage.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"

namespace urbanvec::vectorize {

namespace {

struct Frame {
  const GridSpec& grid;
  Vec2 toWorld(const Vec2& p) const { return vectorize::toWorld(p, grid); }
  Vec2 toCells(const Vec2& w) const {
    const Vec2 px = grid.transform.worldToPixel(w);
    return {px.x, (grid.frameHeight > 0 ? grid.frameHeight : grid.height) - px.y};
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

/// The road frontage of every block (road_frontage.hpp) from the pavement layer, in cells.
std::vector<MultiLineString> roadFacingEdges(const BlocksResult& blocks, const Frame& frame, double tolerance,
                                             int threads) {
  std::vector<Polygon> pieces;
  for (const Feature& f : blocks.pavement.features) {
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) pieces.push_back(frame.toCells(*p));
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry))
      for (const Polygon& p : *mp) pieces.push_back(frame.toCells(p));
  }
  std::vector<const Polygon*> outlines;
  outlines.reserve(blocks.blockInfo.size());
  for (const BlockInfo& info : blocks.blockInfo) outlines.push_back(&info.shape);
  return vectorize::roadFacingEdges(std::move(pieces), outlines, tolerance, threads);
}

/// Rotates a ring to start at its smallest vertex (x, then y), keeping its orientation and closure.
void startAtSmallestVertex(Ring& ring) {
  if (ring.size() < 4) return;
  const bool closed = ring.front() == ring.back();
  if (closed) ring.pop_back();
  std::rotate(ring.begin(), std::min_element(ring.begin(), ring.end(), lexicographicLess), ring.end());
  if (closed) ring.push_back(ring.front());
}

/// A block's outline in one canonical form: each ring starting at its smallest vertex, holes in the
/// order of those vertices. The overlays of C-D give the same rings with a start that depends on
/// the other pieces they met, which differ between a tile's window and a single run (issue 22);
/// stages E2-E6 follow the outline from its start, so they get the same block in any window.
void canonicalizeOutline(Polygon& polygon) {
  startAtSmallestVertex(polygon.outer);
  for (Ring& hole : polygon.holes) startAtSmallestVertex(hole);
  std::sort(polygon.holes.begin(), polygon.holes.end(), [](const Ring& a, const Ring& b) {
    return !b.empty() && (a.empty() || lexicographicLess(a.front(), b.front()));
  });
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
                                                  const std::vector<SimParcel>& parcels,
                                                  const Grid<std::uint8_t>& cells) {
  parcels::SimBlockSummary summary;
  summary.useArea.assign(256, 0.0);
  for (int index : simBlockIndices) {
    const SimBlock& block = blocks.at(static_cast<size_t>(index));
    for (std::int32_t patch : block.patches)
      summary.useArea[cells.cells.at(static_cast<size_t>(patch))] += 1.0;
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
                         const GridSpec& grid, const CityOptions& options, const Progress& progress,
                         const LayerSink& sink) {
  CityResult result;
  const LayerSink emit = sinkOrAppend(sink, result.layers);
  const Frame frame{grid};
  BlocksOptions blocksOptions = options.blocks;
  blocksOptions.road.threads = options.parcels.threads;  // one thread setting for every parallel stage
  blocksOptions.water.threads = options.parcels.threads;
  blocksOptions.outline.threads = options.parcels.threads;
  blocksOptions.external.threads = options.parcels.threads;
  {
    // Only C-D5 read the simulated city (its cell lists take 8 bytes per cell of a block or parcel).
    const SimulatedCity city = simulatedCity(cells, blocks, simParcels);
    result.blocks = vectorizeBlocks(network, city, grid, blocksOptions, subProgress(progress, 0.0, 0.35));
  }
  releaseFreedMemory();  // the overlays of C-D5 and the simulated city
  for (BlockInfo& info : result.blocks.blockInfo) canonicalizeOutline(info.shape);

  reportProgress(progress, 0.35, "road frontage");
  std::vector<MultiLineString> facing =
      roadFacingEdges(result.blocks, frame, options.roadFacingTolerance, options.parcels.threads);
  // Nothing reads the pavement layer after the road frontage: it is final (a writer can store it
  // while the parcels are searched).
  emit(std::move(result.blocks.pavement));
  releaseFreedMemory();
  std::vector<parcels::ParcelBlock> parcelBlocks;  // the part 3 input, aligned with blocks.blockInfo
  parcelBlocks.reserve(result.blocks.blockInfo.size());
  for (size_t i = 0; i < result.blocks.blockInfo.size(); ++i) {
    const BlockInfo& info = result.blocks.blockInfo[i];
    parcels::ParcelBlock block;
    block.blockId = info.blockId;
    block.polygon = info.shape;
    block.external = !info.internal;
    block.hasCulDeSac = info.hasCulDeSac;
    block.roadFacing = std::move(facing[i]);
    if (block.roadFacing.empty() && options.islandFrontage) {
      block.roadFacing.push_back(info.shape.outer);
      for (const Ring& hole : info.shape.holes) block.roadFacing.push_back(hole);
    }
    block.obbAspect = info.obb.aspect;
    block.obbDiagonal = info.obb.diagonal;
    block.sim = summarizeSimulatedBlocks(info.simBlockIndices, blocks, simParcels, cells);
    // Seed stream = the block's first simulated cell (row-major) in the whole raster, (row << 32) | col:
    // the same in a tile's window as in a single run (issue 22), whatever the block numbering.
    std::int32_t first = -1;
    for (int k : info.simBlockIndices)
      for (std::int32_t p : blocks[static_cast<size_t>(k)].patches)
        if (first < 0 || p < first) first = p;
    if (first >= 0 && cells.width > 0)
      block.seedStream = (static_cast<std::uint64_t>(first / cells.width + options.originRow) << 32) |
                         static_cast<std::uint64_t>(first % cells.width + options.originCol);
    parcelBlocks.push_back(std::move(block));
  }
  std::vector<MultiLineString>().swap(facing);
  result.parcels = parcels::vectorizeParcels(parcelBlocks, options.parcels, subProgress(progress, 0.4, 0.97));
  std::vector<parcels::ParcelBlock>().swap(parcelBlocks);  // copies of the outlines, frontage, summaries
  releaseFreedMemory();

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
                            {"relaxed_rules", FieldType::Integer},
                            {"sim_population", FieldType::Real},
                            {"ignored_population", FieldType::Real},
                            {"ignored_uses", FieldType::Integer}});
  const int hasSpineField = result.blocks.blocks.fieldIndex("has_spine");
  std::int64_t nextParcelId = 1;
  std::int64_t nextSpineId = 1;
  std::size_t parcelCount = 0;
  for (const parcels::BlockParcels& out : result.parcels.blocks) parcelCount += out.parcels.size();
  parcelLayer.features.reserve(parcelCount);
  report.features.reserve(result.parcels.blocks.size());
  // Each spine and parcel polygon is released once its world copy is in its layer: the layers hold
  // the only copy of the geometry (ParcelsResult keeps the reports and populations).
  for (size_t i = 0; i < result.parcels.blocks.size(); ++i) {
    parcels::BlockParcels& out = result.parcels.blocks[i];
    const std::int64_t blockId = result.blocks.blockInfo[i].blockId;
    if (!out.spine.empty()) {
      MultiLineString world;
      for (const LineString& line : out.spine) world.push_back(frame.toWorld(line));
      spines.features.push_back({std::move(world), {nextSpineId++, blockId}});
    }
    if (hasSpineField >= 0 && i < result.blocks.blocks.features.size())
      result.blocks.blocks.features[i].values[static_cast<size_t>(hasSpineField)] =
          std::int64_t{out.report.hasSpine && !out.spine.empty() ? 1 : 0};
    for (parcels::VectorParcel& parcel : out.parcels) {
      const double areaM2 = parcel.area * cellArea;
      const std::string use = parcel.undeveloped ? "undeveloped" : std::string(landUseName(parcel.use));
      parcelLayer.features.push_back({frame.toWorld(parcel.polygon),
                                      {nextParcelId++, blockId, use, parcel.population,
                                       areaM2 > 0.0 ? parcel.population / areaM2 : 0.0, areaM2}});
      parcel.polygon = Polygon();
    }
    out.spine = MultiLineString();
    const parcels::BlockReport& r = out.report;
    report.features.push_back(
        {std::monostate{},
         {blockId, std::int64_t{r.simParcels}, std::int64_t{r.targetParcels}, std::int64_t{r.parcels},
          std::int64_t{r.tries}, r.cost, r.costUse, r.costDistance, r.costSize, r.shortfall,
          std::int64_t{r.relaxedRules}, r.simPopulation, r.ignoredPopulation, std::int64_t{r.ignoredUses}}});
  }
  // Moved, not copied (an initializer list copies): at city scale each layer is tens of MB.
  result.blockFeatures = result.blocks.blocks.features.size();
  emit(std::move(result.blocks.blocks));
  emit(std::move(result.blocks.water));
  emit(std::move(spines));
  emit(std::move(parcelLayer));
  emit(std::move(report));
  reportProgress(progress, 1.0, "city layers");
  return result;
}

}  // namespace urbanvec::vectorize
