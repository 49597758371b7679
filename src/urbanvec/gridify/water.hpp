// Water of the grid: water polygons plus the sea side of the coastline (issue 2 §2 "water from water
// polygons and, where the data holds a coastline, the sea side of it").
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/gridify/city_data.hpp"

namespace urbanvec::gridify {

/// The parts of the extent lying on the sea side of the coastline. OSM draws natural=coastline ways
/// with the land on the left and the sea on the right; the extent is cut along the coastline and each
/// piece is sea when most of its coastline edges have it on their right. Empty when no coastline
/// crosses the extent.
MultiPolygon seaFromCoastline(const std::vector<LineString>& coastlines, const Extent& box);

}  // namespace urbanvec::gridify
