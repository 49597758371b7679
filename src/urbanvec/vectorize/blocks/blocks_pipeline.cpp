// Vectorizer part 2 pipeline (shared/specs/sexton-vectorizer.md §1 rows C-D5, §11.3-11.4 checks).
#include "urbanvec/vectorize/blocks/blocks_pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <sstream>
#include <string>
#include <thread>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/memory.hpp"

namespace urbanvec::vectorize {

namespace {

constexpr double kPi = 3.14159265358979323846;

Ring ringToWorld(const Ring& ring, const GridSpec& grid) {
  Ring out;
  out.reserve(ring.size());
  for (const Vec2& p : ring) out.push_back(vectorize::toWorld(p, grid));
  return out;
}

Polygon toWorld(const Polygon& p, const GridSpec& grid) {
  Polygon out{ringToWorld(p.outer, grid), {}};
  for (const Ring& h : p.holes) out.holes.push_back(ringToWorld(h, grid));
  orientClockwise(out);  // a south-up transform mirrors the frame
  return out;
}

std::string blockKindName(bool internal) {
  return internal ? "internal" : "external";
}

std::vector<Polygon> layerPolygons(const Layer* layer, const std::string& kindFilter = {}) {
  std::vector<Polygon> out;
  if (!layer) return out;
  const int kind = layer->fieldIndex("kind");
  for (const Feature& f : layer->features) {
    if (!kindFilter.empty()) {
      if (kind < 0) continue;
      const auto* value = std::get_if<std::string>(&f.values[kind]);
      if (!value || *value != kindFilter) continue;
    }
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) out.push_back(*p);
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry))
      out.insert(out.end(), mp->begin(), mp->end());
  }
  return out;
}

/// waterPolygons on a thread of its own when more than one thread is allowed (WaterSplitOptions::threads);
/// joined by join() or, on an exception of the caller (cancel), stopped and joined by the destructor.
class ConcurrentWater {
 public:
  ConcurrentWater(const Grid<LandUse>& landUse, const WaterSplitOptions& options) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads) : cores;
    if (threads < 2) return;
    thread_ = std::thread([this, &landUse, &options] {
      try {
        water_ = waterPolygons(landUse, options, [this](double, std::string_view) { return !stop_.load(); });
      } catch (...) {
        failure_ = std::current_exception();
      }
    });
  }
  ConcurrentWater(const ConcurrentWater&) = delete;
  ConcurrentWater& operator=(const ConcurrentWater&) = delete;
  ~ConcurrentWater() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool started() const { return thread_.joinable(); }
  MultiPolygon join() {
    thread_.join();
    if (failure_) std::rethrow_exception(failure_);
    return std::move(water_);
  }

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false};
  MultiPolygon water_;
  std::exception_ptr failure_;
};

}  // namespace

BlocksResult vectorizeBlocks(const RoadNetwork& network, const SimulatedCity& city, const GridSpec& grid,
                             const BlocksOptions& options, const Progress& progress) {
  if (city.grid.width != grid.width || city.grid.height != grid.height)
    throw invalidInput("The land-use grid is " + std::to_string(city.grid.width) + " x " +
                       std::to_string(city.grid.height) + " cells but the grid it belongs to is " +
                       std::to_string(grid.width) + " x " + std::to_string(grid.height) + ".");
  BlocksResult result;
  BlocksStats& stats = result.stats;
  stats.simulatedBlocks = static_cast<int>(city.blocks.size());

  // C: pavement.
  RoadGeometry roads = buildRoadGeometry(network, options.road, subProgress(progress, 0.0, 0.35));
  stats.convexHullFallbacks = roads.convexHullFallbacks;

  // The water regions depend on the land-use grid alone: with more than one thread they are traced on
  // a second thread while D1's outlining (one core) runs (issue 21). Same
  // result either way; the water stage's progress is reported once it is joined.
  MultiPolygon water;
  ConcurrentWater concurrentWater(city.grid, options.water);
  if (!concurrentWater.started())
    water = waterPolygons(city.grid, options.water, subProgress(progress, 0.5, 0.6));

  // D1: internal blocks and the perimeter.
  BlockOutline outline = outlineBlocks(roads.pieces, options.outline, subProgress(progress, 0.35, 0.5));
  result.perimeterCells = outline.perimeter;
  stats.absorbedSlivers =
      absorbSlivers(roads.pieces, outline.slivers, options.outline.precisionGrid, options.outline.threads);
  releaseFreedMemory();  // D1's overlays and union
  // Only D2-D5 read the simulated block of each cell: built after D1's union, not beside it.
  const Grid<int> blockOfCell = simulatedBlockOfCells(city);

  // D3 + D4: external blocks from the perimeter and the boundary lines.
  if (concurrentWater.started()) {
    water = concurrentWater.join();
    reportProgress(progress, 0.6, "water");
  }
  ExternalBlocks external = buildExternalBlocks(network, outline.perimeter, city, blockOfCell,
                                                options.external, subProgress(progress, 0.6, 0.75));
  stats.boundaryLines = external.boundaryLines;
  stats.deletedBoundaryLines = external.deletedLines;
  stats.droppedExternalFaces = external.droppedFaces;

  // D2: water splitting of every block.
  std::vector<Polygon> blocks = std::move(outline.internalBlocks);
  std::vector<bool> internal(blocks.size(), true);
  for (Polygon& p : external.blocks) {
    blocks.push_back(std::move(p));
    internal.push_back(false);
  }
  WaterSplit split = splitBlocksByWater(blocks, internal, water, city, blockOfCell, options.water,
                                        subProgress(progress, 0.75, 0.85));
  stats.waterSplitBlocks = split.blocksSplit;
  stats.shoreScraps = static_cast<int>(split.shoreScraps.size());

  // D5: matching; water-split pieces keep their pairing (the piece holding most of the block's cells).
  std::vector<Polygon> vectorBlocks;
  std::vector<int> preMatched(city.blocks.size(), -1);
  std::vector<int> preMatchedCells(city.blocks.size(), 0);
  for (size_t v = 0; v < split.blocks.size(); ++v) {
    vectorBlocks.push_back(split.blocks[v].shape);
    const int sim = split.blocks[v].pairedSimBlock;
    if (sim < 0) continue;
    const int cells = [&] {
      for (const auto& [b, n] : tallyCells(split.blocks[v].shape, blockOfCell, city.grid).blocks)
        if (b == sim) return n;
      return 0;
    }();
    if (preMatched[sim] < 0 || cells > preMatchedCells[sim]) {
      preMatched[sim] = static_cast<int>(v);
      preMatchedCells[sim] = cells;
    }
  }
  result.matching = matchSimulatedBlocks(vectorBlocks, city, blockOfCell, preMatched,
                                         subProgress(progress, 0.85, 0.95), options.matching);
  stats.failsafeUses = result.matching.failsafeUses;
  stats.failsafeWithParcels = result.matching.failsafeWithParcels;
  stats.majorityUses = result.matching.majorityUses;
  stats.overlapUses = result.matching.overlapUses;
  stats.underPavement = result.matching.underPavement;
  stats.matchedSimulatedBlocks = result.matching.matched;

  // Output layers and per-block data.
  geos::Context ctx;
  const double cellSize = grid.transform.cellSize();
  std::vector<geos::GeomPtr> culDeSacs;
  std::vector<const GEOSGeometry*> culDeSacRaw;
  for (const PavementPiece& piece : roads.pieces)
    if (piece.kind == PavementKind::CulDeSac) {
      culDeSacs.push_back(ctx.multiPolygon(piece.shape));
      culDeSacRaw.push_back(culDeSacs.back().get());
    }
  GeometryIndex culDeSacIndex(ctx, culDeSacRaw);

  result.blocks.name = "blocks";
  result.blocks.geometryType = GeometryType::Polygon;
  result.blocks.fields = {{"block_id", FieldType::Integer},     {"kind", FieldType::String},
                          {"sim_block_id", FieldType::Integer}, {"area", FieldType::Real},
                          {"has_spine", FieldType::Integer},    {"obb_aspect", FieldType::Real},
                          {"obb_diagonal", FieldType::Real}};
  std::vector<std::vector<std::pair<int, int>>> simOfVector(vectorBlocks.size());  // (cells, sim index)
  for (size_t sim = 0; sim < city.blocks.size(); ++sim) {
    const int v = result.matching.vectorBlockOfSim[sim];
    if (v >= 0)
      simOfVector[v].emplace_back(static_cast<int>(city.blocks[sim].cells.size()), static_cast<int>(sim));
  }
  for (size_t v = 0; v < vectorBlocks.size(); ++v) {
    BlockInfo info;
    info.blockId = static_cast<int>(v) + 1;
    info.internal = split.blocks[v].internal;
    info.shape = vectorBlocks[v];
    info.areaCells = area(info.shape);
    info.obb = orientedBoundingBox(info.shape);
    info.obbDiagonal = info.obb.diagonal * cellSize;
    std::stable_sort(simOfVector[v].begin(), simOfVector[v].end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [cells, sim] : simOfVector[v]) {
      info.simBlockIndices.push_back(sim);
      info.simBlockIds.push_back(city.blocks[sim].id);
    }
    geos::GeomPtr g = ctx.polygon(info.shape);
    for (int k : culDeSacIndex.query(g.get())) {
      double d = 1.0;
      GEOSDistance_r(ctx.handle(), culDeSacRaw[k], g.get(), &d);
      if (d <= 10.0 * options.road.precisionGrid) info.hasCulDeSac = true;
    }
    Polygon world = toWorld(info.shape, grid);
    Feature f;
    f.values = {std::int64_t{info.blockId},
                blockKindName(info.internal),
                info.simBlockIds.empty() ? FieldValue{} : FieldValue{std::int64_t{info.simBlockIds.front()}},
                area(world),
                std::int64_t{0},
                info.obb.aspect,
                info.obbDiagonal};
    f.geometry = std::move(world);
    result.blocks.features.push_back(std::move(f));
    result.blockInfo.push_back(std::move(info));
  }

  result.pavement.name = "pavement";
  result.pavement.geometryType = GeometryType::Polygon;
  result.pavement.fields = {
      {"pavement_id", FieldType::Integer}, {"kind", FieldType::String}, {"road_class", FieldType::String}};
  for (const PavementPiece& piece : roads.pieces)
    for (const Polygon& p : piece.shape) {
      Feature f;
      f.values = {std::int64_t(result.pavement.features.size() + 1),
                  std::string(pavementKindName(piece.kind)), std::string(roadClassName(piece.roadClass))};
      f.geometry = toWorld(p, grid);
      result.pavement.features.push_back(std::move(f));
    }

  // Shore scraps join the water they border.
  MultiPolygon allWater = water;
  if (!split.shoreScraps.empty()) {
    std::vector<geos::GeomPtr> parts;
    parts.push_back(ctx.multiPolygon(water));
    parts.push_back(ctx.multiPolygon(split.shoreScraps));
    geos::GeomPtr merged = unionOnGrid(ctx, std::move(parts), options.water.precisionGrid);
    allWater = ctx.toPolygons(merged.get());
  }
  result.water.name = "water";
  result.water.geometryType = GeometryType::Polygon;
  result.water.fields = {{"water_id", FieldType::Integer}};
  for (const Polygon& p : allWater) {
    Feature f;
    f.values = {std::int64_t(result.water.features.size() + 1)};
    f.geometry = toWorld(p, grid);
    result.water.features.push_back(std::move(f));
  }
  for (const Polygon& p : outline.perimeter) result.perimeter.push_back(toWorld(p, grid));
  reportProgress(progress, 1.0, "blocks");
  return result;
}

BlocksCheckReport checkBlocks(const BlocksCheckInput& input, const BlocksQualityTargets& targets) {
  if (!input.pavement || !input.blocks)
    throw internalError("checkBlocks needs the pavement and blocks layers.");
  geos::Context ctx;
  const GEOSContextHandle_t h = ctx.handle();
  BlocksCheckReport report;

  auto build = [&](const std::vector<Polygon>& polygons, std::vector<geos::GeomPtr>& geoms,
                   std::vector<const GEOSGeometry*>& raw) {
    for (const Polygon& p : polygons) {
      geoms.push_back(ctx.polygon(p));
      raw.push_back(geoms.back().get());
      ++report.polygons;
      if (GEOSisValid_r(h, geoms.back().get()) != 1) ++report.invalidPolygons;
    }
  };
  std::vector<geos::GeomPtr> pave, blocks, water;
  std::vector<const GEOSGeometry*> paveRaw, blocksRaw, waterRaw;
  const std::vector<Polygon> pavePolys = layerPolygons(input.pavement);
  const std::vector<Polygon> blockPolys = layerPolygons(input.blocks);
  const std::vector<Polygon> internalPolys = layerPolygons(input.blocks, "internal");
  const std::vector<Polygon> waterPolys = layerPolygons(input.water);
  build(pavePolys, pave, paveRaw);
  build(blockPolys, blocks, blocksRaw);
  build(waterPolys, water, waterRaw);
  // Overlay of invalid input would throw; measure overlaps on repaired copies.
  auto repaired = [&](std::vector<geos::GeomPtr>& geoms, std::vector<const GEOSGeometry*>& raw) {
    for (size_t i = 0; i < geoms.size(); ++i)
      if (GEOSisValid_r(h, geoms[i].get()) != 1) {
        geoms[i] = ctx.own(GEOSMakeValid_r(h, geoms[i].get()), "make valid");
        raw[i] = geoms[i].get();
      }
  };
  repaired(pave, paveRaw);
  repaired(blocks, blocksRaw);
  repaired(water, waterRaw);
  auto overlapArea = [&](const GEOSGeometry* a, const GEOSGeometry* b) {
    if (GEOSIntersects_r(h, a, b) != 1) return 0.0;
    geos::GeomPtr i = ctx.own(GEOSIntersection_r(h, a, b), "intersection");
    return geosArea(ctx, i.get());
  };

  GeometryIndex paveIndex(ctx, paveRaw), blockIndex(ctx, blocksRaw), waterIndex(ctx, waterRaw);
  for (size_t i = 0; i < pave.size(); ++i) {
    report.pavementArea += geosArea(ctx, paveRaw[i]);
    for (int j : paveIndex.query(paveRaw[i]))
      if (static_cast<size_t>(j) > i) report.pavementOverlapArea += overlapArea(paveRaw[i], paveRaw[j]);
  }
  for (size_t i = 0; i < blocks.size(); ++i) {
    report.blockArea += geosArea(ctx, blocksRaw[i]);
    for (int j : paveIndex.query(blocksRaw[i]))
      report.blockPavementOverlapArea += overlapArea(blocksRaw[i], paveRaw[j]);
    for (int j : waterIndex.query(blocksRaw[i]))
      report.blockWaterOverlapArea += overlapArea(blocksRaw[i], waterRaw[j]);
    for (int j : blockIndex.query(blocksRaw[i]))
      if (static_cast<size_t>(j) > i) report.blockBlockOverlapArea += overlapArea(blocksRaw[i], blocksRaw[j]);
  }

  // Tiling of the perimeter by pavement, internal blocks and water.
  std::vector<geos::GeomPtr> roadLand;
  for (const GEOSGeometry* g : paveRaw) roadLand.push_back(ctx.own(GEOSGeom_clone_r(h, g), "clone"));
  for (const Polygon& p : internalPolys) {
    geos::GeomPtr g = ctx.polygon(p);
    if (GEOSisValid_r(h, g.get()) != 1) g = ctx.own(GEOSMakeValid_r(h, g.get()), "make valid");
    roadLand.push_back(std::move(g));
  }
  geos::GeomPtr roadLandAll = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(roadLand));
  geos::GeomPtr roadLandUnion = ctx.own(GEOSUnaryUnion_r(h, roadLandAll.get()), "union");
  MultiPolygon perimeter = input.perimeter;
  if (perimeter.empty())
    for (const Polygon& p : ctx.toPolygons(roadLandUnion.get())) perimeter.push_back(Polygon{p.outer, {}});
  geos::GeomPtr perimeterGeom = ctx.multiPolygon(perimeter);
  if (GEOSisValid_r(h, perimeterGeom.get()) != 1)
    perimeterGeom = ctx.own(GEOSMakeValid_r(h, perimeterGeom.get()), "make valid");
  perimeterGeom = ctx.own(GEOSUnaryUnion_r(h, perimeterGeom.get()), "union");
  report.perimeterArea = geosArea(ctx, perimeterGeom.get());
  std::vector<geos::GeomPtr> covered;
  covered.push_back(ctx.own(GEOSGeom_clone_r(h, roadLandUnion.get()), "clone"));
  for (const GEOSGeometry* g : waterRaw) covered.push_back(ctx.own(GEOSGeom_clone_r(h, g), "clone"));
  geos::GeomPtr coveredAll = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(covered));
  geos::GeomPtr coveredUnion = ctx.own(GEOSUnaryUnion_r(h, coveredAll.get()), "union");
  geos::GeomPtr gap = ctx.own(GEOSDifference_r(h, perimeterGeom.get(), coveredUnion.get()), "difference");
  report.tilingGapArea = geosArea(ctx, gap.get());
  geos::GeomPtr excess = ctx.own(GEOSDifference_r(h, roadLandUnion.get(), perimeterGeom.get()), "difference");
  report.tilingExcessArea = geosArea(ctx, excess.get());

  // Outline smoothness: share of vertices turning by 90° ± tolerance.
  const double tol = targets.squareTurnToleranceDegrees;
  auto countTurns = [&](const Ring& ring) {
    std::vector<Vec2> p;
    for (const Vec2& v : ring)
      if (p.empty() || distance(p.back(), v) > 1e-12) p.push_back(v);
    while (p.size() > 1 && distance(p.front(), p.back()) <= 1e-12) p.pop_back();
    if (p.size() < 3) return;
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec2 a = p[(i + p.size() - 1) % p.size()], b = p[i], c = p[(i + 1) % p.size()];
      const double turn = std::fabs(std::atan2(cross(b - a, c - b), dot(b - a, c - b))) * 180.0 / kPi;
      ++report.outlineVertices;
      if (std::fabs(turn - 90.0) <= tol) ++report.squareTurnVertices;
    }
  };
  for (const Polygon& p : blockPolys) {
    countTurns(p.outer);
    for (const Ring& r : p.holes) countTurns(r);
  }
  report.squareTurnShare =
      report.outlineVertices > 0 ? double(report.squareTurnVertices) / double(report.outlineVertices) : 0.0;

  // Truth blocks: IoU of the best-overlapping result block.
  if (input.truthBlocks) {
    const double minArea = targets.minTruthBlockCells * input.cellSize * input.cellSize;
    for (const Polygon& t : layerPolygons(input.truthBlocks)) {
      geos::GeomPtr tg = ctx.polygon(t);
      if (GEOSisValid_r(h, tg.get()) != 1) tg = ctx.own(GEOSMakeValid_r(h, tg.get()), "make valid");
      const double ta = geosArea(ctx, tg.get());
      if (ta < minArea) continue;
      ++report.truthBlocks;
      double best = 0.0;
      for (int j : blockIndex.query(tg.get())) {
        const double inter = overlapArea(tg.get(), blocksRaw[j]);
        const double uni = ta + geosArea(ctx, blocksRaw[j]) - inter;
        if (uni > 0.0) best = std::max(best, inter / uni);
      }
      if (best >= targets.truthIoU) ++report.truthBlocksMatched;
    }
    report.truthMatchShare =
        report.truthBlocks > 0 ? double(report.truthBlocksMatched) / report.truthBlocks : 1.0;
  } else {
    report.truthBlocks = -1;
  }
  report.failsafeShare = input.failsafeUses < 0      ? -1.0
                         : input.simulatedBlocks > 0 ? double(input.failsafeUses) / input.simulatedBlocks
                                                     : 0.0;
  return report;
}

std::vector<std::string> qualityFailures(const BlocksCheckReport& r, const BlocksQualityTargets& t) {
  std::vector<std::string> out;
  auto add = [&](const std::string& what, double value, double limit) {
    std::ostringstream s;
    s << what << " is " << value << ", the target is " << limit << ".";
    out.push_back(s.str());
  };
  if (r.invalidPolygons > 0) add("The number of invalid polygons", r.invalidPolygons, 0);
  const double paveShare = r.pavementArea > 0 ? r.pavementOverlapArea / r.pavementArea : 0.0;
  if (paveShare > t.maxPavementOverlapShare)
    add("The pavement overlap share", paveShare, t.maxPavementOverlapShare);
  const double blockShare =
      r.blockArea > 0
          ? (r.blockPavementOverlapArea + r.blockWaterOverlapArea + r.blockBlockOverlapArea) / r.blockArea
          : 0.0;
  if (blockShare > t.maxBlockOverlapShare) add("The block overlap share", blockShare, t.maxBlockOverlapShare);
  const double gapShare =
      r.perimeterArea > 0 ? (r.tilingGapArea + r.tilingExcessArea) / r.perimeterArea : 0.0;
  if (gapShare > t.maxTilingGapShare) add("The tiling gap share", gapShare, t.maxTilingGapShare);
  if (r.truthBlocks >= 0 && r.truthMatchShare < t.minTruthMatchShare)
    add("The share of truth blocks matched with IoU >= " + std::to_string(t.truthIoU), r.truthMatchShare,
        t.minTruthMatchShare);
  if (r.squareTurnShare > t.maxSquareTurnShare)
    add("The share of square outline turns", r.squareTurnShare, t.maxSquareTurnShare);
  if (r.failsafeShare > t.maxFailsafeShare)
    add("The failsafe matching share", r.failsafeShare, t.maxFailsafeShare);
  return out;
}

}  // namespace urbanvec::vectorize
