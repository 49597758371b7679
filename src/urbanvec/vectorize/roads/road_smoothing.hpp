// Stage B2 — road smoothing (spec §3 B2; thesis §3.2.2, paper §3.2.1): nodes are averaged with their
// same-type neighbours, keeping dead ends, intersections and primary/secondary connection nodes fixed,
// then intersections whose roads pass almost straight through are put back on the line.
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

/// [INFERENCE] How far from the cells a node was placed for smoothing (B2 and B6 together) may move it,
/// in pw: a secondary node may move this far from its placement, a primary node (placed at the centre
/// of a 2x2 window, 0.71 pw from its cells) 0.71 pw less. Unbounded averaging pulls the centreline of
/// a bend inwards, on 2-wide primaries by more than a cell, so the outer cells of the bend end up far
/// from every road. 1.0 pw keeps the road cells within 1.5 pw of the road with room for the output
/// simplification, and still lets shallow staircases straighten: on the sample cities it measured
/// best between 0.8 (turning ratio 3.3 on Monaco: primaries stay stepped) and 1.3 (more uncovered
/// cells), see docs/vectorize.md. Values <= 0 lift the limit (the documents' rule).
inline constexpr double kDefaultSmoothingReach = 1.0;

/// How far smoothing may move a node of this type from its placement: `reach` less the distance from
/// the placement to the farthest centre of the cells it stands for; no limit (infinity) when reach <= 0.
double smoothingShiftLimit(NodeType type, double reach);

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
  /// Largest distance a node may end up from the cells it was placed for, in pw (kDefaultSmoothingReach).
  double reach = kDefaultSmoothingReach;
  /// [INFERENCE, beyond the documents] When set (LandUse codes after A3/A4), a node's averaging move is
  /// undone when it would leave a road cell its links covered farther than `coverRadius` pw from them:
  /// the one-cell fringes of 3-wide primary stretches otherwise creep out of reach. nullptr = the
  /// documents' unconstrained averaging (within `reach`).
  const Grid<std::uint8_t>* coverCells = nullptr;
  double coverRadius = 1.5;
  /// Worker threads of the averaging passes; 0 = all cores. Does not change the output.
  int threads = 0;
};

struct RoadSmoothingStats {
  std::size_t nodesMoved = 0;          ///< road nodes that took part in the averaging
  std::size_t intersectionsMoved = 0;  ///< by the second straightening
};

/// One Jacobi averaging pass: each node with `movable[i]` takes the mean of its position and its
/// same-type neighbours' positions, pulled back onto the circle of radius smoothingShiftLimit(type,
/// `reach`) around its placement when the mean lies farther. Shared with curve smoothing (B6).
/// With `coverCells`, a move is undone when it would leave a road cell its links covered (within
/// `coverRadius`) uncovered by them. Runs on `threads` workers (0 = all cores); the result does not
/// depend on their number.
void averagePass(RoadGraph& graph, const std::vector<char>& movable, double reach,
                 const Grid<std::uint8_t>* coverCells = nullptr, double coverRadius = 1.5, int threads = 1);

/// Which nodes B2/B6 may move: alive road nodes that are not dead ends, intersections (or, when
/// `fixConnections`, primary/secondary connection nodes) and have at least two same-type neighbours.
std::vector<char> smoothableRoadNodes(const RoadGraph& graph, bool fixConnections);

RoadSmoothingStats smoothRoads(RoadGraph& graph, const RoadSmoothingOptions& options,
                               const Progress& progress = {});

}  // namespace urbanvec::vectorize
