// Stage B1 — intersection straightening (spec §3 B1, §9.2 Q9; thesis §3.2.1, paper §3.2.1): for each
// pair of roads entering an intersection, a line is fitted to their nodes within 5 pw and, when the
// residual norm is at most 1.2, the nodes are snapped onto it.
#pragma once

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

struct StraighteningOptions {
  /// Nodes at most this far from the intersection enter the fit, in pw.
  double window = 5.0;
  /// Largest residual norm (2-norm of the perpendicular residuals) that is snapped, in pw.
  double maxResidual = 1.2;
  /// [INFERENCE] When two pairs are snapped at one intersection, move the intersection to the crossing
  /// of the two fitted lines (the spec's "optional improvement"), if that is within this distance of
  /// where the first pair put it, in pw; 0 = faithful (only the best pair moves the intersection, which
  /// reproduces the thesis's "one road straight, the other kinked" shortfall).
  double crossingSnapDistance = 1.0;
};

struct StraighteningStats {
  std::size_t intersections = 0;  ///< intersections examined
  std::size_t pairsSnapped = 0;
};

/// Total-least-squares line through points: returns the residual norm and sets centre and unit
/// direction.
double fitLine(const std::vector<Vec2>& points, Vec2& centre, Vec2& direction);

/// Straightens every road intersection (Primary/Secondary nodes flagged as intersections).
StraighteningStats straightenIntersections(RoadGraph& graph, const StraighteningOptions& options,
                                           const Progress& progress = {});

/// B2's second straightening: at each intersection, if the two first neighbours of a pair of arms are
/// seen under an angle above `minAngleDegrees`, the intersection is moved onto the segment joining
/// them (the pair closest to 180 degrees wins). Returns the intersections moved.
std::size_t straightenNearStraightPairs(RoadGraph& graph, double minAngleDegrees);

}  // namespace urbanvec::vectorize
