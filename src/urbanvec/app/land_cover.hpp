// A land-cover raster as a source of gridify's land use (issue 20, "Land use where the map has
// none"; docs/gridify.md "Land-cover raster"): a product the user downloaded (a built-up or land-cover
// raster in any CRS) and a `value,class_name` table, brought onto the grid with GDAL's warper.
// An app-layer adapter: it knows GDAL (through io) and gridify's input type.
#pragma once

#include <cstdint>
#include <string>

#include "urbanvec/core/grid.hpp"

namespace urbanvec::app {

struct LandCoverSource {
  std::string raster;  ///< -landcover: any raster GDAL reads, band 1, with a CRS
  std::string table;   ///< -landcover-table: `value,class_name`, every value the grid takes
  /// gdalwarp resampling: the class most of a grid cell's area holds (categorical data).
  std::string resampling = "mode";
};

/// The raster's class per cell of `grid` (a LandUse code; Unused where the raster has nodata or does
/// not reach). Throws InvalidInput naming the file for an unreadable raster or table, a raster without
/// CRS, one that covers no cell of the grid, or a value the grid takes that the table does not map
/// (naming the value, a cell holding it and the line to add).
Grid<std::uint8_t> readLandCover(const LandCoverSource& source, const GridSpec& grid);

}  // namespace urbanvec::app
