// Stage A5 — parcel data loading (spec §3 A5; thesis §3.1.5, paper §3.1): simulated parcels from the
// ownership raster and the per-parcel list, each attached to the simulated block holding its first
// patch (the documents) or most of its patches (ParcelLoadingOptions::majorityBlock).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

struct ParcelLoadingOptions {
  /// [INFERENCE, beyond the documents] Attach a parcel to the block holding most of its patches ("no
  /// block" counts as a candidate; ties go to the first patch's, then to a block before none, then to
  /// the lower block index). The documents take the block of
  /// the first patch: the same whenever a parcel lies in one block, as a simulator's parcels do. On
  /// grids rasterized from real plots, roads split plots over several blocks, and the first patch's
  /// block can hold a sliver of the plot while its whole use and population go there.
  /// false = the first patch (the documents).
  bool majorityBlock = true;
};

struct ParcelLoading {
  std::vector<SimParcel> parcels;   ///< ascending id
  std::size_t unattached = 0;       ///< parcels attached to no block (logged)
  double unattachedPopulation = 0;  ///< people of the unattached parcels
  /// The unattached parcels by the land under most of their cells outside every block (ties: the
  /// first in this order): open land (unused), road, water, reserved land.
  std::array<std::size_t, 4> unattachedOn{};
  std::size_t derivedFromRaster = 0;  ///< parcels absent from the table, derived from the rasters
};

/// Builds the simulated parcels and fills SimBlock::parcels. Uses the table's use and population when
/// the table lists the parcel; otherwise the majority land use of its patches and the density sum
/// (spec §2.2 population source, A1 fallback).
/// The warning about the parcels `loading` attached to no block: how many, their people, the land
/// they lie on and that they are left out of the parcels layer; "" when every parcel has a block.
/// `majorityBlock` as ParcelLoadingOptions (false: the parcels' first cell lies outside every block).
std::string unattachedParcelsWarning(const ParcelLoading& loading, bool majorityBlock);

/// A number of people as the messages print it: at most one decimal, "1 person", "2.5 people".
std::string peopleText(double people);

ParcelLoading loadParcels(const VectorizeInput& input, const Grid<std::int32_t>& blockOf,
                          std::vector<SimBlock>& blocks, const Progress& progress = {},
                          const ParcelLoadingOptions& options = {});

}  // namespace urbanvec::vectorize
