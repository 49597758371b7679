// Derived parcels, when the source has no parcel layer (issue 2 §2 "parcels are derived by a
// documented rule that gives plausible plots"): a building-based tessellation of each block, after
// momepy's morphological tessellation (docs/gridify.md "Parcels").
#pragma once

#include <cstddef>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/gridify/blocks.hpp"

namespace urbanvec::gridify {

struct TessellatedParcel {
  MultiPolygon shape;
  std::size_t building = 0;  ///< index into the footprints
  std::size_t block = 0;     ///< index into the blocks
};

struct Tessellation {
  std::vector<TessellatedParcel> parcels;
  /// Per block: whether a building stands in it (blocks without one get no tessellated parcel).
  std::vector<bool> blockBuilt;
};

/// Each building belongs to the block holding a point on its footprint's surface. Within a block the
/// Voronoi cells of those points split the block; each building's parcel is its cell clipped to the
/// block and to `reach` metres around its footprint.
Tessellation tessellateBlocks(const std::vector<TruthBlock>& blocks, const std::vector<MultiPolygon>& footprints,
                              double reach);

}  // namespace urbanvec::gridify
