// `gridify`: real city vectors -> the gridded input the vectorizer consumes (issue 2 §2;
// CONVENTIONS.md "Gridded input"; docs/gridify.md gives every rule and default).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/gridify/city_data.hpp"
#include "urbanvec/gridify/untagged_land.hpp"

namespace urbanvec::gridify {

struct GridifyOptions {
  /// Cell edge length in metres (the source simulation uses 12 m cells).
  double cellSize = 12.0;
  /// Extent in the city's CRS; empty = cityExtent() snapped outwards to multiples of cellSize.
  std::optional<Extent> extent;
  /// Storeys assumed for a building whose level count is unknown.
  double defaultLevels = 3.0;
  /// Gross floor area per inhabitant in m² (population = footprint × levels / this).
  double floorAreaPerPerson = 40.0;
  /// Class of a building standing in no land-use area and carrying no class of its own.
  LandUse defaultBuildingUse = LandUse::Residential;
  /// Derived parcels reach at most this far (metres) from their building (momepy's tessellation limit).
  double parcelReach = 50.0;
  /// Dual carriageways and parallel roads whose rasterized centrelines come within this many cells of
  /// each other are merged so that widths stay exact (see docs/gridify.md "Road widths").
  int mergeGapCells = 1;
  /// Truth blocks end at curbs this many cells from a primary / secondary centreline: the road
  /// widths the grid gives them, and where the vectorizer puts its curbs (spec C).
  double truthCurbPrimaryCells = 1.0;
  double truthCurbSecondaryCells = 0.5;
  /// Truth roads keep the pieces of their centrelines within this many cells of a road cell's centre:
  /// the roads the grid holds (a centreline on its own cells is within 0.71 cell; merged carriageways
  /// and cleared cells leave pieces the grid does not hold).
  double truthRoadReachCells = 1.0;
  /// The use of land no land-use polygon covers (issue 20; untagged_land.hpp).
  UntaggedLandOptions untagged;
};

struct ParcelRecord {
  std::int32_t id = 0;
  LandUse use = LandUse::Unused;
  double population = 0.0;
  std::int64_t cells = 0;
};

struct GridifyResult {
  GridSpec spec;  ///< frame of every raster (CRS = the city's)
  Grid<std::uint8_t> landUse;
  Grid<float> density;                ///< population per cell
  Grid<std::int32_t> parcelIds;       ///< 0 = none
  std::vector<ParcelRecord> parcels;  ///< ids 1..n in order
  /// Truth layers in the grid's CRS: roads, blocks, parcels, water, and the grid_info table (whose
  /// crs field the caller fills with the CRS short name, which needs PROJ).
  std::vector<Layer> truth;
  // Figures for the report.
  std::size_t roadsRasterized = 0;
  std::size_t roadsMerged = 0;  ///< primary corner cells or secondary cells removed to keep widths exact
  /// Untagged blocks inside the urban extent given a use by their buildings, streets, or the default,
  /// and the cells that took it.
  std::size_t untaggedByBuildings = 0;
  std::size_t untaggedByStreets = 0;
  std::size_t untaggedByDefault = 0;
  std::size_t inferredCells = 0;
  /// Cells no land-use polygon covers that took their class from CityData::landCover.
  std::size_t landCoverCells = 0;
};

/// The grid gridify() lays over the city: the extent (options.extent, else cityExtent() snapped
/// outwards to whole cells), north-up cells of options.cellSize, the city's CRS. Throws InvalidOption
/// for a bad cell size or an extent without cells, InvalidInput when the city has nothing to grid.
GridSpec gridFrame(const CityData& city, const GridifyOptions& options);

/// Builds the grid. Throws InvalidOption when cellSize <= 0 or the extent holds no cell, InvalidInput
/// when the city has nothing to grid.
GridifyResult gridify(const CityData& city, const GridifyOptions& options, const Progress& progress = {});

}  // namespace urbanvec::gridify
