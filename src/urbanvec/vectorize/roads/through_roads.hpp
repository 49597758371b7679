// Stage B7 — through roads and straight roads (issue 20; extends spec §3 B1 "Intersection
// straightening" with its "optional improvement" and §9.2 Q9, and runs after B6 "Curve smoothing"):
// at each intersection the arms that continue each other (nearly collinear) are paired and the node
// goes to the least-squares crossing of the paired arms' fitted lines, bounded by the cells as
// smoothing is (-smooth-reach); each arm's approach is put on its line, so a straight street stays
// straight through a crossing and a T-junction's stem meets the through road at its own angle. Then
// every road between two intersections or dead ends whose cells are consistent with a straight line
// becomes that line.
//
// The straightness rule: the cells of a 4-connected road along a straight line at angle θ have
// their centres (a primary's 2×2 windows their corners) within (|cos θ| + |sin θ|) / 2 pw of the
// line — half a cell for a street along the grid, 0.71 pw for a diagonal staircase. A chain of nodes
// (or an arm's approach) counts as straight when every node's placement (the cell it was made for)
// lies within that band plus `slack` of the line; a curve whose cells leave the band stays a curve.
#pragma once

#include <cstddef>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"
#include "urbanvec/vectorize/roads/road_smoothing.hpp"

namespace urbanvec::vectorize {

struct ThroughRoadOptions {
  /// Off = the B1-B6 graph as it is (the documents' road correction).
  bool enabled = true;
  /// Nodes at most this far from an intersection (pw) make its arm's approach (B1's window).
  double window = 5.0;
  /// Nodes nearer than this to the intersection (pw) are moved with their arm but not fitted: their
  /// cells belong to the crossing, whose cluster of cells bulges around the node.
  double innerRadius = 1.5;
  /// An arm whose placements within the window are straight, and whose road stays straight up to
  /// this far from the intersection (pw) or to its next end, has its line fitted on all of that: a
  /// staircase at a small angle to the axes has runs about as long as the window (1 / tan θ cells,
  /// 3.7 at 15 degrees), and a fit on one run gives the run's direction, not the road's (a 15-degree
  /// street's arms fitted at 0 and 37 degrees are no pair). 7.5 (1.5 windows) spans two runs of a
  /// 15-degree road on each side. Pairs are still tested on the placements within the window. The
  /// window (5) = the fit within the window only. Measured: docs/vectorize.md, "Arms fitted beyond
  /// the window".
  double fitReach = 7.5;
  /// Two arms continue each other when their directions are within this many degrees of opposite.
  double pairAngle = 25.0;
  /// How far an intersection or approach node may end up from the road cells, in pw, as smoothing
  /// (-smooth-reach, kDefaultSmoothingReach): a moved node must lie within this of a road cell's
  /// centre of `cells` and an approach node within this (a primary's 0.71 pw more) of its own
  /// placement; without `cells`, within smoothingShiftLimit of a placement of the crossing's nodes.
  /// A move beyond it is not made.
  double reach = kDefaultSmoothingReach;
  /// The land-use codes after A3 (internal frame: cell (c, r) centred at (c + 0.5, H - r - 0.5)).
  /// With them, moves are also undone when they would leave a road cell that the moved nodes' links
  /// covered within `coverRadius` farther than that from every link (as B2, B6 and B5 do).
  const Grid<std::uint8_t>* cells = nullptr;
  double coverRadius = 1.5;
  /// Placements may lie this far (pw) outside the band of a digital straight line
  /// ((|cos θ| + |sin θ|) / 2) and still count as straight. Measured (docs/vectorize.md, "Through
  /// roads and straight roads"): 0.25 halves the turning left on the synthetic diagonal grids but
  /// moves Bubeneč's p95 distance out by 12 % and costs Monaco a matched block; 0 keeps every distance
  /// within a few % of the B6 output.
  double slack = 0.0;
  /// A road between two ends is also straight when its placements are consistent with their own
  /// fitted line (total least squares) and both ends, where the road is drawn from and to, lie within
  /// this share of that line's band of it: ends that earlier stages left a little off the cells' line
  /// (a crossing's cluster mean, a 2x2 window corner) no longer keep a straight road zigzagging.
  /// 0 = only the segment between the ends is tried. Measured (docs/vectorize.md, "Curves drawn as
  /// curves, straight roads between ends off their line"): 0.5 takes 18-31 % of the turning off the 15-45
  /// degree grids and leaves Bubenec as it is; a whole band (1) also moves Bubenec's p95 distance out by 5 %.
  double endOffset = 0.5;
  /// An arm's approach (its nodes from the crossing to the first node left in place) is drawn straight
  /// only when its placements pass the straight-road rule between the crossing and that node (the
  /// crossings' own cells left out as for straight roads); false = every approach within reach of its
  /// cells is drawn straight, curves included. Measured (docs/vectorize.md, "Curves drawn as curves, straight
  /// roads between ends off their line"): Monaco 54 instead of 52 of its 72 matchable blocks, distances
  /// closer on both samples.
  bool straightApproachesOnly = true;
  /// An approach's chain nodes may leave their placements' reach (up to twice it) to go onto the
  /// straight piece when the whole piece, crossing to anchor, lies within reach of road cells (a stem
  /// whose skeleton hooks through another road's band meets the crossing at its own angle; their
  /// placements are left out of the straightness check); false = every node stays within reach of its
  /// placement (issue 20, docs/vectorize.md "Junction clusters").
  bool stemThroughBands = true;
  /// Junction consolidation, before the rest of the stage. Junctions (road nodes of three or more
  /// links) joined by short chains form a cluster (no two of its junctions farther apart than two
  /// primaries' span, junctionSpan x 4); its arms (the roads leaving it) are fitted and paired as an
  /// intersection's (an arm too short to fit pairs with a fitted arm when its cells lie in that arm's
  /// band), and the cluster is rebuilt as the junctions their lines imply: one where two through
  /// roads cross and one where each unpaired straight arm (a stem) first meets a through road,
  /// crossings whose least-squares point lies in every line's band being one; the junctions are linked
  /// along the through roads and each arm to the junction of its line on its side, its approach drawn
  /// straight within reach of its cells. A rebuild whose junctions or links leave the road cells, whose
  /// links cross others, or which uncovers a road cell is undone. A chain is short when its length (pw)
  /// is at most junctionSpan times the widths (2 primary, 1 secondary) of its road and of the widest
  /// other road at its ends summed: two roads of widths w1 and w2 crossing at angle a share a stretch
  /// about (w1 + w2) / sin a long, and 1 / sin(25 degrees) = 2.37 reaches the through-angle, the
  /// shallowest crossing of two roads that are not one. 0 = off. Measured (docs/vectorize.md,
  /// "Junction clusters"): 2 and 2.37 within noise, 1.5 and 3 worse on the synthetic grids.
  double junctionSpan = 2.37;
  /// When a cluster's rebuild would leave a few road cells just over `coverRadius` from every link,
  /// retry once with the rebuilt junctions on one through road nudged toward those cells (a crossing
  /// of two through roads stays at their crossing, approach nodes stay on their lines): each the
  /// smallest move that covers a cell, within `reach` of where the rebuild put it and within each of
  /// its lines' band (digitalLineBand + slack); the rebuild stays only when every cell is then covered
  /// and nothing crosses. false = such a rebuild is undone. Measured: docs/vectorize.md, "Junction
  /// clusters".
  bool nudgeToCover = true;
  /// A cluster's stem (an unpaired straight arm) goes on through the first through road it meets to the
  /// next one, each crossing a junction, while its line between the two runs on road cells and part of
  /// that stretch lies farther than `coverRadius` from every other line of the cluster (cells only the
  /// stem explains: its other side ran into another road's band); false = a stem ends at the first
  /// through road it meets. Needs `cells`. Measured: docs/vectorize.md, "Junction clusters".
  bool stemsThrough = true;
  /// Two stems of a cluster whose lines cross before each reaches the through road it meets cross
  /// there (a junction of the two); false = they are left to cross on their links (and the rebuild is
  /// undone).
  bool stemsCross = true;
  /// A dead-end arm that ends within the window (a spur a cell or two long) and whose every node lies
  /// within the band of one of the cluster's through roads is that road's cells, where a street's
  /// staircase runs beside another road's band: it gets no line of its own and goes with the rebuild
  /// (its cells stay covered, or the rebuild is undone). Only when every arm that goes on has a line:
  /// one without a line is joined to its nearest junction with a bend. false = such a spur keeps a stem
  /// line fitted on its few placements. Measured: docs/vectorize.md, "Junction clusters" (round 6).
  bool spursInBands = true;
  /// A road between two ends is also straight when some straight line, not only its placements' total
  /// least-squares line, holds every placement within its band and both ends within endOffset of that
  /// band (the digital straight line test: at a staircase's step, a primary's 2x2 corners or a street's
  /// cells can lie just outside the fitted line's band although a line holding them all exists).
  /// Approaches keep the fitted line: a few cells of a road that curves beyond them fit some line.
  /// false = the fitted line only. Measured: docs/vectorize.md, "Junction clusters".
  bool digitalStraightRoads = true;
  /// Worker threads (0 = all cores). Does not change the output: the moves are made speculatively on
  /// each thread's copy of the graph and committed in node order (SpeculativeMoves).
  int threads = 0;
};

struct ThroughRoadStats {
  std::size_t clusters = 0;              ///< clusters of junctions joined by short chains
  std::size_t clustersConsolidated = 0;  ///< clusters rebuilt as the junctions their lines imply
  std::size_t junctionsRemoved = 0;      ///< junctions fewer after those rebuilds (net)
  std::size_t intersections = 0;         ///< intersections examined
  std::size_t pairs = 0;                 ///< pairs of arms found to continue each other
  std::size_t nodesPlaced = 0;           ///< intersections moved to their arms' crossing
  std::size_t outOfReach = 0;            ///< intersections whose crossing lay beyond reach of their cells
  std::size_t approaches = 0;            ///< arm approaches put on their line
  std::size_t straightChains = 0;        ///< roads between intersections/dead ends drawn as a straight line
  std::size_t crossingsAvoided = 0;      ///< moves not made because a moved link would cross another
  std::size_t uncoveringAvoided = 0;     ///< moves not made because they would uncover a road cell
  std::size_t clustersNudged = 0;        ///< cluster rebuilds kept by nudging nodes toward uncovered cells
};

/// Half-width of the band holding the cell placements of a road along direction `d` (unit), in pw:
/// (|d.x| + |d.y|) / 2.
double digitalLineBand(const Vec2& d);

/// True when every placement lies within digitalLineBand(direction of ab) + slack of the line ab.
bool consistentWithSegment(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b, double slack);

/// B7's straight-road rule for a chain drawn between its ends a and b: its placements are consistent
/// with the segment ab, or with their own fitted line while a and b lie within
/// ThroughRoadOptions::endOffset of that line's band of it. B7 tries it on all the chain's placements
/// (its ends' included) and on those farther than innerRadius from an intersection end's placement
/// (a crossing's cells bulge around its node, as the arms' fits leave them out).
/// With anyLine, also when some line (not only the fitted one) holds every placement within its band
/// and both ends within endOffset of that band (ThroughRoadOptions::digitalStraightRoads).
bool straightChain(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b,
                   const ThroughRoadOptions& options, bool anyLine = false);

ThroughRoadStats straightenThroughRoads(RoadGraph& graph, const ThroughRoadOptions& options,
                                        const Progress& progress = {});

}  // namespace urbanvec::vectorize
