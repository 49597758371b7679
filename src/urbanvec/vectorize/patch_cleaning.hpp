// Stage A3 — extraneous intersection patch cleaning (spec §3 A3; thesis §3.1.3, paper §3.2.1).
// Redundant secondary patches hugging a primary road are turned into kRemovedRoad, keeping for each
// "primary-disconnected" patch one shortest path back to the primary road.
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::vectorize {

struct PatchCleaningStats {
  std::size_t searches = 0;        ///< BFS clusters examined
  std::size_t removedPatches = 0;  ///< secondary patches set to kRemovedRoad
};

/// Cleans `cells` (LandUse codes) in place.
PatchCleaningStats cleanIntersectionPatches(Grid<std::uint8_t>& cells, const Progress& progress = {});

}  // namespace urbanvec::vectorize
