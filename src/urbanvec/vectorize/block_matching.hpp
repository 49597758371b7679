// Stage D5 of shared/specs/sexton-vectorizer.md, "Matching simulated blocks to vector blocks"
// [DOC T §3.4.1; P §3.3.1]. For each simulated block not already paired during water splitting:
//   1. centre rule: if the block's centre lies in one of its own cells, the vector block containing it;
//   2. parcel rule: otherwise the parcel centre closest to the block centre that lies in the block
//      ([INFERENCE] then the block's own cell centres, nearest first);
//   3. failsafe: the vector block whose centroid is closest to the block centre, counted.
// All coordinates are in the internal frame of spec §0 (cells).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/road_network.hpp"

namespace urbanvec::vectorize {

enum class MatchRule : unsigned char { None, WaterSplit, Centre, ParcelCentre, CellCentre, Failsafe };

struct BlockMatching {
  /// Per simulated block (index into SimulatedCity::blocks): the vector block index, -1 if none.
  std::vector<int> vectorBlockOfSim;
  std::vector<MatchRule> rule;  ///< how each simulated block was matched
  int failsafeUses = 0;
  /// Simulated blocks that were matched (all with at least one cell when any vector block exists).
  int matched = 0;
};

/// D5. `preMatched` holds, per simulated block, the vector block paired during water splitting or -1
/// (an empty vector means none).
BlockMatching matchSimulatedBlocks(const std::vector<Polygon>& vectorBlocks, const SimulatedCity& city,
                                   const Grid<int>& blockOfCell, const std::vector<int>& preMatched,
                                   const Progress& progress = {});

}  // namespace urbanvec::vectorize
