// Reading and writing single-band rasters with GDAL into plain grids.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/grid.hpp"

namespace urbanvec::io {

/// GDAL's name of a band's data type, e.g. "Byte", "Float32".
struct RasterInfo {
  GridSpec spec;
  std::string dataType;
  std::optional<double> nodata;
  int bandCount = 0;
  /// The dataset's metadata items of the default domain (gdalinfo's "Metadata:"), NAME -> VALUE.
  std::map<std::string, std::string> metadata;
};

/// Opens a raster and describes it; throws urbanvec::Error (naming the file) when it is missing or
/// not a raster GDAL can read. `role` names the input in messages ("land-use raster").
RasterInfo inspectRaster(const std::string& path, const std::string& role);

/// A block of cells of a raster, as gdal_translate's -srcwin: the first column and row and the size.
struct RasterWindow {
  int xoff = 0;
  int yoff = 0;
  int xsize = 0;
  int ysize = 0;
};

/// Reads band 1 converted to T, with its frame and nodata. With a window, only those cells are read
/// and the frame is the window's (origin moved to its first cell, as gdal_translate -srcwin); a window
/// not wholly inside the raster is an error (InvalidOption, naming -srcwin and the raster's size).
template <class T>
Grid<T> readRasterBand(const std::string& path, const std::string& role, RasterInfo* info = nullptr,
                       const RasterWindow* window = nullptr);

/// Band 1 of a raster in any CRS brought onto the north-up grid `target` with GDAL's warper
/// (gdalwarp -t_srs -te -ts -r <resampling>), as doubles; NaN where the raster says nothing (its nodata,
/// or outside it). Throws InvalidInput naming the file when it is unreadable, has no CRS or no
/// georeferencing; `info` receives the source's description.
Grid<double> warpRasterBand(const std::string& path, const std::string& role, const GridSpec& target,
                            const std::string& resampling, RasterInfo* info = nullptr);

/// The frame of `window` within `full` (checked as readRasterBand does; `path` names the raster).
GridSpec windowSpec(const GridSpec& full, const RasterWindow& window, const std::string& role,
                    const std::string& path);

struct RasterWriteOptions {
  std::string format = "GTiff";
  std::vector<std::string> creationOptions;  ///< NAME=VALUE, GDAL's -co
  /// Dataset metadata items written with the band (default domain), as gdal_edit -mo NAME=VALUE.
  std::map<std::string, std::string> metadata;
};

/// Checks the format and its -co options before any work (throws invalidOption naming the option).
void checkRasterWriteOptions(const RasterWriteOptions& options);

/// Writes one band to `path` (which the caller makes atomic) with the frame and CRS of `spec`.
template <class T>
void writeRasterBand(const std::string& path, const GridSpec& spec, const Grid<T>& grid,
                     std::optional<double> nodata, const RasterWriteOptions& options = {});

/// Throws an error naming both files and what differs when two frames are not the same grid
/// (size, geotransform, CRS).
void requireSameGrid(const GridSpec& a, const std::string& aPath, const GridSpec& b,
                     const std::string& bPath);

}  // namespace urbanvec::io
