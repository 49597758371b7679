// The written geometry of a traced island: the outline of its pixels, holes filled like the thesis's
// trace ignores them (spec wijgerse-boundary.md §5.4). The thesis keeps the chain through pixel
// centres, which is what the realism metrics measure; as a polygon that chain collapses to zero width
// wherever the island is one pixel wide, so it falls apart into dozens of pieces on a rough boundary.
// The pixel outline is one valid polygon with the island's exact area.
#pragma once

#include <cstdint>

#include "urbanvec/boundary/contour_trace.hpp"
#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

/// The outline, in pixel-corner coordinates (x right, y down; pixel (c, r) spans [c, c+1] x [r, r+1]),
/// of the 8-connected island of `mask` containing `seed`, with its holes filled. Where two pixels of
/// the island touch only at a corner, the pixel above the contact is added so the outline stays one
/// simple polygon. Only the turning points are kept; the ring is closed.
Ring cellOutline(const Grid<std::uint8_t>& mask, Pixel seed);

}  // namespace urbanvec::boundary
