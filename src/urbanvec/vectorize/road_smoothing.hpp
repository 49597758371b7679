// Stage B2 — road smoothing (spec §3 B2; thesis §3.2.2, paper §3.2.1): nodes are averaged with their
// same-type neighbours, keeping dead ends, intersections and primary/secondary connection nodes fixed,
// then intersections whose roads pass almost straight through are put back on the line.
#pragma once

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/road_graph.hpp"

namespace urbanvec::vectorize {

struct RoadSmoothingOptions {
  /// [INFERENCE] Averaging passes (the documents give no count; spec §6 starts at 1; 2 measured best
  /// with the output simplification on the sample cities, see docs/vectorize.md).
  int passes = 2;
  /// [INFERENCE] Pairs of roads at an intersection straighter than this trigger the second
  /// straightening, in degrees (spec §6: "approaches 180").
  double straightAngle = 170.0;
  /// [INFERENCE] Averaging passes for the external perimeter staircases among themselves, ends fixed
  /// (Q8); 0 = faithful-literal raw staircases.
  int perimeterPasses = 2;
};

struct RoadSmoothingStats {
  std::size_t nodesMoved = 0;          ///< road nodes that took part in the averaging
  std::size_t intersectionsMoved = 0;  ///< by the second straightening
};

/// One Jacobi averaging pass: each node with `movable[i]` takes the mean of its position and its
/// same-type neighbours' positions. Shared with curve smoothing (B6).
void averagePass(RoadGraph& graph, const std::vector<char>& movable);

/// Which nodes B2/B6 may move: alive road nodes that are not dead ends, intersections (or, when
/// `fixConnections`, primary/secondary connection nodes) and have at least two same-type neighbours.
std::vector<char> smoothableRoadNodes(const RoadGraph& graph, bool fixConnections);

RoadSmoothingStats smoothRoads(RoadGraph& graph, const RoadSmoothingOptions& options,
                               const Progress& progress = {});

}  // namespace urbanvec::vectorize
