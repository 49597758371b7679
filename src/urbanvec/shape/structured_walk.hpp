// The structured walk (divider / Richardson method) that measures how a boundary's length grows as the
// measuring chord shrinks (spec wijgerse-boundary.md §6.2, §6.3 and §6.6; thesis §2.1.4, §4.1, §5.3.2,
// after Batty & Longley 1994).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::shape {

struct StructuredWalkOptions {
  /// Base chord length l0 in the ring's units; 0 = the mean segment length of the ring (the thesis's
  /// rule, taken from Batty & Longley).
  double baseChord = 0.0;
  /// Ratio k between successive chord lengths l_n = l0 k^n (thesis: sqrt(2) "for extra detail").
  double scaleFactor = 1.4142135623730951;
  /// Number of chord lengths W, n = 0..W-1 (thesis: 12, giving 11 dimension estimates).
  int scales = 12;
  /// Walk from every s-th vertex only (thesis §5.3.2: s = 15, within 0.0025 of s = 1).
  int skip = 15;
};

/// One chord length's averages over the walked start vertices (Eqs. 4.3-4.8).
struct WalkScale {
  double chord = 0.0;       ///< l_n
  double chordCount = 0.0;  ///< N_n: mean number of chords, the leftover chord counted
  double meanChord = 0.0;   ///< r_n: mean chord length, the leftover chord included
  double fullChords = 0.0;  ///< mean number of full chords N_{n,x} (without the leftover)
};

struct StructuredWalk {
  size_t vertices = 0;       ///< distinct vertices of the ring walked
  size_t startVertices = 0;  ///< vertices a walk started from (every skip-th)
  double baseChord = 0.0;    ///< l0 used
  std::vector<WalkScale> scales;
};

/// Walks the closed ring (closing point repeated or not; repeated consecutive points ignored) with
/// chords l_n from every skip-th vertex: from the current point, the next point is where the ring
/// first leaves the circle of radius l_n; the walk ends back at its start vertex with a leftover chord
/// shorter than l_n. Throws InvalidInput for a ring with fewer than 3 distinct vertices and
/// InvalidOption for bad options.
StructuredWalk structuredWalk(const Ring& ring, const StructuredWalkOptions& options);

}  // namespace urbanvec::shape
