// Polygon rasterization by cell centre (issue 2 §2: land use, water and parcels onto the grid). A cell
// belongs to a polygon when its centre lies inside it (GDAL's default rasterization rule).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/gridify/road_raster.hpp"

namespace urbanvec::gridify {

/// Appends the cells of a width × height grid whose centres lie inside the polygon (pixel coordinates,
/// holes excluded), row by row.
void cellsInside(const Polygon& pixelPolygon, int width, int height, std::vector<Cell>& out);
void cellsInside(const MultiPolygon& pixelPolygons, int width, int height, std::vector<Cell>& out);

}  // namespace urbanvec::gridify
