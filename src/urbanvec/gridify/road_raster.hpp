// Road rasterization with the width and connectivity rules the vectorizer relies on (issue 2 §2,
// CONVENTIONS.md "Gridded input": secondary roads exactly 1 cell wide, primary exactly 2, both
// 4-connected). docs/gridify.md "Roads" states the rules and the width check.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::gridify {

/// A cell (col, row).
using Cell = std::pair<int, int>;

/// The cells a segment passes through, in order, 4-connected (where the segment crosses a cell corner
/// exactly, the row step is taken first). `a` and `b` are in pixel coordinates: cell (c, r) spans
/// [c, c+1) × [r, r+1). Appends to `out`, not repeating its last cell.
void traverseCells(const Vec2& a, const Vec2& b, std::vector<Cell>& out);

/// A road centreline in pixel coordinates.
struct PixelRoad {
  LineString line;
  LandUse roadClass = LandUse::SecondaryRoad;
};

struct RoadRasterOptions {
  /// Parallel primary centrelines whose corner paths are this many corners apart or less are merged
  /// (a gap of 1 would otherwise paint a 4-cell-wide band).
  int mergeGapCells = 1;
};

struct RoadRaster {
  /// 0 = no road, 2 = secondary, 3 = primary (the LandUse codes).
  Grid<std::uint8_t> classes;
  /// Per input road: true when it painted at least one cell that survived.
  std::vector<bool> rasterized;
  /// Corner points (primary) and cells (secondary) removed or added to keep widths exact.
  std::size_t adjustments = 0;
};

/// Secondary roads: the 4-connected path of cells their centreline crosses. Primary roads: the
/// 4-connected path of grid corners nearest their centreline, painting the 2×2 cells around each
/// corner. Then parallel primary paths are merged and 2×2 blocks thinned away (keeping connectivity),
/// and primary cells win over secondary.
RoadRaster rasterizeRoads(const std::vector<PixelRoad>& roads, int width, int height,
                          const RoadRasterOptions& options = {});

/// Counts of violations of the road rules in a land-use grid; all zero for a valid grid.
struct RoadWidthReport {
  std::size_t secondaryBlocks2x2 = 0;  ///< 2×2 windows whose four cells are all secondary
  std::size_t primaryOutside2x2 = 0;   ///< primary cells in no all-primary 2×2 window
  std::size_t primaryBlocks3x3 = 0;    ///< 3×3 windows whose nine cells are all primary
  std::size_t diagonalOnlyLinks = 0;   ///< diagonal road neighbours with no road cell beside both
  bool ok() const {
    return secondaryBlocks2x2 == 0 && primaryOutside2x2 == 0 && primaryBlocks3x3 == 0 &&
           diagonalOnlyLinks == 0;
  }
};

/// Checks a grid of LandUse codes (docs/gridify.md "Width check").
RoadWidthReport checkRoadWidths(const Grid<std::uint8_t>& landUse);

/// The pieces of a centreline (pixel coordinates, y down) lying within `reachCells` of the centre
/// of a road cell of `classes`: the part of the road the grid actually holds. A centreline on its own
/// rasterized cells is within 0.71 cell of one; a carriageway merged into its neighbour, or cells
/// cleared to keep widths exact, leave pieces farther away, which no vectorizer can recover.
MultiLineString partsOnRoadCells(const LineString& line, const Grid<std::uint8_t>& classes, double reachCells,
                                 double stepCells = 0.25);

}  // namespace urbanvec::gridify
