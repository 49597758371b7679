// Stage A2 — raw block generation by flood fill, internal vs external simulated blocks
// (spec §3 A2, §9.1 Q6; thesis §3.1.2, paper §3.1).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

struct RawBlockOptions {
  /// Exclude reserved patches from blocks as the thesis does (the paper omits this; spec ⚠DIFF 3).
  bool excludeReserved = true;
};

struct RawBlocks {
  std::vector<SimBlock> blocks;
  /// Block index per patch, -1 where no block.
  Grid<std::int32_t> blockOf;
};

/// Two-level 4-connected flood fill: non-road regions (enclosed iff they avoid the grid border), then
/// block-eligible components inside each region. `cells` holds LandUse codes (and kRemovedRoad).
RawBlocks buildRawBlocks(const Grid<std::uint8_t>& cells, const RawBlockOptions& options,
                         const Progress& progress = {});

}  // namespace urbanvec::vectorize
