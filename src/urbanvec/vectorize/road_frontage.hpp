// The road frontage of each block (E2's input, spec Q17): the parts of its outline within a small
// tolerance of the pavement, computed exactly from segment-to-segment geometry (issue 21).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::vectorize {

/// For each block, the parts of its outline (outer ring and holes) within distance `tolerance` of the
/// pavement pieces (the closed set: the pieces and a band `tolerance` wide around them), as lines
/// merged along each ring: a stretch running over several edges is one line, a ring covered all
/// round is one closed line. Per outline edge, the pavement edges near it (a bucket grid over all of
/// them) each give the one interval of the edge within `tolerance` of them (`withinDistanceInterval`),
/// and a stretch between those intervals is covered only when it lies inside a piece. An edge that is
/// an edge of a piece, most of them since the outlines are cut from the pavement, is covered whole.
/// Blocks run on `threads` workers (0 = all cores) and write only their own entry, so the result does
/// not depend on the thread count. Coordinates of pieces and blocks in one frame (cells). The pieces are
/// taken by value (move them in): they are copied into one array as they are released.
std::vector<MultiLineString> roadFacingEdges(std::vector<Polygon> pavement,
                                             const std::vector<const Polygon*>& blocks, double tolerance,
                                             int threads);

}  // namespace urbanvec::vectorize
