// Stage A4 — road graph generation (spec §3 A4.1–A4.7; thesis §3.1.4, paper §3.2.1): node placement
// for secondary (1 wide) and primary (2 wide) roads, 4-connected linking, 2x2 short-cycle elimination,
// intersection cluster simplification, long-link subdivision and clockwise link ordering.
// External block perimeters (A4.8) are in perimeters.hpp.
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

struct RoadGraphOptions {
  /// Place a primary node at its patch's south-east corner (paper, on the 2-wide centreline); false =
  /// the thesis's centre of the south-east neighbour (spec ⚠DIFF 4, Q2).
  bool primaryNodeAtCorner = true;
  /// Eliminate 2x2 cycles among secondary nodes only (paper); false = all nodes (thesis) (Q3).
  bool twoByTwoSecondaryOnly = true;
  /// Collapse an intersection cluster with exactly two outside neighbours to a plain degree-2 node at
  /// its centroid (paper's "centroiding the loops"); false = leave it untouched (Q4).
  bool collapseTwoLinkClusters = true;
  /// [INFERENCE, beyond the documents] An intersection cluster is replaced by its mean only when every
  /// member lies within this distance of the mean, in pw; 0 = always (the documents). The documents'
  /// clusters are rasterized junctions, a few patches across. But "linked only to other
  /// intersections" also chains junctions a few cells apart through the short roads between them (a
  /// primary stub between parallel primaries, a one-patch dead end), and their mean lies between the
  /// roads: the stub vanishes and its patches end 2 cells or more from any road. A wider cluster keeps
  /// its nodes; B4 removes the short cycles it holds and B5 contracts nodes within 1 pw. 1 pw keeps
  /// every cluster of a 2x2 window or of two neighbouring nodes (Monaco: road cells farther than 1.5
  /// cells from a road 31 -> 10).
  double maxClusterRadius = 1.0;
  /// [INFERENCE, not in the documents] Also link primary nodes of diagonally adjacent patches when
  /// neither shared 4-neighbour has a node. A 2-wide diagonal (staircase) primary road has its 2x2
  /// node blocks touching only at corners, so pure 4-linking would cut it into isolated nodes.
  bool linkPrimaryDiagonals = true;
  /// [INFERENCE, not in the documents] Also link primary nodes whose 2x2 windows touch along an edge
  /// a knight's move apart (offsets (1,2) and (2,1)) when no window overlaps both. Rasterized
  /// junctions of 2-wide roads at an angle leave such steps; without the link the two roads end short
  /// of each other and the block between them stays open.
  bool linkPrimaryKnightSteps = true;
  /// Links of this length or more are subdivided until all are shorter (A4.6), in pw.
  double maxLinkLength = 2.0;
};

struct RoadGraphBuild {
  RoadGraph graph;
  std::size_t squaresOpened = 0;   ///< 2x2 cycles opened by removing one patch (A4.3)
  std::size_t squaresLeft = 0;     ///< 2x2 cycles with no qualifying patch, left to A4.4
  std::size_t clustersMerged = 0;  ///< intersection clusters replaced by one node (A4.4)
  std::size_t nodesInserted = 0;   ///< nodes added by long-link subdivision (A4.6)
};

/// Builds the road graph from `cells` (LandUse codes after A3); patches removed by A4.3 are set to
/// kRemovedRoad in `cells`.
RoadGraphBuild buildRoadGraph(Grid<std::uint8_t>& cells, const RoadGraphOptions& options,
                              const Progress& progress = {});

/// A4.4: replaces every connected cluster of intersection nodes by one node at the cluster's mean
/// position, inheriting all links to non-members; a cluster with a member farther than
/// maxClusterRadius (> 0) from the mean is left as it is. Returns the number of clusters merged. Also
/// used after the primary/secondary connection (B3).
std::size_t simplifyIntersectionClusters(RoadGraph& graph, bool collapseTwoLinkClusters,
                                         double maxClusterRadius = 0.0);

/// A4.6: splits every link of length >= maxLinkLength into k = floor(L / max) + 1 equal parts
/// ([INFERENCE] split rule of the spec), inserted nodes taking the link's type. Returns nodes added.
std::size_t subdivideLongLinks(RoadGraph& graph, double maxLinkLength);

/// The type a link carries: the common type of its ends; a primary-secondary link is secondary, and
/// any link touching a perimeter node is a perimeter link.
NodeType linkType(const RoadGraph& graph, int a, int b);

}  // namespace urbanvec::vectorize
