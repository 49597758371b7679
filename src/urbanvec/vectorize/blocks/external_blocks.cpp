// Stages D3 + D4, external blocks (shared/specs/sexton-vectorizer.md §3 D3, D4, §11.4 check 26).
#include "urbanvec/vectorize/blocks/external_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "urbanvec/core/cell_regions.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/blocks/block_outline.hpp"
#include "urbanvec/vectorize/blocks/water_split.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"

namespace urbanvec::vectorize {

namespace {

/// Q8 smoothing of a boundary line: resample to `spacing`, then average every inner point with its
/// two neighbours `passes` times; the end points (where the line meets the road) stay put.
LineString smoothBoundaryLine(const LineString& line, int passes, double spacing) {
  if (passes <= 0 || line.size() < 3) return line;
  LineString dense = densified(line, spacing);
  for (int pass = 0; pass < passes; ++pass) {
    LineString next = dense;
    for (size_t i = 1; i + 1 < dense.size(); ++i) next[i] = (dense[i - 1] + dense[i] + dense[i + 1]) / 3.0;
    dense = std::move(next);
  }
  return dense;
}

}  // namespace

bool boundaryLineTrappedInside(const std::vector<bool>& inside, double insideNodeShare) {
  if (inside.empty() || !inside.front() || !inside.back()) return false;
  size_t count = 0;
  for (bool in : inside) count += in ? 1 : 0;
  return static_cast<double>(count) > insideNodeShare * static_cast<double>(inside.size());
}

ExternalBlocks buildExternalBlocks(const RoadNetwork& network, const MultiPolygon& perimeter,
                                   const SimulatedCity& city, const Grid<int>& blockOfCell,
                                   const ExternalBlocksOptions& options, const Progress& progress) {
  if (!(options.insideNodeShare >= 0.0 && options.insideNodeShare < 1.0))
    throw invalidOption("The inside node share must be in [0, 1), got " +
                        std::to_string(options.insideNodeShare) + ".");
  if (!(options.externalCellShare >= 0.0 && options.externalCellShare < 1.0))
    throw invalidOption("The external cell share must be in [0, 1), got " +
                        std::to_string(options.externalCellShare) + ".");
  if (options.boundarySmoothingPasses < 0 || !(options.boundaryResampleSpacing > 0.0))
    throw invalidOption("Boundary smoothing needs 0 or more passes and a positive spacing, got " +
                        std::to_string(options.boundarySmoothingPasses) + " passes and " +
                        std::to_string(options.boundaryResampleSpacing) + " cells.");
  geos::Context ctx;
  const double grid = options.precisionGrid;
  ExternalBlocks out;

  geos::GeomPtr city_ = ctx.multiPolygon(perimeter);
  const bool hasPerimeter = !perimeter.empty();
  geos::GeomPtr ring = ctx.own(GEOSBoundary_r(ctx.handle(), city_.get()), "boundary");
  // Prepared (indexed) geometries: a city's perimeter has as many vertices as its boundary lines have
  // points, so plain GEOS distance and overlay calls per point or per line would grow quadratically.
  geos::PreparedGeometries preparedCity(ctx, {ring.get()});
  const GEOSPreparedGeometry* preparedRing = preparedCity[0];

  // D3's inside tests, a prepared point-in-polygon and distance test per node of every boundary line,
  // and D4's face tests run on the workers: each prepares its own copy of the perimeter (GEOS prepares
  // lazily, so prepared geometries are not shared between threads).
  const GeosWorkers workers(options.threads);
  struct Perimeter {
    geos::GeomPtr city, ring;
    std::unique_ptr<geos::PreparedGeometries> prepared;
  };
  std::vector<Perimeter> copies(workers.size());
  for (Perimeter& copy : copies) {
    copy.city = ctx.own(GEOSGeom_clone_r(ctx.handle(), city_.get()), "clone");
    copy.ring = ctx.own(GEOSGeom_clone_r(ctx.handle(), ring.get()), "clone");
  }
  // Worker w's prepared perimeter (0) and, during D3, ring (1), prepared on its first use.
  auto preparedOf = [&](size_t w, const geos::Context& context) -> geos::PreparedGeometries& {
    Perimeter& copy = copies[w];
    if (!copy.prepared) {
      std::vector<const GEOSGeometry*> parts{copy.city.get()};
      if (copy.ring) parts.push_back(copy.ring.get());
      copy.prepared = std::make_unique<geos::PreparedGeometries>(context, parts);
    }
    return *copy.prepared;
  };
  std::vector<std::vector<bool>> insideOf(network.segments.size());
  const Progress lines = subProgress(progress, 0.0, 0.6);
  ProgressTicker ticker(lines, "external blocks", network.segments.size());
  workers.run(
      network.segments.size(),
      [&](size_t s, size_t w, const geos::Context& context) {
        const NetworkSegment& seg = network.segments[s];
        if (seg.roadClass != RoadClass::Perimeter || seg.points.size() < 2) return;
        geos::PreparedGeometries& copy = preparedOf(w, context);
        const LineString nodes =
            options.insideShareSpacing > 0.0 ? densified(seg.points, options.insideShareSpacing) : seg.points;
        for (const Vec2& p : nodes) {
          bool inside = false;
          if (hasPerimeter) {
            geos::GeomPtr pt = context.point(p);
            // Context::withinDistance, not GEOSPreparedDistanceWithin: GEOS 3.11 answers the latter
            // for a prepared line by DistanceOp over every segment of the ring, quadratic in the city.
            inside = GEOSPreparedContains_r(context.handle(), copy[0], pt.get()) == 1 &&
                     !context.withinDistance(copy[1], pt.get(), options.insideTolerance);
          }
          insideOf[s].push_back(inside);
        }
      },
      [&](size_t done) { ticker.tick(done); });
  ticker.finish();
  // The ring copies and their prepared forms (GEOS's facet index behind Context::withinDistance) are
  // not needed past D3: freed before the noding, where the stage's memory peaks.
  for (Perimeter& copy : copies) copy.prepared.reset(), copy.ring.reset();

  std::vector<int> perimeterLinesAtNode(network.nodes.size(), 0);
  for (const NetworkSegment& seg : network.segments)
    if (seg.roadClass == RoadClass::Perimeter) {
      if (seg.fromNode >= 0 && static_cast<size_t>(seg.fromNode) < network.nodes.size())
        ++perimeterLinesAtNode[seg.fromNode];
      if (seg.toNode >= 0 && static_cast<size_t>(seg.toNode) < network.nodes.size())
        ++perimeterLinesAtNode[seg.toNode];
    }

  std::vector<geos::GeomPtr> linework;
  if (hasPerimeter) linework.push_back(ctx.own(GEOSGeom_clone_r(ctx.handle(), ring.get()), "clone"));
  for (size_t s = 0; s < network.segments.size(); ++s) {
    const NetworkSegment& seg = network.segments[s];
    if (seg.roadClass != RoadClass::Perimeter || seg.points.size() < 2) continue;
    ++out.boundaryLines;
    const std::vector<bool>& inside = insideOf[s];
    if (boundaryLineTrappedInside(inside, options.insideNodeShare)) {
      ++out.deletedLines;
      continue;
    }
    // The part of the line inside the road perimeter is not cut away here (an overlay with the whole
    // perimeter per line): it only bounds faces inside the perimeter, which are dropped below.
    geos::GeomPtr line = ctx.lineString(
        smoothBoundaryLine(seg.points, options.boundarySmoothingPasses, options.boundaryResampleSpacing));
    line = ctx.own(GEOSGeom_setPrecision_r(ctx.handle(), line.get(), grid, 0), "set precision");
    linework.push_back(std::move(line));
    // A line end left in the open is reconnected to the nearest point of the road perimeter (D4 step 1),
    // unless another boundary line continues from it.
    if (!hasPerimeter) continue;
    const std::pair<int, Vec2> ends[2] = {{seg.fromNode, seg.points.front()},
                                          {seg.toNode, seg.points.back()}};
    for (size_t e = 0; e < 2; ++e) {
      const auto& [node, p] = ends[e];
      const bool continued =
          node >= 0 && static_cast<size_t>(node) < network.nodes.size() && perimeterLinesAtNode[node] > 1;
      if (continued || inside[e == 0 ? 0 : inside.size() - 1]) continue;
      geos::GeomPtr pt = ctx.point(p);
      GEOSCoordSequence* nearest = GEOSPreparedNearestPoints_r(ctx.handle(), preparedRing, pt.get());
      if (!nearest) continue;
      Vec2 q;
      GEOSCoordSeq_getXY_r(ctx.handle(), nearest, 0, &q.x, &q.y);
      GEOSCoordSeq_destroy_r(ctx.handle(), nearest);
      if (distance(p, q) > options.insideTolerance) linework.push_back(ctx.lineString({p, q}));
    }
  }

  if (linework.empty()) {
    // No road and no boundary line (a grid of developed land without roads): the islands are the
    // only external blocks.
    if (options.islandBlocks) addIslandBlocks(ctx, city, blockOfCell, options, out);
    reportProgress(progress, 1.0, "external blocks");
    return out;
  }
  geos::GeomPtr noded = unionOnGrid(ctx, std::move(linework), grid);
  const GEOSGeometry* nodedRaw = noded.get();
  geos::GeomPtr faces = ctx.own(GEOSPolygonize_r(ctx.handle(), &nodedRaw, 1), "polygonize");
  reportProgress(progress, 0.7, "external blocks");
  // Each face is classified on its own (its point on surface against the perimeter, then its cell
  // tally), on the workers; the kept faces go out in face order.
  std::vector<Polygon> faceList = ctx.toPolygons(faces.get());
  enum class Face : char { InsidePerimeter, Dropped, Kept };
  std::vector<Face> verdict(faceList.size(), Face::InsidePerimeter);
  workers.run(faceList.size(), [&](size_t f, size_t w, const geos::Context& context) {
    Polygon& face = faceList[f];
    if (hasPerimeter) {
      geos::GeomPtr g = context.polygon(face);
      geos::GeomPtr probe = context.own(GEOSPointOnSurface_r(context.handle(), g.get()), "point on surface");
      if (GEOSPreparedContains_r(context.handle(), preparedOf(w, context)[0], probe.get()) == 1) return;
    }
    const CellTally tally = tallyCells(face, blockOfCell, city.grid);
    int externalCells = 0;
    for (const auto& [block, cells] : tally.blocks)
      if (!city.blocks[block].internal) externalCells += cells;
    const int land = tally.cells - tally.road - tally.water;
    verdict[f] =
        externalCells > 0 && externalCells > options.externalCellShare * land ? Face::Kept : Face::Dropped;
    if (verdict[f] == Face::Kept) orientClockwise(face);
  });
  for (size_t f = 0; f < faceList.size(); ++f) {
    if (verdict[f] == Face::Kept) out.blocks.push_back(std::move(faceList[f]));
    out.droppedFaces += verdict[f] == Face::Dropped ? 1 : 0;
  }
  if (options.islandBlocks) addIslandBlocks(ctx, city, blockOfCell, options, out);
  reportProgress(progress, 1.0, "external blocks");
  return out;
}

void addIslandBlocks(const geos::Context& ctx, const SimulatedCity& city, const Grid<int>& blockOfCell,
                     const ExternalBlocksOptions& options, ExternalBlocks& out) {
  const Grid<LandUse>& grid = city.grid;
  const int h = grid.height;
  auto undeveloped = [&](int c, int r) {
    if (!grid.inside(c, r)) return true;
    const LandUse u = grid.at(c, r);
    return u == LandUse::Unused || (options.undeveloped.waterIsUndeveloped && u == LandUse::Water) ||
           (options.undeveloped.reservedIsUndeveloped && u == LandUse::Reserved && blockOfCell.at(c, r) < 0);
  };
  std::vector<geos::GeomPtr> kept;
  std::vector<const GEOSGeometry*> keptRaw;
  for (const Polygon& block : out.blocks) {
    kept.push_back(ctx.polygon(block));
    keptRaw.push_back(kept.back().get());
  }
  const GeometryIndex keptIndex(ctx, keptRaw);
  geos::PreparedGeometries preparedKept(ctx, keptRaw);
  // A face D4 kept may already hold part of the island (a pier in a harbour inside an external
  // block, or land next to a removed road patch, which A4.8 does not count as undeveloped).
  auto covered = [&](const GEOSGeometry* island) {
    for (int k : keptIndex.query(island))
      if (GEOSPreparedIntersects_r(ctx.handle(), preparedKept[k], island) == 1) return true;
    return false;
  };
  for (size_t b = 0; b < city.blocks.size(); ++b) {
    const SimulatedBlock& block = city.blocks[b];
    if (block.internal || block.cells.empty()) continue;
    bool island = true;
    // Its A4.8 edges close on themselves exactly when every 4-neighbour outside it is undeveloped.
    const int dc[4] = {0, 1, 0, -1}, dr[4] = {-1, 0, 1, 0};
    for (size_t k = 0; k < block.cells.size() && island; ++k)
      for (int d = 0; d < 4 && island; ++d) {
        const int c = block.cells[k].col + dc[d], r = block.cells[k].row + dr[d];
        if (blockOfCell.inside(c, r) && blockOfCell.at(c, r) == static_cast<int>(b)) continue;
        island = undeveloped(c, r);
      }
    if (!island) continue;
    // The block's cells traced along their edges (core/cell_regions) on a mask over its bounding box,
    // framed so that its cells keep the whole raster's coordinates (Grid::frameDx/frameDy, issue 22).
    int c0 = block.cells.front().col, c1 = c0, r0 = block.cells.front().row, r1 = r0;
    for (const GridCell& cell : block.cells) {
      c0 = std::min(c0, cell.col), c1 = std::max(c1, cell.col);
      r0 = std::min(r0, cell.row), r1 = std::max(r1, cell.row);
    }
    Grid<std::uint8_t> mask(c1 - c0 + 1, r1 - r0 + 1, 0);
    mask.frameDx = grid.frameDx + c0;
    mask.frameDy = grid.frameDy + h - r0 - mask.height;
    for (const GridCell& cell : block.cells) mask.at(cell.col - c0, cell.row - r0) = 1;
    const MultiPolygon regions = cellRegions(mask);
    if (covered(ctx.multiPolygon(regions).get())) continue;
    for (const Polygon& part : regions) {
      auto smoothed = [&](const Ring& ring) {
        return options.boundarySmoothingPasses > 0
                   ? smoothClosedRing(ring, options.boundarySmoothingPasses, options.boundaryResampleSpacing)
                   : ring;
      };
      Polygon smooth{smoothed(part.outer), {}};
      for (const Ring& hole : part.holes) smooth.holes.push_back(smoothed(hole));
      geos::GeomPtr valid = ctx.own(GEOSMakeValid_r(ctx.handle(), ctx.polygon(smooth).get()), "make valid");
      for (Polygon& piece : ctx.toPolygons(valid.get())) {
        if (area(piece) <= 0.0) continue;
        orientClockwise(piece);
        out.blocks.push_back(std::move(piece));
        ++out.islands;
      }
    }
  }
}

}  // namespace urbanvec::vectorize
