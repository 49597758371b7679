// Merging split vertices (beyond the thesis, issue 17): after collapsing and segment cleaning, the
// jittered copies of one drawn vertex may still stand as two or more vertices a few centimetres to
// decimetres apart (the anti-drift rule refused a cluster that grew too wide, or segment cleaning
// moved a free end onto a line next to its own vertex), leaving small kinks in the polygons. Two
// vertices closer than a few times the drawing's noise merge when no drawn segment joins them and the
// merge changes no face of the linework but slivers.
#pragma once

#include <cstddef>

#include "urbanvec/cadastre/linework.hpp"

namespace urbanvec::cadastre {

struct MergeStats {
  std::size_t candidates = 0;       ///< vertex pairs closer than the merge distance
  std::size_t merged = 0;           ///< merges done
  std::size_t refusedDrawn = 0;     ///< refused: a drawn segment joins them (a true short edge)
  std::size_t refusedFace = 0;      ///< refused: a face wider than a sliver would collapse
  std::size_t refusedCrossing = 0;  ///< refused: a segment would cross one it did not cross
};

/// Merges, closest pair first, the vertices of `lw` closer than `distance` (m) when
/// - no drawn segment joins them (one of `lw.copies` of one observes the other: a true short edge,
///   e.g. the 20 % of the sample's edges under 1 m, always survives),
/// - every triangle they close with a common neighbour is a sliver (width 2 area / longest side below
///   `sliverWidth`, a face the circuits drop anyway): no real face collapses,
/// - the segments at the merged vertex cross no more segments than before (no crossing is created).
/// The merged vertex stands at the mean of the copies of both; segments and copies are renumbered,
/// duplicate segments dropped (layers or-ed), vertices renumbered in order of their lowest old id.
/// Deterministic. `distance` <= 0 does nothing.
void mergeSplitVertices(Linework& lw, double distance, double sliverWidth, MergeStats& stats);

}  // namespace urbanvec::cadastre
