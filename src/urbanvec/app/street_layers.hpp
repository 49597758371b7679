// Reading the vector inputs of `urbanvec streets` and `urbanvec street-metrics` (issue 18): line,
// polygon and point layers as plain geometry in one projected CRS in metres. An app-layer adapter
// over io's readers, so the streets module works on plain data only.
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/layer.hpp"

namespace urbanvec::app {

struct LayerRequest {
  std::string path;
  std::string layer;  ///< empty = the first layer
  std::string where;  ///< OGR SQL filter; empty = all
  std::string role;   ///< "input", "-boundary", ... for messages
};

struct LoadedLayer {
  Layer layer;
  std::string crsWkt;  ///< the CRS the coordinates are in (after any reprojection)
};

/// Reads a layer into `targetCrsWkt` (reprojecting; the layer must then have a CRS). With an empty
/// target the layer keeps its CRS, except that a geographic one is reprojected to its UTM zone
/// (as gridify does) when `toUtm`; a layer without CRS keeps its coordinates.
LoadedLayer readLayer(const LayerRequest& request, const std::string& targetCrsWkt, bool toUtm = true);

/// The lines of a layer (LineStrings and MultiLineString parts; polygons give their rings).
std::vector<LineString> linesOf(const Layer& layer);
/// The polygons of a layer; throws InvalidInput naming `role` when it holds no polygon geometry.
MultiPolygon polygonsOf(const Layer& layer, const std::string& role);

}  // namespace urbanvec::app
