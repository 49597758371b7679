// Stage A3 — extraneous intersection patch cleaning (spec §3 A3; thesis §3.1.3, paper §3.2.1).
// Redundant secondary patches hugging a primary road are turned into kRemovedRoad, keeping for each
// "primary-disconnected" patch one shortest path back to the primary road.
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::vectorize {

struct PatchCleaningOptions {
  /// [INFERENCE, beyond the documents] Keep a secondary patch whose primary 4-neighbours touch each
  /// other only through it (two primary roads meeting at a corner, bridged by one secondary cell as
  /// rasterized junctions make). Such a patch is not redundant: removing it, as the documents' rule
  /// would, disconnects the primary roads and opens the blocks they enclose. B3 links it to both.
  bool keepPrimaryBridges = true;
};

struct PatchCleaningStats {
  std::size_t searches = 0;        ///< BFS clusters examined
  std::size_t removedPatches = 0;  ///< secondary patches set to kRemovedRoad
  std::size_t bridgesKept = 0;     ///< secondary patches kept as the only link between primaries
};

/// Cleans `cells` (LandUse codes) in place.
PatchCleaningStats cleanIntersectionPatches(Grid<std::uint8_t>& cells, const Progress& progress = {},
                                            const PatchCleaningOptions& options = {});

}  // namespace urbanvec::vectorize
