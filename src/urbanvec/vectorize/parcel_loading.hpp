// Stage A5 — parcel data loading (spec §3 A5; thesis §3.1.5, paper §3.1): simulated parcels from the
// ownership raster and the per-parcel list, each attached to the simulated block holding its first
// patch.
#pragma once

#include <vector>

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

struct ParcelLoading {
  std::vector<SimParcel> parcels;     ///< ascending id
  std::size_t unattached = 0;         ///< parcels whose first patch lies in no block (logged)
  std::size_t derivedFromRaster = 0;  ///< parcels absent from the table, derived from the rasters
};

/// Builds the simulated parcels and fills SimBlock::parcels. Uses the table's use and population when
/// the table lists the parcel; otherwise the majority land use of its patches and the density sum
/// (spec §2.2 population source, A1 fallback).
ParcelLoading loadParcels(const VectorizeInput& input, const Grid<std::int32_t>& blockOf,
                          std::vector<SimBlock>& blocks, const Progress& progress = {});

}  // namespace urbanvec::vectorize
