// Segment cleaning: self-redundancy and redundancy between polylines (spec pueyo-urban-data.md §A.5,
// Figs. 11-12), plus the T-vertices and undershoots onto the middle of a segment the thesis leaves open.
#pragma once

#include "urbanvec/cadastre/linework.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::cadastre {

struct SegmentCleaningStats {
  std::size_t duplicateSegments = 0;   ///< copies removed (covered segments, §A.5 cases 1-2)
  std::size_t verticesOnSegments = 0;  ///< segments split at a vertex lying on them (T-vertices,
                                       ///< undershoots onto a segment's middle, partial overlaps)
  std::size_t cornersKeptOff = 0;      ///< vertices of lot/building lines met by two or more segments in
                                       ///< each layer, left off a segment within the threshold
};

/// Cleans the segments in place. A vertex closer than `threshold` to the inside of a segment it is not
/// joined to (neither end is its neighbour) moves onto the nearest such segment and splits it there, so
/// partial overlaps (§A.5 case 3) become identical pieces and an end stopping on the middle of a segment
/// becomes a T-vertex; then identical segments (either direction) are kept once, with the union of their
/// layers. The result is sorted, so it does not depend on the drawing's entity order. Vertices marked sound
/// in the linework (lines met there exactly) split nothing. O(n log n) with a grid of `threshold` cells (the
/// quad-tree improvement the thesis suggests, instead of its O(n²) pairs). Beyond the thesis, unless
/// `snapJoined`: a vertex with no block-layer segment and two or more segments in each of its layers (lot,
/// building) is not moved — its lines already meet there, so it is a corner or a through point, not a
/// stray end, and a line passing within the threshold is a neighbour (a short edge, a notch), not its
/// place. Free ends (one segment in a layer) and block-layer vertices move as before.
void cleanSegments(Linework& linework, double threshold, SegmentCleaningStats& stats,
                   const Progress& progress = {}, bool snapJoined = false);

/// Drops repeated segments (either direction), keeping one with the union of their layers; returns how
/// many were dropped. Segments come out sorted by (min end, max end).
std::size_t dropDuplicateSegments(std::vector<Segment>& segments);

}  // namespace urbanvec::cadastre
