// Stages D3 and D4 of shared/specs/sexton-vectorizer.md [DOC T §3.4; P §3.3.1]:
// D3 deletes the external boundary lines (A4.8 perimeter lines) that smoothing left inside the road
// perimeter: both end points inside AND more than 50% of their nodes inside. D4 then builds the
// external blocks from the road perimeter and the surviving boundary lines.
//
// D4 uses the robust equivalent of spec §3 D4 [INFERENCE]: each surviving line is clipped to the
// outside of the perimeter (which reconnects it to the perimeter ring exactly), a line end left in the
// open is joined to the nearest point of the ring, the ring and the lines are noded and polygonized,
// and a face outside the perimeter is an external block iff the majority of the non-road, non-water
// cell centres it covers belong to external simulated blocks. Undeveloped pockets between boundary
// lines become separate faces and are dropped, which is the "follow the next boundary line rather
// than the road perimeter" rule of the documents.
//
// All coordinates are in the internal frame of spec §0 (cells).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"
#include "urbanvec/vectorize/roads/perimeters.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

struct ExternalBlocksOptions {
  /// D3: a boundary line with both ends inside the perimeter is deleted when more than this share of
  /// its nodes is inside too (no unit) (spec §5.2: > 50%).
  double insideNodeShare = 0.5;
  /// D3: points within this distance of the perimeter ring do not count as inside, in cells
  /// ([INFERENCE] spec D3 "points within ε of the ring count as not inside"; §11 ε = 1e-6 pw).
  double insideTolerance = 1e-6;
  /// D4: a face outside the perimeter is kept when more than this share of its non-road, non-water
  /// cell centres belongs to external simulated blocks (no unit) ([INFERENCE] spec D4 "majority").
  double externalCellShare = 0.5;
  /// Neighbour-averaging passes over each surviving boundary line, end points fixed, after D3 (no
  /// unit) ([INFERENCE] spec Q8: the A4.8 lines are raw cell-corner staircases; 0 keeps them raw).
  int boundarySmoothingPasses = 2;
  /// Spacing the boundary lines are resampled to before smoothing, in cells ([INFERENCE]).
  double boundaryResampleSpacing = 0.5;
  /// Overlay precision grid, in cells (see kDefaultPrecisionGrid).
  double precisionGrid = kDefaultPrecisionGrid;
  /// [INFERENCE, beyond the documents] An external simulated block surrounded by undeveloped land
  /// (a pier, an estate in the fields) meets no road, so A4.8 gives it only a closed loop and D4 no
  /// face; its cell outline, smoothed like a boundary line, becomes its block. false = such blocks
  /// go to the failsafe.
  bool islandBlocks = true;
  /// Which land around an island counts as undeveloped: A4.8's own definition (vectorize hands the
  /// road stage's PerimeterOptions over), so the islands are exactly the blocks A4.8 gave only closed
  /// loops.
  PerimeterOptions undeveloped;
  /// [INFERENCE] D3 counts a boundary line's nodes at this spacing along it, in pw: the A4.8 line had
  /// a node at every cell corner, but output simplification kept only its turns, and a straight
  /// two-point line between two culs-de-sac (both ends in pavement, all its length in the open)
  /// would count as 100% inside. 0 = the output vertices (the documents' "nodes" read literally).
  double insideShareSpacing = 1.0;
  /// Worker threads of D3's inside tests (0 = all cores). Does not change the output.
  int threads = 0;
};

struct ExternalBlocks {
  std::vector<Polygon> blocks;  ///< outer rings clockwise
  int boundaryLines = 0;        ///< perimeter-class segments in the network
  int deletedLines = 0;         ///< removed by D3
  int droppedFaces = 0;         ///< faces outside the perimeter that were not external land
  int islands = 0;              ///< island blocks (ExternalBlocksOptions::islandBlocks)
};

/// D3 + D4 on the perimeter-class segments of `network` and the road perimeter of D1.
ExternalBlocks buildExternalBlocks(const RoadNetwork& network, const MultiPolygon& perimeter,
                                   const SimulatedCity& city, const Grid<int>& blockOfCell,
                                   const ExternalBlocksOptions& options, const Progress& progress = {});

/// Adds to `out` a block for each external simulated block that touches only undeveloped land (unused,
/// water, reserved, off-grid) and no block of `out` covers yet.
void addIslandBlocks(const geos::Context& ctx, const SimulatedCity& city, const Grid<int>& blockOfCell,
                     const ExternalBlocksOptions& options, ExternalBlocks& out);

/// The D3 rule for one boundary line: both end points inside the perimeter AND more than
/// `insideNodeShare` of its points inside. `inside` tells for each point whether it is inside.
bool boundaryLineTrappedInside(const std::vector<bool>& inside, double insideNodeShare);

}  // namespace urbanvec::vectorize
