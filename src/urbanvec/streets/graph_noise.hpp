// Graph noise (spec chen-streets.md §13.6, Fig. 13): streets that stop and restart. Complete and
// partial deletions of minor street segments, chosen by Halton points (bases 2 and 3) mapped to the
// nearest segment, so they are spread evenly and reproducible. A full deletion merges two blocks and
// turns the crossings at its ends into T-junctions; a partial one leaves a dead end.
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/streets/hyperstreamlines.hpp"

namespace urbanvec::streets {

struct GraphNoiseOptions {
  /// Share of the minor segments (edges between crossings) deleted completely [INFERENCE: the spec
  /// gives no value; 0.15 turns a regular grid's crossings into a mix of T-junctions and crossings
  /// inside Boeing's 3-way and 4-way ranges].
  double fullShare = 0.15;
  /// Share of the minor segments cut back to a stub of 20-60 % of their length (a dead end).
  double partialShare = 0.05;
  /// First Halton index used (spec: reproducible for a fixed start index; generateStreets sets it from
  /// StreetsOptions::seed).
  int startIndex = 1;
  /// Only segments whose two ends have at least this street degree are touched: 4 = between two
  /// crossings, so a deletion turns two crossings into T-junctions and never a T-junction into a bend.
  int minEndDegree = 4;
  /// Share of the minor segments deleted at a T-junction so that the two streets left there meet at a
  /// turn: the street turns the corner (a degree-2 bend) instead of running on. Real streets turn
  /// corners without a junction; a traced network has none, which keeps its circuity near 1
  /// [INFERENCE: the spec's "streets that stop and restart, or connect slightly irregularly" (§13.6);
  /// no value is given; 0 = off].
  double bendShare = 0.1;
  /// A T-junction counts as a turn when its two remaining streets deviate from straight by at least
  /// this (degrees).
  double minTurnDegrees = 45.0;
};

/// Curved streets (the authors' perpendicular Perlin jitter, spec Appendix A, with the nodes held
/// fixed): each traced piece (major or minor, not an existing road or an outline) between two nodes
/// bows sideways by a half sine, zero at its ends, of amplitude u × ratio × its chord, u uniform in
/// [−1, 1] drawn per piece from the seed, at most maxOffset metres. A tensor field's streets run
/// straight between their crossings (circuity 1.00-1.02, under the 5th percentile of the world's
/// cities, 1.02, Boeing 2020), and a rotation of the field does not change that (measured in
/// docs/streets.md); real streets curve between intersections. A bow that would cross or touch
/// another piece (a street, the boundary, the water's edge) anywhere but at its own ends is halved,
/// then dropped, so the graph and its nodes stay as they are.
struct BowOptions {
  /// Largest bow as a share of a piece's chord [INFERENCE: the spec gives no value]. A half sine of
  /// relative amplitude r adds about (π r)² / 4 to a piece's circuity, so u uniform in [−1, 1] adds
  /// π² ratio² / 12 on average: 0.033 at 0.2, which lifts a straight traced grid into Boeing's range
  /// (1.02-1.10); of 0, 0.1, 0.15, 0.2 the one that holds that range most often on the generated
  /// areas of bench/streets/compare.sh, seeds 1-8 (28 of 32; docs/streets.md). 0 = off.
  double ratio = 0.2;
  /// Largest bow (m); generateStreets sets it to StreetsOptions::bowMaxOffsetRatio × the minor d_sep
  /// (a quarter), so that two facing bows never close the gap d_test between parallel streets.
  double maxOffset = 20.0;
  /// Seed of the per-street draws (generateStreets sets it from StreetsOptions::seed).
  std::uint64_t seed = 1;
};

/// Bows the traced pieces in place (see BowOptions). Deterministic: the draws are numbered by the
/// pieces' order.
void bowStreets(std::vector<Street>& pieces, const BowOptions& options);

/// The pieces that remain: each graph edge's line and level, minus the deleted ones, with cut-back
/// edges shortened. Only minor edges whose two ends have degree >= minEndDegree at that moment are
/// touched, so no street is cut off from the network by a full deletion. Then bendShare of the minor
/// edges go at T-junctions that become corners (their other end keeps degree >= 2: no dead end).
std::vector<Street> applyGraphNoise(const PlanarGraph& graph, const std::vector<StreetLevel>& edgeLevel,
                                    const GraphNoiseOptions& options);

/// The i-th element of the Halton sequence in a base (radical inverse).
double halton(int index, int base);

}  // namespace urbanvec::streets
