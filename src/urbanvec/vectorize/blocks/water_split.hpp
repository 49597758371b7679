// Stage D2 of shared/specs/sexton-vectorizer.md, "Water splitting" [DOC T §3.4; P §3.3.1]: blocks
// must not include water. The water polygon is the union of the water cells, smoothed by neighbour
// averaging; every block that meets it is cut by it, and each resulting piece is paired with the
// simulated block owning the majority of the cell centres it covers (so D5 skips those simulated
// blocks). A piece that covers no simulated-block cell is a shore scrap between water and road; it goes
// to the water layer instead of being dropped, so blocks, pavement and water still tile the city.
//
// Also holds the cell bookkeeping shared by D2, D4 and D5. All coordinates are in the internal frame of
// spec §0 (cells).
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

struct WaterSplitOptions {
  /// Neighbour-averaging passes over the water outline (no unit) ([INFERENCE] spec D2 "smoothed";
  /// the count is not given; 2 matches the spine smoothing default of spec §6).
  int smoothingPasses = 2;
  /// Spacing of the vertices the staircase outline is resampled to before smoothing, in cells
  /// ([INFERENCE]: half a cell keeps the averaging local).
  double resampleSpacing = 0.5;
  /// Overlay precision grid, in cells (see kDefaultPrecisionGrid).
  double precisionGrid = kDefaultPrecisionGrid;
  /// Worker threads for the per-block splitting (0 = all cores); the result does not depend on it.
  int threads = 0;
};

/// Simulated-block index (into SimulatedCity::blocks) of every cell, -1 where none.
Grid<int> simulatedBlockOfCells(const SimulatedCity& city);

/// The cell containing a point of the internal frame, as (col, row); may lie off the grid.
GridCell cellAt(const Vec2& p, int gridHeight);

/// Q8-style smoothing of a closed ring (first point repeated at the end): resampled so no edge is
/// longer than `spacing`, then every vertex averaged with its two neighbours `passes` times, cyclically,
/// except the vertices `fixedVertex` holds in place. Returned closed. Used for water outlines (chain
/// ends fixed, D2) and island blocks (D4).
Ring smoothClosedRing(const Ring& ring, int passes, double spacing,
                      const std::function<bool(const Vec2&)>& fixedVertex = {});
/// Centre of a cell in the internal frame.
Vec2 cellCentre(const GridCell& cell, int gridHeight);

/// What the cell centres inside a polygon belong to.
struct CellTally {
  std::vector<std::pair<int, int>> blocks;  ///< (simulated block index, cells), most cells first
  int cells = 0;                            ///< all covered cell centres on the grid
  int road = 0;                             ///< covered road cells
  int water = 0;                            ///< covered water cells
  /// The simulated block with most cells (ties: lower index), or -1.
  int majorityBlock() const { return blocks.empty() ? -1 : blocks.front().first; }
};

/// Tallies the cell centres strictly inside `polygon` (scanline, even-odd rule).
CellTally tallyCells(const Polygon& polygon, const Grid<int>& blockOfCell, const Grid<LandUse>& landUse);

/// The smoothed water polygons of the land-use grid (water cells), outer rings clockwise.
MultiPolygon waterPolygons(const Grid<LandUse>& landUse, const WaterSplitOptions& options,
                           const Progress& progress = {});

struct WaterSplitBlock {
  Polygon shape;
  bool internal = true;
  /// Simulated block paired during the split (index into SimulatedCity::blocks), -1 if the block did
  /// not meet water.
  int pairedSimBlock = -1;
};

struct WaterSplit {
  std::vector<WaterSplitBlock> blocks;
  /// Shore scraps: block pieces cut off by water that hold no simulated-block cell.
  MultiPolygon shoreScraps;
  int blocksSplit = 0;  ///< blocks that met water
};

/// Cuts every block by the water polygons. `internal` tells for each block whether it is internal.
WaterSplit splitBlocksByWater(const std::vector<Polygon>& blocks, const std::vector<bool>& internal,
                              const MultiPolygon& water, const SimulatedCity& city,
                              const Grid<int>& blockOfCell, const WaterSplitOptions& options,
                              const Progress& progress = {});

}  // namespace urbanvec::vectorize
