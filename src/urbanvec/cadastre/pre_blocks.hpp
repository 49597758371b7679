// Pre-block graphs (spec pueyo-urban-data.md §A.6.1): noding into a planar graph, joining the ends that
// stop short (within the Block Threshold, the thesis's "close" conditions), fringe removal, and the
// greedy proximity clustering of block-layer linework into pre-blocks.
#pragma once

#include <vector>

#include "urbanvec/cadastre/linework.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::cadastre {

struct GraphStats {
  std::size_t cornersClosed = 0;         ///< pairs of dangling ends met at their lines' crossing
  std::size_t undershootsToSegment = 0;  ///< dangling ends extended onto a segment (new T-vertex)
  std::size_t undershootsToVertex = 0;   ///< dangling ends joined to the nearest vertex
  std::size_t overshootsCut = 0;         ///< ends running past a crossing, cut there
  std::size_t fringeEdgesRemoved = 0;    ///< edges of fringe paths removed (no circuit through them)
  std::size_t verticesStraightened = 0;  ///< degree-2 vertices dropped on straight chains
  std::size_t hooksCut = 0;              ///< short last edges folding back, the line ended at the fold
};

/// The planar graph of the segments whose layers meet `layerMask`: lines are noded where they cross
/// (GEOS), a dangling end is continued along its direction onto the first segment within `gap` (an
/// undershoot, also onto a segment's middle) or else joined to the nearest vertex within `gap`, an end
/// running less than `gap` past a crossing is an overshoot and is left to fringe removal, and fringe
/// paths (one end free) are removed until none is left (§A.6.1 "fringe removal").
/// With `simplifyTolerance` > 0 the result goes through straightenChains.
PlanarGraph structuredGraph(const Linework& linework, std::uint8_t layerMask, double gap, GraphStats& stats,
                            const Progress& progress = {}, double simplifyTolerance = 0.0);

/// §A.0 error 1 ("a straight segment drawn as several smaller segments"): the nodes of degree 2 along
/// each chain between junctions are dropped when within `tolerance` of the straight line their
/// neighbours keep (Douglas-Peucker); junctions and ends never move. Edges become straight segments.
PlanarGraph straightenChains(const PlanarGraph& graph, double tolerance, GraphStats& stats);

/// Pre-blocks (§A.6.1 greedy clustering): edges of the graph closer than `blockThreshold` belong to the
/// same pre-block. Union-find over a grid of `blockThreshold` cells instead of the thesis's quadratic
/// passes (the spatial-index version it suggests). Returns the pre-block id of every node, numbered
/// in order of their lowest node; `count` receives how many there are.
std::vector<int> preBlocks(const PlanarGraph& graph, double blockThreshold, int* count = nullptr);

}  // namespace urbanvec::cadastre
