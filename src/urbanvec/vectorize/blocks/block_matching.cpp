// Stage D5, matching simulated blocks to vector blocks (shared/specs/sexton-vectorizer.md §3 D5,
// §11.4 check 27).
#include "urbanvec/vectorize/blocks/block_matching.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/blocks/water_split.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

BlockMatching matchSimulatedBlocks(const std::vector<Polygon>& vectorBlocks, const SimulatedCity& city,
                                   const Grid<int>& blockOfCell, const std::vector<int>& preMatched,
                                   const Progress& progress, const BlockMatchingOptions& options) {
  if (!preMatched.empty() && preMatched.size() != city.blocks.size())
    throw internalError("matchSimulatedBlocks: preMatched needs one entry per simulated block.");
  geos::Context ctx;
  std::vector<geos::GeomPtr> geoms;
  std::vector<const GEOSGeometry*> raw;
  std::vector<geos::GeomPtr> centroids;
  std::vector<const GEOSGeometry*> centroidRaw;
  for (const Polygon& p : vectorBlocks) {
    geoms.push_back(ctx.polygon(p));
    raw.push_back(geoms.back().get());
    centroids.push_back(ctx.own(GEOSGetCentroid_r(ctx.handle(), geoms.back().get()), "centroid"));
    centroidRaw.push_back(centroids.back().get());
  }
  GeometryIndex index(ctx, raw);
  // Nearest-centroid search for the failsafe.
  GEOSSTRtree* centroidTree = GEOSSTRtree_create_r(ctx.handle(), 10);
  struct TreeGuard {
    GEOSContextHandle_t h;
    GEOSSTRtree* t;
    ~TreeGuard() { GEOSSTRtree_destroy_r(h, t); }
  } treeGuard{ctx.handle(), centroidTree};
  std::map<const GEOSGeometry*, int> centroidIndex;
  for (size_t k = 0; k < centroids.size(); ++k) {
    GEOSSTRtree_insert_r(ctx.handle(), centroidTree, centroidRaw[k],
                         const_cast<GEOSGeometry*>(centroidRaw[k]));
    centroidIndex.emplace(centroidRaw[k], static_cast<int>(k));
  }
  geos::PreparedGeometries prepared(ctx, raw);

  auto locate = [&](const Vec2& p) {
    geos::GeomPtr pt = ctx.point(p);
    for (int v : index.query(pt.get())) {
      if (GEOSPreparedContains_r(ctx.handle(), prepared[v], pt.get()) == 1) return v;
    }
    return -1;
  };
  const int h = city.grid.height;
  // A window keeps the whole raster's frame (Grid::frameDx/frameDy, issue 22): positions are shifted
  // by `off` against the window's cells (exactly: integers).
  const Vec2 off = frameOffset(city.grid);
  const int x0Frame = city.grid.frameDx, topFrame = city.grid.frameDy + h;
  auto centreOf = [&](const GridCell& cell) { return cellCentre(cell, h) + off; };
  auto ownCell = [&](const Vec2& p, int b) {
    const GridCell c = cellAt(p - off, h);
    return blockOfCell.inside(c.col, c.row) && blockOfCell.at(c.col, c.row) == b;
  };
  std::map<int, size_t> parcelById;
  for (size_t i = 0; i < city.parcels.size(); ++i) parcelById.emplace(city.parcels[i].id, i);

  BlockMatching out;
  out.vectorBlockOfSim.assign(city.blocks.size(), -1);
  out.rule.assign(city.blocks.size(), MatchRule::None);
  ProgressTicker ticker(progress, "block matching", city.blocks.size());
  for (size_t bi = 0; bi < city.blocks.size(); ++bi) {
    ticker.tick();
    const int b = static_cast<int>(bi);
    const SimulatedBlock& block = city.blocks[bi];
    if (!preMatched.empty() && preMatched[bi] >= 0) {
      out.vectorBlockOfSim[bi] = preMatched[bi];
      out.rule[bi] = MatchRule::WaterSplit;
      ++out.matched;
      continue;
    }
    if (block.cells.empty() || vectorBlocks.empty()) continue;
    const Vec2 c = block.centre;
    // A deterministic, even sample of the block's cells, for the share and overlap rules.
    const size_t n = block.cells.size();
    const size_t counted = std::min(n, static_cast<size_t>(std::max(1, options.maxCellsCounted)));
    auto sampled = [&](size_t k) { return block.cells[k * n / counted]; };
    int v = -1;
    MatchRule rule = MatchRule::None;
    if (ownCell(c, b)) {
      v = locate(c);
      rule = MatchRule::Centre;
    }
    if (v < 0) {
      std::vector<std::pair<double, size_t>> parcels;
      for (int id : block.parcelIds) {
        auto it = parcelById.find(id);
        if (it != parcelById.end() && !city.parcels[it->second].cells.empty())
          parcels.emplace_back(distance(city.parcels[it->second].centre, c), it->second);
      }
      std::sort(parcels.begin(), parcels.end());
      for (const auto& [d, pi] : parcels) {
        const Vec2 pc = city.parcels[pi].centre;
        if (!ownCell(pc, b)) continue;
        v = locate(pc);
        if (v >= 0) break;
      }
      rule = MatchRule::ParcelCentre;
    }
    if (v >= 0 && options.minShareOfCells > 0.0 && block.cells.size() > 1) {
      // Where the sampled cells lie.
      std::map<int, size_t> cellsIn;
      for (size_t k = 0; k < counted; ++k) {
        const int w = locate(centreOf(sampled(k)));
        if (w >= 0) ++cellsIn[w];
      }
      const size_t picked = cellsIn.count(v) ? cellsIn[v] : 0;
      if (static_cast<double>(picked) < options.minShareOfCells * static_cast<double>(counted)) {
        int most = v;
        size_t mostCells = picked;
        for (const auto& [w, c] : cellsIn)
          if (c > mostCells) most = w, mostCells = c;
        if (most != v) {
          v = most;
          rule = MatchRule::Majority;
          ++out.majorityUses;
        }
      }
    }
    if (v < 0) {
      std::vector<std::pair<double, size_t>> cells;
      for (size_t k = 0; k < block.cells.size(); ++k)
        cells.emplace_back(distance(centreOf(block.cells[k]), c), k);
      std::sort(cells.begin(), cells.end());
      for (const auto& [d, k] : cells) {
        v = locate(centreOf(block.cells[k]));
        if (v >= 0) break;
      }
      rule = MatchRule::CellCentre;
    }
    if (v < 0 && options.matchByCellOverlap) {
      // No cell centre lies in a vector block; the land still overlapping one went there.
      // Each candidate is clipped once to the cells' box, so a cell meets a small piece, not a city.
      double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
      for (size_t k = 0; k < counted; ++k) {
        const GridCell cell = sampled(k);
        x0 = std::min(x0, static_cast<double>(x0Frame + cell.col));
        x1 = std::max(x1, x0Frame + cell.col + 1.0);
        y0 = std::min(y0, topFrame - cell.row - 1.0);
        y1 = std::max(y1, static_cast<double>(topFrame - cell.row));
      }
      geos::GeomPtr box = ctx.polygon({{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}, {}});
      double best = options.minOverlapArea;
      std::vector<int> candidates = index.query(box.get());
      std::sort(candidates.begin(), candidates.end());  // ties go to the lowest index
      for (int w : candidates) {
        GEOSGeometry* clipped = GEOSClipByRect_r(ctx.handle(), raw[w], x0, y0, x1, y1);
        if (!clipped) continue;  // GEOS could not clip this block: it takes no part in the rule
        geos::GeomPtr piece = ctx.own(clipped, "clip");
        double area = 0.0;
        for (size_t k = 0; k < counted; ++k) {
          const GridCell cell = sampled(k);
          const double cx = x0Frame + cell.col, cy = topFrame - cell.row - 1.0;
          GEOSGeometry* part = GEOSClipByRect_r(ctx.handle(), piece.get(), cx, cy, cx + 1, cy + 1);
          if (!part) continue;
          double a = 0.0;
          GEOSArea_r(ctx.handle(), part, &a);
          GEOSGeom_destroy_r(ctx.handle(), part);
          area += a;
        }
        if (area > best) v = w, best = area;
      }
      if (v >= 0) {
        rule = MatchRule::CellOverlap;
        ++out.overlapUses;
      }
    }
    if (v < 0 && options.leaveBlocksUnderPavement && block.parcelIds.empty()) {
      out.rule[bi] = MatchRule::UnderPavement;
      ++out.underPavement;
      continue;
    }
    if (v < 0) {
      geos::GeomPtr pt = ctx.point(c);
      const GEOSGeometry* nearest = GEOSSTRtree_nearest_r(ctx.handle(), centroidTree, pt.get());
      auto it = centroidIndex.find(nearest);
      if (it != centroidIndex.end()) v = it->second;
      rule = MatchRule::Failsafe;
      ++out.failsafeUses;
      if (!block.parcelIds.empty()) ++out.failsafeWithParcels;
    }
    out.vectorBlockOfSim[bi] = v;
    out.rule[bi] = rule;
    ++out.matched;
  }
  ticker.finish();
  return out;
}

}  // namespace urbanvec::vectorize
