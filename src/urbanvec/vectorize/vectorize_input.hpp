// Plain input and simulated-data types of the vectorizer (spec §2.1, §2.2). app/grid_input.hpp fills
// VectorizeInput from rasters and CSV files; tests build it in code.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::vectorize {

/// One row of the per-parcel list (CONVENTIONS.md parcels.csv).
struct ParcelRecord {
  std::int32_t id = 0;
  LandUse use = LandUse::Unused;
  double population = 0.0;  ///< people
  std::int64_t cells = 0;   ///< patch count stated by the table
};

struct VectorizeInput {
  GridSpec spec;
  /// LandUse codes 0..8 per patch (CONVENTIONS.md "Gridded input").
  Grid<std::uint8_t> landUse;
  /// Population per patch; empty grid (0 x 0) when not given.
  Grid<float> density;
  /// Parcel (ownership) id per patch, 0 = none; empty grid when not given.
  Grid<std::int32_t> parcelIds;
  /// The per-parcel list; empty when not given (then derived from parcelIds).
  std::vector<ParcelRecord> parcelTable;
  /// Column and row of this grid's first cell in the whole raster when it is a window of it (`-srcwin`,
  /// tiles of issue 22), else 0. Random streams are keyed by whole-raster cells, so a block draws the
  /// same numbers in every window that holds it.
  std::int64_t originCol = 0;
  std::int64_t originRow = 0;
  /// Optional (empty = none): 1 where the cell's road-bounded region (4-connected non-road cells)
  /// reaches the edge of the whole grid, 0 where it is enclosed. A2 then takes a region's status from
  /// it rather than from this grid's own edge, so a window (issue 22) classes a region it cuts as the
  /// whole grid does. urbanvec-tiles computes it over the whole grid, tile by tile.
  Grid<std::uint8_t> openRegions;
  /// The grid was rasterized from mapped street centrelines (gridify records it in its rasters'
  /// metadata, app/grid_input.hpp kRoadSourceKey), not drawn by a simulator: its roads are real roads,
  /// and VectorizeOptions::roadRemovals = Auto keeps them (docs/vectorize.md, "Keeping every road").
  bool roadsFromMappedStreets = false;
};

/// Working patch code beyond the nine classes: a patch that was road and was removed by A3 or A4.3
/// (spec §2.1 "removed road").
constexpr std::uint8_t kRemovedRoad = 9;

inline bool isRoadCode(std::uint8_t c) {
  return c == static_cast<std::uint8_t>(LandUse::SecondaryRoad) ||
         c == static_cast<std::uint8_t>(LandUse::PrimaryRoad);
}

/// A cell's centre in the internal frame (spec §0): (c + 0.5, H - r - 0.5).
inline Vec2 patchCentre(int col, int row, int height) {
  return {col + 0.5, height - row - 0.5};
}

/// A cell's centre in the internal frame of a grid that may be a window (Grid::frameDx/frameDy):
/// (dx + c + 0.5, dy + H - r - 0.5), the whole raster's frame.
template <class T>
Vec2 patchCentre(const Grid<T>& grid, int col, int row) {
  return patchCentre(grid.frameDx + col, row, grid.frameDy + grid.height);
}

/// The internal-frame position of a grid's corner (col 0, y 0): subtract it from a position to get
/// the grid's own frame (x = col, y = H - row) for cell look-ups; exact for integer offsets.
template <class T>
Vec2 frameOffset(const Grid<T>& grid) {
  return {static_cast<double>(grid.frameDx), static_cast<double>(grid.frameDy)};
}

/// A simulated block (spec §2.2 SimBlock, built by A2).
struct SimBlock {
  int id = 0;
  bool internal = false;
  std::vector<std::int32_t> patches;  ///< row-major cell indices
  std::vector<int> parcels;           ///< indices into VectorizeResult::parcels (A5)
  double area = 0;                    ///< pw^2 (patch count)
  double developedArea = 0;           ///< pw^2 of residential, commercial, industrial, park
  double undevelopedArea = 0;         ///< pw^2 of unused patches
  Vec2 center;                        ///< mean of patch centres, internal frame
  bool touchesWater = false;
};

/// A simulated parcel (spec §2.2 SimParcel, loaded by A5).
struct SimParcel {
  int id = 0;
  LandUse use = LandUse::Unused;
  std::vector<std::int32_t> patches;  ///< row-major cell indices, ascending
  double area = 0;                    ///< pw^2 (patch count)
  double population = 0;              ///< people
  Vec2 center;                        ///< mean of patch centres, internal frame
  int simBlock = -1;                  ///< index into blocks, or -1 when attached to nothing
};

}  // namespace urbanvec::vectorize
