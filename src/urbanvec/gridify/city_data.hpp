// Real city vectors as plain data, already in the grid's projected CRS (metres): what io/city_source
// reads from OSM / GeoPackage / shapefile sources and what gridify() turns into the gridded input
// (issue 2 §2; CONVENTIONS.md "Gridded input").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::gridify {

struct CityRoad {
  LineString centreline;
  LandUse roadClass = LandUse::SecondaryRoad;  ///< SecondaryRoad or PrimaryRoad
  std::string sourceClass;                     ///< the source's value (OSM highway=*), for the truth layer
  std::string name;
};

/// A land-use polygon (OSM landuse/leisure/amenity/... area, or a -landuse-layer feature).
struct CityArea {
  MultiPolygon shape;
  LandUse use = LandUse::Unused;
};

struct CityBuilding {
  MultiPolygon footprint;
  std::optional<LandUse> use;    ///< from its own tags; empty = inherit from the area it stands in
  std::optional<double> levels;  ///< storeys above ground; empty = unknown
};

struct CityParcel {
  MultiPolygon shape;
  std::optional<LandUse> use;        ///< empty = derived from what stands on it
  std::optional<double> population;  ///< empty = estimated from its buildings
  std::string sourceId;
};

struct CityData {
  std::string crsWkt;  ///< projected CRS in metres of every coordinate below
  std::vector<CityRoad> roads;
  std::vector<CityArea> areas;
  std::vector<CityBuilding> buildings;
  std::vector<MultiPolygon> water;
  /// OSM natural=coastline ways: land on the left, sea on the right.
  std::vector<LineString> coastlines;
  /// Real parcels; when empty, gridify derives parcels from buildings and blocks.
  std::vector<CityParcel> parcels;
  /// A land-cover source already on the grid (gridFrame(); issue 20): a land-use class per cell, where
  /// the developed classes (residential, commercial, industrial, park, reserved) claim cells no
  /// land-use polygon covers and any other value says nothing. Empty = no such source.
  Grid<std::uint8_t> landCover;
};

/// Bounding box in world units.
struct Extent {
  double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;
  bool empty() const { return !(maxX > minX && maxY > minY); }
};

/// The extent of the city proper: roads, buildings and land-use areas (not water, coastline or
/// parcels, which often reach far beyond the streets). Empty when there is none.
Extent cityExtent(const CityData& city);

}  // namespace urbanvec::gridify
