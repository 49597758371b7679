// Input of `urbanvec evaluate` beyond vector_io (issue 2 §3): layers narrowed by an OGR SQL where
// clause (to evaluate e.g. the non-road polygons of a gdal_polygonize.py output as blocks), a check
// that a layer holds the kind of geometry its role needs, and the cell size of the truth's grid_info.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "urbanvec/io/vector_io.hpp"

namespace urbanvec::io {

enum class GeometryKind { Lines, Polygons };

/// Names of the layers of a vector dataset, like listVectorLayers, but a raster given where vectors
/// are needed is named as such ("result 'landuse.tif' is a raster, not a vector dataset").
std::vector<std::string> listEvaluationLayers(const std::string& path, const std::string& role);

/// Reads layer `layerName` of `path` like readVectorLayer, keeping only the features matching the
/// OGR SQL `where` clause when it is not empty (an error naming `whereOption` when GDAL rejects it),
/// and reprojecting it to options.targetCrs when that is set. Returns nothing when the dataset has no
/// such layer; throws when the layer has no geometry, holds geometries of another kind than `kind`,
/// has no CRS, or cannot be transformed. `role` names the layer in messages ("result roads").
std::optional<LayerRead> readEvaluationLayer(const std::string& path, const std::string& layerName,
                                             const std::string& where, const std::string& whereOption,
                                             GeometryKind kind, const std::string& role,
                                             const VectorReadOptions& options = {});

/// The cell size in metres from the one-row `grid_info` table of a truth dataset written by gridify;
/// nothing when the dataset has no such table; throws when the table has no positive `cell_size`.
std::optional<double> readGridInfoCellSize(const std::string& truthPath);

}  // namespace urbanvec::io
