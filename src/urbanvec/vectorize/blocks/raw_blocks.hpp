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
  /// Optional, same size as the cells: 1 where the cell's region reaches the whole grid's edge
  /// (VectorizeInput::openRegions); a region is then enclosed iff none of its cells is 1, instead of
  /// iff it avoids this grid's border. Not owned.
  const Grid<std::uint8_t>* openRegions = nullptr;
};

struct RawBlocks {
  std::vector<SimBlock> blocks;
  /// Block index per patch, -1 where no block.
  Grid<std::int32_t> blockOf;
};

/// Two-level 4-connected flood fill: non-road regions (enclosed iff they avoid the grid border, or as
/// options.openRegions says), then
/// block-eligible components inside each region. `cells` holds LandUse codes (and kRemovedRoad).
RawBlocks buildRawBlocks(const Grid<std::uint8_t>& cells, const RawBlockOptions& options,
                         const Progress& progress = {});

}  // namespace urbanvec::vectorize
