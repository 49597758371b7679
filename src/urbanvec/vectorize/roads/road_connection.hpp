// Stage B3 — primary and secondary connection (spec §3 B3; thesis §3.2.3, paper §3.2.1): the
// disjoint primary and secondary graphs are merged by linking each connection node to the closest
// primary node, clusters are simplified again, and perimeter ends are connected to the roads.
#pragma once

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

struct RoadConnectionOptions {
  /// [INFERENCE] A connection node links to the closest primary node only within this distance, in
  /// pw (a secondary patch touching a 2-wide primary is about 1-1.6 pw from its centreline; farther
  /// nodes mean the primary road had no node nearby and a link would cut across blocks).
  double maxConnectionDistance = 3.0;
  /// [INFERENCE, beyond the documents] A connection node touching primary patches of two roads (a
  /// secondary cell bridging two primaries, as rasterized junctions make) links to the closest
  /// primary node of each side, so the grid's connection is kept; the documents' single link to "the
  /// closest node" leaves the other primary road ending short, and the block between them open.
  bool linkEverySide = true;
  /// [beyond the documents, issue 20] A street crossing a primary road ends in a connection node on
  /// each side; linking each to its own closest primary node makes two T-junctions offset along the
  /// primary when it crosses at a slant (a diagonal avenue). Two connection nodes that continue each
  /// other across a primary — each within crossingAngle of the line to the other along its street's
  /// direction, the directions within crossingAngle of opposite, at most crossingReach apart, with
  /// a primary node between them — link to the one primary node nearest to the line joining them,
  /// so the crossing is one 4-way node (B7 then puts it where the lines cross). 0 = off.
  double crossingAngle = 25.0;  ///< degrees (B7's -through-angle)
  /// A 2-wide primary crossed at angle a separates the two ends by about 3 / sin(a) pw: 8 pw reaches
  /// crossings down to 22 degrees.
  double crossingReach = 8.0;
  /// The street's direction at a connection node: the line from the node to its street followed this
  /// far (pw) along secondary links through nodes of two links (B1's window).
  double crossingWindow = 5.0;
  /// [INFERENCE] A perimeter end links to the nearest road node without a perimeter link only
  /// within this distance, in pw.
  double maxPerimeterDistance = 3.0;
  /// As RoadGraphOptions::collapseTwoLinkClusters, for the clusters the merge creates.
  bool collapseTwoLinkClusters = true;
  /// As RoadGraphOptions::maxClusterRadius, for the clusters the merge creates, in pw. Here the
  /// merge's new links make most wide clusters: a connection node linked to a primary stub, or
  /// secondary cells linked to two parallel primaries, join junctions several cells apart.
  double maxClusterRadius = 1.0;
  /// As RoadGraphOptions::maxLinkLength, for the new links (A4.6 re-run), in pw.
  double maxLinkLength = 2.0;
};

struct RoadConnectionStats {
  std::size_t connections = 0;  ///< secondary-to-primary links added
  std::size_t bridges = 0;      ///< of those, second links to the primary road on another side
  std::size_t crossings = 0;    ///< pairs of connection nodes linked to one primary node (a street crossing)
  std::size_t unconnected = 0;  ///< connection nodes with no primary node in reach
  std::size_t clustersMerged = 0;
  std::size_t perimeterEndsLinked = 0;
  std::size_t perimeterEndsLeft = 0;  ///< ends with no free road node in reach
};

RoadConnectionStats connectRoads(RoadGraph& graph, const RoadConnectionOptions& options,
                                 const Progress& progress = {});

}  // namespace urbanvec::vectorize
