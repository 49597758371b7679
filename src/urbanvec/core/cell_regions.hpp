// Regions of raster cells as polygons, traced along the cell edges in one pass (issue 21): what a
// union of the cells' squares gives, in time linear in the grid, without an overlay.
#pragma once

#include <cstdint>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"

namespace urbanvec {

/// The regions of the cells of `mask` that are not 0, one polygon per 4-connected region with its holes,
/// in the internal frame of the grid (cell (col, row) spans x in [frameDx + col, frameDx + col + 1],
/// y in [top - row - 1, top - row] with top = frameDy + height). The same point sets as the union of the
/// cells' squares; where two cells of a region touch only at a corner, the rings pass that corner
/// once each (a region's outer ring and a hole, or two holes, may touch there), as an overlay's minimal
/// rings do. Rings hold only their turning points, start at their first vertex in row-major order
/// (top row first, then left to right) and are closed; outer rings run clockwise and holes
/// counter-clockwise. Polygons come in the row-major order of their first cell, holes in the order of
/// their first vertex.
MultiPolygon cellRegions(const Grid<std::uint8_t>& mask);

}  // namespace urbanvec
