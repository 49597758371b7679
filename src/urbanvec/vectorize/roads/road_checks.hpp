// Topology checks of a road network output (issue 3 quality list): no two segments cross except at a
// shared node, no zero-length segments, no duplicate nodes, every segment ends on a node. Also the
// graph-level repair used as the pipeline's last step.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

struct RoadNetworkCheck {
  std::size_t segments = 0;           ///< LineString features examined
  std::size_t crossings = 0;          ///< pairs of pieces meeting anywhere but a shared end node
  std::size_t zeroLengthPieces = 0;   ///< consecutive equal vertices, or features of length 0
  std::size_t duplicateNodes = 0;     ///< road_nodes features at the position of an earlier one
  std::size_t loneEnds = 0;           ///< LineString ends that are not at a road_nodes point
  std::vector<Vec2> crossingSamples;  ///< where the first crossings are (at most 5), for messages
  bool ok() const { return crossings == 0 && zeroLengthPieces == 0 && duplicateNodes == 0 && loneEnds == 0; }
  std::string describe() const;
};

/// Checks `roads` (LineStrings) against `roadNodes` (Points) with a uniform-grid sweep: each pair of
/// straight pieces sharing a bucket is tested once, so the cost is near-linear in the piece count.
RoadNetworkCheck checkRoadNetwork(const Layer& roads, const Layer& roadNodes);

/// Issue 3 quality item "every road cell of the grid lies within 1.5 cells of a result road (nothing
/// silently dropped except what the spec removes on purpose: extraneous patches, short cycles)".
struct RoadCoverageCheck {
  double maxDistance = 1.5;   ///< cells
  std::size_t roadCells = 0;  ///< road cells (codes 2 and 3) of the input grid
  std::size_t far = 0;        ///< farther than maxDistance from every road, and not removed on purpose
  std::size_t farRemovedPatches = 0;  ///< farther, but set to removed road by A3 (extraneous patches) or A4.3
  std::size_t farRemovedCycles = 0;   ///< farther, but within maxDistance of a link B4 removed (short cycles)
  std::size_t farRemovedDeadEnds = 0;  ///< farther, but within maxDistance of a dead end B5 removed
  std::vector<GridCell> farSamples;    ///< the first far cells in row-major order (at most 5), for messages
  std::size_t removedOnPurpose() const { return farRemovedPatches + farRemovedCycles + farRemovedDeadEnds; }
  bool ok() const { return far == 0; }
  std::string describe() const;
};

/// Measures how many road cells of `landUse` (the input codes) have their centre farther than
/// `maxDistance` cells from every primary or secondary segment of `network` (perimeter lines are no
/// roads). A far cell is excused as removed on purpose when `cleaned` (the codes after A3/A4) marks it
/// kRemovedRoad, or when it lies within `maxDistance` of one of `cycleRemovedLinks` (B4's removed
/// links, internal frame) or of `deadEndRemovedLinks` (B5's). Cost: linear in grid cells plus road
/// length (a distance mask, no search).
RoadCoverageCheck checkRoadCoverage(const Grid<std::uint8_t>& landUse, const Grid<std::uint8_t>& cleaned,
                                    const RoadNetwork& network,
                                    const std::vector<std::array<Vec2, 2>>& cycleRemovedLinks,
                                    const std::vector<std::array<Vec2, 2>>& deadEndRemovedLinks = {},
                                    double maxDistance = 1.5);

/// [INFERENCE, output only] GEOS's topology-preserving simplification keeps lines from crossing, but it
/// can lay two segments that share both end nodes (a thin loop left by planarization) onto the same
/// chord. Every segment of `simplified` that touches another one anywhere but at a shared end node gets
/// back its line from `exact` (the same network unsimplified, segment for segment), until none does.
/// Returns the number of segments restored.
std::size_t restoreTouchingSegments(RoadNetwork& simplified, const RoadNetwork& exact);

/// [INFERENCE, output only] The output simplification moves a line up to its `tolerance`; where that
/// leaves a road cell of `landUse` (not marked kRemovedRoad in `cleaned`) farther than `maxDistance`
/// from every simplified road, each segment whose `exact` line (the same network unsimplified, segment
/// for segment) passes within `maxDistance` of the cell is simplified again with half, then a quarter
/// of the tolerance, and gets its exact line back when neither covers the cell (at once with a
/// `tolerance` of 0, for lines that were changed otherwise than by simplifying). Returns the number of
/// segments changed. Cost: linear in grid cells plus road length. A segment simplified on its own may
/// touch another: run restoreTouchingSegments afterwards.
std::size_t restoreUncoveringSegments(RoadNetwork& simplified, const RoadNetwork& exact,
                                      const Grid<std::uint8_t>& landUse, const Grid<std::uint8_t>& cleaned,
                                      double tolerance, double maxDistance = 1.5);

/// [INFERENCE, not in the documents] Planarizes the graph: every pair of links that cross at an
/// interior point gets a shared node there, and links shorter than `minLength` pw are contracted, so
/// the output meets the "cross only at shared nodes, no zero-length segments" contract after
/// smoothing has moved nodes. Returns the number of crossings noded.
std::size_t nodeCrossingsAndContractTinyLinks(RoadGraph& graph, double minLength = 1e-6);

}  // namespace urbanvec::vectorize
