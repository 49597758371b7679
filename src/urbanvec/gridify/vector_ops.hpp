// GEOS operations shared by the gridify stages (clipping to the grid's extent, repairing source
// polygons, unions), on plain geometry.
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/gridify/city_data.hpp"

namespace urbanvec::gridify {

Polygon boxPolygon(const Extent& box);
/// A valid GEOS geometry of the polygons (OSM multipolygons are often self-intersecting).
geos::GeomPtr validPolygons(const geos::Context& ctx, const MultiPolygon& polygons);
/// The polygons clipped to the extent, repaired; parts smaller than minArea are dropped.
MultiPolygon clipPolygons(const geos::Context& ctx, const MultiPolygon& polygons, const Extent& box,
                          double minArea = 0.0);
/// The part of a line inside the extent, as line strings.
MultiLineString clipLine(const geos::Context& ctx, const LineString& line, const Extent& box);
/// Union of many polygons, valid.
geos::GeomPtr unionPolygons(const geos::Context& ctx, const std::vector<MultiPolygon>& polygons);

}  // namespace urbanvec::gridify
