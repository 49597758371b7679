// Stage D2, "Water splitting" (shared/specs/sexton-vectorizer.md §3 D2, §11.4 check 25).
#include "urbanvec/vectorize/blocks/water_split.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <string>

#include "urbanvec/core/cell_regions.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/blocks/block_outline.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"

namespace urbanvec::vectorize {

namespace {

/// A water outline vertex stays put where the water chain inside simulated land ends: on the grid
/// border or against a road cell (spec D2 "endpoints fixed where the chain ends"). Without this the
/// averaging would pull water away from the curbs and leave land bridges that stop the split.
bool chainEnd(const Vec2& p, const Grid<LandUse>& landUse) {
  // A window keeps the whole raster's frame (Grid::frameDx/frameDy, issue 22).
  const int x0 = landUse.frameDx, y0 = landUse.frameDy;
  const int w = x0 + landUse.width, h = y0 + landUse.height;
  if (p.x <= x0 || p.y <= y0 || p.x >= w || p.y >= h) return true;
  constexpr double kTouch = 1e-9;
  for (double dx : {-kTouch, kTouch})
    for (double dy : {-kTouch, kTouch}) {
      const int col = static_cast<int>(std::floor(p.x + dx)) - x0;
      const int row = h - 1 - static_cast<int>(std::floor(p.y + dy));
      if (isRoad(landUse.get(col, row, LandUse::Unused))) return true;
    }
  return false;
}

}  // namespace

Ring smoothClosedRing(const Ring& ring, int passes, double spacing,
                      const std::function<bool(const Vec2&)>& fixedVertex) {
  Ring open = densified(ring, spacing);
  if (!open.empty()) open.pop_back();  // the closing point is implied while averaging
  const size_t n = open.size();
  if (n < 4) {
    if (!open.empty()) open.push_back(open.front());
    return open;
  }
  std::vector<bool> fixed(n, false);
  if (fixedVertex)
    for (size_t i = 0; i < n; ++i) fixed[i] = fixedVertex(open[i]);
  for (int pass = 0; pass < passes; ++pass) {
    Ring next(n);
    for (size_t i = 0; i < n; ++i)
      next[i] = fixed[i] ? open[i] : (open[(i + n - 1) % n] + open[i] + open[(i + 1) % n]) / 3.0;
    open = std::move(next);
  }
  open.push_back(open.front());
  return open;
}

Grid<int> simulatedBlockOfCells(const SimulatedCity& city) {
  Grid<int> owner(city.grid.width, city.grid.height, -1);
  for (size_t b = 0; b < city.blocks.size(); ++b)
    for (const GridCell& c : city.blocks[b].cells) {
      if (!owner.inside(c.col, c.row))
        throw invalidInput("Simulated block " + std::to_string(city.blocks[b].id) + " has cell (" +
                           std::to_string(c.col) + ", " + std::to_string(c.row) + ") outside the " +
                           std::to_string(owner.width) + " x " + std::to_string(owner.height) + " grid.");
      owner.at(c.col, c.row) = static_cast<int>(b);
    }
  return owner;
}

GridCell cellAt(const Vec2& p, int gridHeight) {
  return {static_cast<std::int32_t>(std::floor(p.x)),
          static_cast<std::int32_t>(gridHeight - 1 - std::floor(p.y))};
}

Vec2 cellCentre(const GridCell& cell, int gridHeight) {
  return {cell.col + 0.5, gridHeight - cell.row - 0.5};
}

CellTally tallyCells(const Polygon& polygon, const Grid<int>& blockOfCell, const Grid<LandUse>& landUse) {
  CellTally tally;
  double minY = 1e300, maxY = -1e300;
  for (const Vec2& p : polygon.outer) {
    minY = std::min(minY, p.y);
    maxY = std::max(maxY, p.y);
  }
  const int dx = landUse.frameDx, h = landUse.frameDy + landUse.height;  // a window's frame (issue 22)
  const int rowFirst = std::max(0, static_cast<int>(std::floor(h - 0.5 - maxY)));
  const int rowLast = std::min(landUse.height - 1, static_cast<int>(std::ceil(h - 0.5 - minY)));
  if (rowFirst > rowLast) return tally;
  // The scanline of a row (its cell centres, y = h - row - 0.5) crosses an edge a-b where a and b lie on
  // either side of it. Each edge visits only the rows its y range spans (one row of slack either way
  // for rounding; the exact test decides), and the crossings are bucketed by row, counted first and
  // filled second: a polygon costs its edges plus its crossings, not its rows times its edges (a large
  // face of a 4096² grid has thousands of rows and a hundred thousand edges).
  const size_t rows = static_cast<size_t>(rowLast - rowFirst) + 1;
  auto forEachCrossing = [&](auto&& fn) {
    auto ring = [&](const Ring& r) {
      for (size_t i = 0; i + 1 < r.size(); ++i) {
        const Vec2& a = r[i];
        const Vec2& b = r[i + 1];
        if (a.y == b.y) continue;  // never on either side of a scanline
        const double from = std::max(rowFirst - 1.0, std::floor(h - 0.5 - std::max(a.y, b.y)) - 1.0);
        const double to = std::min(rowLast + 1.0, std::ceil(h - 0.5 - std::min(a.y, b.y)) + 1.0);
        for (int row = std::max(rowFirst, static_cast<int>(from));
             row <= std::min(rowLast, static_cast<int>(to)); ++row) {
          const double y = h - row - 0.5;
          if ((a.y <= y) != (b.y <= y))
            fn(static_cast<size_t>(row - rowFirst), a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
        }
      }
    };
    ring(polygon.outer);
    for (const Ring& hole : polygon.holes) ring(hole);
  };
  std::vector<size_t> start(rows + 1, 0);
  forEachCrossing([&](size_t k, double) { ++start[k + 1]; });
  for (size_t k = 0; k < rows; ++k) start[k + 1] += start[k];
  std::vector<double> xs(start[rows]);
  std::vector<size_t> next(start.begin(), start.end() - 1);
  forEachCrossing([&](size_t k, double x) { xs[next[k]++] = x; });

  std::map<int, int> counts;
  int runBlock = -1, runCells = 0;  // consecutive cells of one block go to the map at once
  for (size_t k = 0; k < rows; ++k) {
    const int row = rowFirst + static_cast<int>(k);
    std::sort(xs.begin() + static_cast<std::ptrdiff_t>(start[k]),
              xs.begin() + static_cast<std::ptrdiff_t>(start[k + 1]));
    for (size_t c = start[k]; c + 1 < start[k + 1]; c += 2) {
      const int colFirst = std::max(0, static_cast<int>(std::ceil(xs[c] - 0.5)) - dx);
      const int colLast = std::min(landUse.width - 1, static_cast<int>(std::ceil(xs[c + 1] - 0.5)) - 1 - dx);
      for (int col = colFirst; col <= colLast; ++col) {
        ++tally.cells;
        const LandUse use = landUse.at(col, row);
        if (isRoad(use)) ++tally.road;
        if (use == LandUse::Water) ++tally.water;
        const int b = blockOfCell.at(col, row);
        if (b < 0) continue;
        if (b != runBlock) {
          if (runBlock >= 0) counts[runBlock] += runCells;
          runBlock = b, runCells = 0;
        }
        ++runCells;
      }
    }
  }
  if (runBlock >= 0) counts[runBlock] += runCells;
  for (const auto& [block, cells] : counts) tally.blocks.emplace_back(block, cells);
  std::stable_sort(tally.blocks.begin(), tally.blocks.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return tally;
}

MultiPolygon waterPolygons(const Grid<LandUse>& landUse, const WaterSplitOptions& options,
                           const Progress& progress) {
  if (options.smoothingPasses < 0)
    throw invalidOption("Water smoothing passes must be 0 or more, got " +
                        std::to_string(options.smoothingPasses) + ".");
  if (!(options.resampleSpacing > 0.0))
    throw invalidOption("The water resample spacing must be positive, got " +
                        std::to_string(options.resampleSpacing) + " cells.");
  reportProgress(progress, 0.0, "water");
  geos::Context ctx;
  // The water cells' regions traced along the cell edges: linear in the grid, where a union of the
  // cells' row runs on the precision grid cost an overlay per pair of runs (issue 21).
  Grid<std::uint8_t> isWater(landUse.width, landUse.height, 0);
  isWater.frameDx = landUse.frameDx;  // a window's frame (issue 22)
  isWater.frameDy = landUse.frameDy;
  bool any = false;
  for (size_t i = 0; i < landUse.cells.size(); ++i)
    if (landUse.cells[i] == LandUse::Water) isWater.cells[i] = 1, any = true;
  if (!any) {
    reportProgress(progress, 1.0, "water");
    return {};
  }
  const MultiPolygon cells = cellRegions(isWater);
  reportProgress(progress, 0.5, "water");
  std::vector<geos::GeomPtr> smoothed;
  for (const Polygon& p : cells) {
    Polygon s;
    auto chainEndOnGrid = [&](const Vec2& v) { return chainEnd(v, landUse); };
    s.outer = smoothClosedRing(p.outer, options.smoothingPasses, options.resampleSpacing, chainEndOnGrid);
    for (const Ring& hole : p.holes)
      s.holes.push_back(
          smoothClosedRing(hole, options.smoothingPasses, options.resampleSpacing, chainEndOnGrid));
    geos::GeomPtr g = ctx.polygon(s);
    // Averaging can pinch narrow channels into self-touching rings; make them valid.
    if (GEOSisValid_r(ctx.handle(), g.get()) != 1)
      g = ctx.own(GEOSMakeValid_r(ctx.handle(), g.get()), "make valid");
    smoothed.push_back(std::move(g));
  }
  geos::GeomPtr water = floatingUnion(ctx, std::move(smoothed), options.precisionGrid);
  MultiPolygon out = ctx.toPolygons(water.get());
  for (Polygon& p : out) orientClockwise(p);
  reportProgress(progress, 1.0, "water");
  return out;
}

WaterSplit splitBlocksByWater(const std::vector<Polygon>& blocks, const std::vector<bool>& internal,
                              const MultiPolygon& water, const SimulatedCity& city,
                              const Grid<int>& blockOfCell, const WaterSplitOptions& options,
                              const Progress& progress) {
  if (internal.size() != blocks.size())
    throw internalError("splitBlocksByWater: one internal flag per block is needed.");
  geos::Context ctx;
  const double grid = options.precisionGrid;
  std::vector<geos::GeomPtr> waterGeoms;
  std::vector<const GEOSGeometry*> waterRaw;
  for (const Polygon& w : water) {
    waterGeoms.push_back(ctx.polygon(w));
    waterRaw.push_back(waterGeoms.back().get());
  }
  GeometryIndex index(ctx, waterRaw);
  // Which water polygons each block meets, on this thread (the index, `ctx` and the prepared water are
  // not shared). A sea is one polygon with a vertex per shore cell that hundreds of blocks touch: the
  // prepared (indexed) test keeps that linear where a plain GEOSIntersects per pair is quadratic.
  geos::PreparedGeometries preparedWater(ctx, waterRaw);
  std::vector<geos::GeomPtr> blockGeoms(blocks.size());
  std::vector<std::vector<int>> hitsOf(blocks.size());
  for (size_t b = 0; b < blocks.size(); ++b) {
    blockGeoms[b] = ctx.polygon(blocks[b]);
    for (int w : index.query(blockGeoms[b].get()))
      if (GEOSPreparedIntersects_r(ctx.handle(), preparedWater[w], blockGeoms[b].get()) == 1)
        hitsOf[b].push_back(w);
  }
  // The overlays of the blocks that meet water are independent: split them across threads, each block
  // writing only its own slot, then gather the slots in block order so the output does not depend on
  // the thread count.
  struct Pieces {
    std::vector<WaterSplitBlock> blocks;
    MultiPolygon shoreScraps;
  };
  std::vector<Pieces> pieces(blocks.size());
  const GeosWorkers workers(options.threads);
  ProgressTicker ticker(progress, "water splitting", blocks.size());
  workers.run(
      blocks.size(),
      [&](size_t b, size_t, const geos::Context& c) {
        Pieces& slot = pieces[b];
        if (hitsOf[b].empty()) {
          slot.blocks.push_back({blocks[b], internal[b], -1});
          return;
        }
        std::vector<geos::GeomPtr> hits;
        for (int w : hitsOf[b])
          hits.push_back(c.own(GEOSGeom_clone_r(c.handle(), waterGeoms[w].get()), "clone"));
        geos::GeomPtr cut = floatingUnion(c, std::move(hits), grid);
        geos::GeomPtr rest = floatingDifference(c, blockGeoms[b].get(), cut.get(), grid);
        for (Polygon& piece : c.toPolygons(rest.get())) {
          if (!(area(piece) >= grid)) continue;  // precision crumbs
          orientClockwise(piece);
          const CellTally tally = tallyCells(piece, blockOfCell, city.grid);
          if (tally.majorityBlock() < 0) {
            slot.shoreScraps.push_back(std::move(piece));
          } else {
            slot.blocks.push_back({std::move(piece), internal[b], tally.majorityBlock()});
          }
        }
      },
      [&](size_t done) { ticker.tick(done); });
  WaterSplit out;
  for (size_t b = 0; b < blocks.size(); ++b) {
    out.blocksSplit += !hitsOf[b].empty();
    for (WaterSplitBlock& piece : pieces[b].blocks) out.blocks.push_back(std::move(piece));
    for (Polygon& scrap : pieces[b].shoreScraps) out.shoreScraps.push_back(std::move(scrap));
  }
  ticker.finish();
  return out;
}

}  // namespace urbanvec::vectorize
