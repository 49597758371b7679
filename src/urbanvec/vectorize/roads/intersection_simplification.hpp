// Stage B5 — intersection simplification (spec §3 B5, §9.2 Q11; thesis §3.2.5, paper §3.2.2): dead
// ends leaving an intersection within 90 degrees of another road are removed, and nodes very close to
// an intersection (primary within 1 pw, secondary within 0.5 pw) are contracted into it.
#pragma once

#include <array>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

struct IntersectionSimplificationOptions {
  /// A dead end next to an intersection is removed when its link makes a smaller angle than this with
  /// another link of the intersection, in degrees.
  double deadEndAngle = 90.0;
  /// [INFERENCE, beyond the documents] The dead-end rule looks at road links only: a node is an
  /// intersection for it with three or more links to road nodes, and the angle is measured against
  /// other road links. The documents speak of dead ends "angled within 90 degrees of another road";
  /// an external block perimeter joined at B3 is a block boundary, not a road. Counting it removed
  /// the last node of a road whose end a perimeter line meets at a sharp angle, and the road's end
  /// patches were left more than 1.5 cells from any road. false = all links (the literal reading).
  bool deadEndRoadsOnly = true;
  /// Primary nodes closer than this to an intersection are contracted into it, in pw.
  double primaryDistance = 1.0;
  /// Secondary nodes closer than this to an intersection are contracted into it, in pw.
  double secondaryDistance = 0.5;
  /// [INFERENCE, beyond the documents] When set (LandUse codes after A3/A4), a contraction or merge
  /// that would leave a road cell farther than `coverRadius` pw from every road link is not made: in
  /// wide secondary areas, chains of contractions can pull the roads off the fringe cells, as
  /// smoothing can (RoadSmoothingOptions::coverCells). nullptr = the documents' rule.
  const Grid<std::uint8_t>* coverCells = nullptr;
  double coverRadius = 1.5;
};

struct IntersectionSimplificationStats {
  std::size_t deadEndsRemoved = 0;
  /// The links of the removed dead ends (internal frame), removed on purpose for the coverage check.
  std::vector<std::array<Vec2, 2>> removedLinks;
  std::size_t nodesContracted = 0;
  std::size_t intersectionsMerged = 0;
  std::size_t contractionsKept = 0;  ///< contractions and merges not made, to keep road cells covered
};

IntersectionSimplificationStats simplifyIntersections(RoadGraph& graph,
                                                      const IntersectionSimplificationOptions& options,
                                                      const Progress& progress = {});

}  // namespace urbanvec::vectorize
