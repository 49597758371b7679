// Reading real city vectors (OpenStreetMap .osm/.pbf through GDAL's OSM driver, GeoPackage,
// shapefile, any OGR source) into the plain data gridify consumes, reprojected to the grid's CRS
// (issue 2 §2 "Input"; docs/gridify.md "Input").
// An app-layer adapter: it knows both GDAL (through io) and gridify's input types, so io stays below
// the modules (docs/architecture.md).
#pragma once

#include <functional>
#include <string>

#include "urbanvec/core/landuse.hpp"
#include "urbanvec/gridify/city_data.hpp"
#include "urbanvec/gridify/class_mapping.hpp"

namespace urbanvec::app {

struct CitySourceOptions {
  std::string assignedCrs;  ///< -a_srs: CRS of an input that has none (or overrides its own)
  std::string targetCrs;    ///< -t_srs: grid CRS; empty = chooseGridCrs()
  // Layers of a non-OSM source; empty = the conventional names (roads/streets, buildings, landuse, water).
  std::string roadsLayer;
  std::string buildingsLayer;
  std::string parcelsLayer;  ///< empty = no real parcels
  std::string landuseLayer;
  std::string waterLayer;
  /// Field holding the road class (highway=* values); a roads layer without it is all defaultRoadClass.
  std::string roadClassField = "highway";
  /// Field holding a land-use class name or landuse=*/building=* value, in land-use, building and parcel
  /// layers; empty = "landuse" for land-use layers, "building" for building layers, none for parcels.
  std::string landuseField;
  std::string populationField;  ///< parcel population field; empty = estimate from buildings
  std::string levelsField = "building:levels";
  LandUse defaultRoadClass = LandUse::SecondaryRoad;
  gridify::RoadClassMapping roadClasses;
};

/// Reads the city. Throws urbanvec::Error naming the file (and the option at fault) for a missing,
/// unreadable or non-vector input, a missing layer or field, or an input without CRS and no -a_srs.
/// `warn` receives non-fatal remarks.
gridify::CityData readCitySource(const std::string& path, const CitySourceOptions& options,
                                 const std::function<void(const std::string&)>& warn = {});

/// The grid CRS (WKT): `userTarget` when given (it must be projected in metres), else the UTM zone
/// of (centreX, centreY) when the source is geographic (x = longitude), else the source CRS, which
/// must then be projected in metres. `option` names where userTarget came from in messages.
std::string chooseGridCrs(const std::string& sourceWkt, double centreX, double centreY,
                          const std::string& userTarget);

}  // namespace urbanvec::app
