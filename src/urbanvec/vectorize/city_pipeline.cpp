#include "urbanvec/vectorize/city_pipeline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/memory.hpp"
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

/// An axis-aligned box, compared as GEOS compares envelopes (closed intervals).
struct Box {
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  explicit Box(const Ring& ring) {
    for (const Vec2& p : ring) {
      minX = std::min(minX, p.x);
      minY = std::min(minY, p.y);
      maxX = std::max(maxX, p.x);
      maxY = std::max(maxY, p.y);
    }
  }
  Box(double x0, double y0, double x1, double y1) : minX(x0), minY(y0), maxX(x1), maxY(y1) {}
  Box grown(double d) const { return {minX - d, minY - d, maxX + d, maxY + d}; }
  bool intersects(const Box& o) const {
    return !(o.minX > maxX || o.maxX < minX || o.minY > maxY || o.maxY < minY);
  }
};

/// Boxes bucketed on a uniform grid: the pieces whose box meets a query box, in index order.
class BoxIndex {
 public:
  explicit BoxIndex(const std::vector<Box>& boxes) : boxes_(boxes), extent_(0, 0, 0, 0) {
    if (boxes.empty()) return;
    extent_ = boxes.front();
    for (const Box& b : boxes)
      extent_ = {std::min(extent_.minX, b.minX), std::min(extent_.minY, b.minY),
                 std::max(extent_.maxX, b.maxX), std::max(extent_.maxY, b.maxY)};
    const double w = extent_.maxX - extent_.minX, h = extent_.maxY - extent_.minY;
    // About one box per bucket on average, and never many more buckets than boxes.
    const double count = static_cast<double>(boxes.size());
    cell_ = std::max(std::sqrt(w * h / count), 1e-9);
    while ((w / cell_ + 1.0) * (h / cell_ + 1.0) > 4.0 * count + 16.0) cell_ *= 1.5;
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    buckets_.resize(static_cast<size_t>(nx_) * static_cast<size_t>(ny_));
    for (size_t i = 0; i < boxes.size(); ++i) {
      const auto [x0, y0, x1, y1] = range(boxes[i]);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          buckets_[static_cast<size_t>(y) * nx_ + x].push_back(static_cast<int>(i));
    }
  }
  /// Indices of the boxes meeting `q`, increasing; `seen` is scratch space of the caller's thread.
  void query(const Box& q, std::vector<int>& out, std::vector<int>& seen, int stamp) const {
    out.clear();
    if (boxes_.empty() || !q.intersects(extent_)) return;
    seen.resize(boxes_.size(), -1);
    const auto [x0, y0, x1, y1] = range(q);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int i : buckets_[static_cast<size_t>(y) * nx_ + x])
          if (seen[i] != stamp && boxes_[i].intersects(q)) {
            seen[i] = stamp;
            out.push_back(i);
          }
    std::sort(out.begin(), out.end());
  }

 private:
  std::array<int, 4> range(const Box& b) const {
    auto clampX = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v - extent_.minX) / cell_)), 0, nx_ - 1);
    };
    auto clampY = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v - extent_.minY) / cell_)), 0, ny_ - 1);
    };
    return {clampX(b.minX), clampY(b.minY), clampX(b.maxX), clampY(b.maxY)};
  }
  const std::vector<Box>& boxes_;
  Box extent_;
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> buckets_;
};

/// The parts of each block's outline that run along pavement: the road frontage E2 measures. Per
/// block, the pavement pieces near it (envelope within the envelope of the block buffered by ten
/// tolerances, and the piece itself within ten tolerances of the block) are buffered together by the
/// tolerance and cut with the outline. Blocks are independent, so they run on `threads` workers; a
/// bucket index finds the candidate pieces, and the block's buffer is only computed for the rare
/// piece whose box ends in the margin where that envelope and the block's bounding box grown by ten
/// tolerances may disagree.
std::vector<MultiLineString> roadFacingEdges(const BlocksResult& blocks, const Frame& frame, double tolerance,
                                             int threads) {
  geos::Context ctx;
  std::vector<geos::GeomPtr> pavement;
  std::vector<Box> boxes;
  std::vector<Ring> outlines;  // each piece's outer ring, for the shared-corner test below
  for (const Feature& f : blocks.pavement.features) {
    MultiPolygon parts;
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) parts.push_back(*p);
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry)) parts = *mp;
    for (const Polygon& p : parts) {
      Polygon cells = frame.toCells(p);
      boxes.emplace_back(cells.outer);
      pavement.push_back(ctx.polygon(cells));
      outlines.push_back(std::move(cells.outer));
    }
  }
  const BoxIndex index(boxes);
  const size_t n = blocks.blockInfo.size();
  std::vector<MultiLineString> out(n);
  const GeosWorkers workers(threads);
  std::vector<std::vector<int>> seen(workers.size());
  std::vector<std::vector<int>> candidates(workers.size());
  std::vector<std::vector<int>> nears(workers.size());
  std::vector<std::vector<Vec2>> corners(workers.size());
  workers.run(n, [&](size_t i, size_t w, const geos::Context& c) {
    GEOSContextHandle_t h = c.handle();
    const BlockInfo& info = blocks.blockInfo[i];
    const Box bounds(info.shape.outer);
    // GEOS's buffer with one segment per quadrant keeps within 10·tol of the block and reaches at
    // least cos(45°)·10·tol beyond every extreme vertex; 5 and 11 tolerances leave room for rounding.
    const Box sure = bounds.grown(5.0 * tolerance);
    index.query(bounds.grown(11.0 * tolerance), candidates[w], seen[w], static_cast<int>(i));
    geos::GeomPtr block = c.polygon(info.shape);
    std::optional<Box> envelope;
    std::vector<int>& near = nears[w];
    near.clear();
    for (int k : candidates[w]) {
      if (!boxes[k].intersects(sure)) {
        if (!envelope) {
          geos::GeomPtr buffered = c.own(GEOSBuffer_r(h, block.get(), tolerance * 10, 1), "block envelope");
          double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
          GEOSGeom_getXMin_r(h, buffered.get(), &x0);
          GEOSGeom_getYMin_r(h, buffered.get(), &y0);
          GEOSGeom_getXMax_r(h, buffered.get(), &x1);
          GEOSGeom_getYMax_r(h, buffered.get(), &y1);
          envelope = Box(x0, y0, x1, y1);
        }
        if (!boxes[k].intersects(*envelope)) continue;
      }
      near.push_back(k);
    }
    // Only pieces within ten tolerances of the block can reach its outline with a band one tolerance
    // wide; the rest only made the band's buffer costlier.
    // A piece with a corner on a corner of the block is at distance 0: most of them, since the block's
    // outline is made of the pieces' edges. Only the others need GEOS's distance test.
    if (!near.empty()) {
      std::vector<Vec2>& blockCorners = corners[w];
      blockCorners.assign(info.shape.outer.begin(), info.shape.outer.end());
      for (const Ring& hole : info.shape.holes)
        blockCorners.insert(blockCorners.end(), hole.begin(), hole.end());
      std::sort(blockCorners.begin(), blockCorners.end(), lexicographicLess);
      auto sharesACorner = [&](int k) {
        for (const Vec2& p : outlines[static_cast<size_t>(k)])
          if (std::binary_search(blockCorners.begin(), blockCorners.end(), p, lexicographicLess)) return true;
        return false;
      };
      const GEOSPreparedGeometry* prepared = nullptr;
      size_t kept = 0;
      for (int k : near) {
        bool within = sharesACorner(k);
        if (!within) {
          if (!prepared) prepared = GEOSPrepare_r(h, block.get());
          if (!prepared) throw internalError("GEOS failed to prepare a block: " + c.lastError());
          // Indexed on the block's segments: GEOSPreparedDistanceWithin compares every pair.
          within = c.withinDistance(prepared, pavement[static_cast<size_t>(k)].get(), 10.0 * tolerance);
        }
        if (within) near[kept++] = k;
      }
      near.resize(kept);
      if (prepared) GEOSPreparedGeom_destroy_r(h, prepared);
    }
    if (near.empty()) return;
    std::vector<geos::GeomPtr> parts;
    for (int k : near)
      parts.push_back(c.own(GEOSGeom_clone_r(h, pavement[static_cast<size_t>(k)].get()), "clone"));
    geos::GeomPtr local = c.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
    geos::GeomPtr band = c.own(GEOSBuffer_r(h, local.get(), tolerance, 2), "pavement band");
    geos::GeomPtr outline = c.own(GEOSBoundary_r(h, block.get()), "block outline");
    geos::GeomPtr facing = c.own(GEOSIntersection_r(h, outline.get(), band.get()), "road-facing edges");
    geos::GeomPtr merged = c.own(GEOSLineMerge_r(h, facing.get()), "road-facing merge");
    out[i] = c.toLines(merged.get());
  });
  return out;
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
                         const GridSpec& grid, const CityOptions& options, const Progress& progress) {
  CityResult result;
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
  result.layers.reserve(6);
  result.layers.push_back(std::move(result.blocks.pavement));
  result.layers.push_back(std::move(result.blocks.blocks));
  result.layers.push_back(std::move(result.blocks.water));
  result.layers.push_back(std::move(spines));
  result.layers.push_back(std::move(parcelLayer));
  result.layers.push_back(std::move(report));
  reportProgress(progress, 1.0, "city layers");
  return result;
}

}  // namespace urbanvec::vectorize
