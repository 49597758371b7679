// Loading the gridded input of `vectorize` (CONVENTIONS.md "Gridded input"): land-use, density and
// parcel rasters plus the parcel table and an optional value-to-class table, checked to share one grid,
// into the plain VectorizeInput.
// An app-layer adapter: it knows both GDAL (through io) and the vectorizer's input types, so io stays
// below the modules (docs/architecture.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::app {

/// Metadata item gridify writes into its rasters: the roads were rasterized from mapped streets
/// (VectorizeInput::roadsFromMappedStreets). A simulator's grid carries no such item.
inline constexpr const char* kRoadSourceKey = "URBANVEC_ROAD_SOURCE";
inline constexpr const char* kMappedStreets = "mapped_streets";

struct GridInputPaths {
  std::string landUse;      ///< required
  std::string density;      ///< optional ("" = none)
  std::string parcels;      ///< optional
  std::string parcelTable;  ///< optional; needs `parcels`
  std::string classes;      ///< optional `value,class_name` CSV mapping raster values to classes
  /// optional 0/1 raster: 1 where the cell's road-bounded region reaches the whole grid's edge
  /// (VectorizeInput::openRegions; written by urbanvec-tiles for its windows)
  std::string openRegions;
  /// Read only this window of every raster (`-srcwin`, issue 22 tiles); the rasters must still be one
  /// grid as a whole. Parcel table rows of ids outside the window are skipped.
  std::optional<io::RasterWindow> window;
};

/// Reads and checks everything; throws urbanvec::Error naming the file and what is wrong. Non-fatal
/// findings are appended to `warnings`.
vectorize::VectorizeInput loadGridInput(const GridInputPaths& paths,
                                        std::vector<std::string>* warnings = nullptr);

/// Parses a `value,class_name` table (header optional, '#' comments allowed) into value -> class;
/// `role` names the table in messages.
std::vector<std::pair<double, LandUse>> readClassTable(const std::string& path,
                                                       const std::string& role = "-classes table");

}  // namespace urbanvec::app
