// Stage B5 — intersection simplification (spec §3 B5, §9.2 Q11; thesis §3.2.5, paper §3.2.2): dead
// ends leaving an intersection within 90 degrees of another road are removed, and nodes very close to
// an intersection (primary within 1 pw, secondary within 0.5 pw) are contracted into it.
#pragma once

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/road_graph.hpp"

namespace urbanvec::vectorize {

struct IntersectionSimplificationOptions {
  /// A dead end next to an intersection is removed when its link makes a smaller angle than this with
  /// another link of the intersection, in degrees.
  double deadEndAngle = 90.0;
  /// Primary nodes closer than this to an intersection are contracted into it, in pw.
  double primaryDistance = 1.0;
  /// Secondary nodes closer than this to an intersection are contracted into it, in pw.
  double secondaryDistance = 0.5;
};

struct IntersectionSimplificationStats {
  std::size_t deadEndsRemoved = 0;
  std::size_t nodesContracted = 0;
  std::size_t intersectionsMerged = 0;
};

IntersectionSimplificationStats simplifyIntersections(RoadGraph& graph,
                                                      const IntersectionSimplificationOptions& options,
                                                      const Progress& progress = {});

}  // namespace urbanvec::vectorize
