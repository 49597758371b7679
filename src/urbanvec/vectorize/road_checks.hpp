// Topology checks of a road network output (issue 3 quality list): no two segments cross except at a
// shared node, no zero-length segments, no duplicate nodes, every segment ends on a node. Also the
// graph-level repair used as the pipeline's last step.
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/layer.hpp"
#include "urbanvec/vectorize/road_graph.hpp"

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

/// [INFERENCE, not in the documents] Planarizes the graph: every pair of links that cross at an
/// interior point gets a shared node there, and links shorter than `minLength` pw are contracted, so
/// the output meets the "cross only at shared nodes, no zero-length segments" contract after
/// smoothing has moved nodes. Returns the number of crossings noded.
std::size_t nodeCrossingsAndContractTinyLinks(RoadGraph& graph, double minLength = 1e-6);

}  // namespace urbanvec::vectorize
