// Stage D6 alternative to Zhang-Suen (spec §8.2: "other thinning methods would give slightly better
// spines"): the interior straight skeleton of the block (CGAL Straight_skeleton_2). Only the inner
// bisectors (edges between two skeleton nodes) are kept: the contour bisectors run into the block's
// corners and would be trimmed anyway. This is the only translation unit that includes CGAL.
#pragma once

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/vectorize/parcels/spines.hpp"

namespace urbanvec::vectorize::parcels {

/// Which CGAL kernel builds the skeleton (both have exact predicates). InexactThenExact: the
/// inexact-construction kernel, then the exact one when that gives no skeleton or one that fails
/// skeletonNodesInside.
enum class SkeletonKernel { InexactThenExact, Inexact, Exact };

/// Inner bisectors of the interior straight skeleton; an empty graph when CGAL cannot build it
/// (degenerate or self-touching input) or the skeleton has no inner edge (e.g. a square).
SpineGraph straightSkeletonGraph(const Polygon& polygon,
                                 SkeletonKernel kernel = SkeletonKernel::InexactThenExact);

/// Every node strictly inside the polygon (off its rings and its holes), with finite coordinates:
/// what every inner bisector node of a correct skeleton satisfies (it lies at a positive offset).
bool skeletonNodesInside(const SpineGraph& graph, const Polygon& polygon);

}  // namespace urbanvec::vectorize::parcels
