// Stage D5 of shared/specs/sexton-vectorizer.md, "Matching simulated blocks to vector blocks"
// [DOC T §3.4.1; P §3.3.1]. For each simulated block not already paired during water splitting:
//   1. centre rule: if the block's centre lies in one of its own cells, the vector block containing it;
//   2. parcel rule: otherwise the parcel centre closest to the block centre that lies in the block
//      ([INFERENCE] then the block's own cell centres, nearest first);
//   3. [INFERENCE] cell overlap: the vector block the block's cell squares overlap most;
//   4. [INFERENCE] a block with no parcels that overlaps no vector block stays unmatched (under pavement);
//   5. failsafe: the vector block whose centroid is closest to the block centre, counted.
// [INFERENCE] A centre or parcel pick holding under half the block's cells gives way to the vector
// block holding most of them (BlockMatchingOptions).
// All coordinates are in the internal frame of spec §0 (cells).
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

enum class MatchRule : unsigned char {
  None,
  WaterSplit,
  Centre,
  ParcelCentre,
  CellCentre,
  Failsafe,
  Majority,
  CellOverlap,
  UnderPavement
};

struct BlockMatchingOptions {
  /// [INFERENCE, beyond the documents] The centre and parcel rules stand in for "the vector block
  /// this simulated block became". When the vector block they pick holds less than this share of the
  /// simulated block's cells (a crescent-shaped block whose centre falls in a sliver the roads cut
  /// off), the vector block holding the most of its cells is taken instead; 0 = the documents' rules
  /// only. Unitless, 0..1.
  double minShareOfCells = 0.5;
  /// At most this many of a block's cells are located to count the shares (an even, deterministic
  /// sample of larger blocks), so the check stays linear in the grid.
  int maxCellsCounted = 400;
  /// [INFERENCE, beyond the documents] Before the failsafe, a block whose cell centres all lie
  /// under pavement goes to the vector block its cell squares overlap most, when that overlap
  /// exceeds minOverlapArea (cells²): the land it kept went there. false = the documents' failsafe.
  bool matchByCellOverlap = true;
  double minOverlapArea = 0.01;
  /// [INFERENCE, beyond the documents] A block with no parcels whose cells overlap no vector block
  /// (mostly a sliver between carriageways that the pavement covers, else land no block was built
  /// on) stays unmatched instead of taking the failsafe: it has nothing to place. false = the
  /// documents' failsafe.
  bool leaveBlocksUnderPavement = true;
};

struct BlockMatching {
  /// Per simulated block (index into SimulatedCity::blocks): the vector block index, -1 if none.
  std::vector<int> vectorBlockOfSim;
  std::vector<MatchRule> rule;  ///< how each simulated block was matched
  int failsafeUses = 0;
  /// Of the failsafe uses, simulated blocks listing at least one parcel (the others carry no parcels
  /// to place: unused land the roads and pavement took).
  int failsafeWithParcels = 0;
  int majorityUses = 0;   ///< centre or parcel picks overruled by BlockMatchingOptions::minShareOfCells
  int overlapUses = 0;    ///< blocks matched by BlockMatchingOptions::matchByCellOverlap
  int underPavement = 0;  ///< blocks left unmatched by BlockMatchingOptions::leaveBlocksUnderPavement
  /// Simulated blocks that were matched (all with at least one cell when any vector block exists,
  /// except those left under pavement).
  int matched = 0;
};

/// D5. `preMatched` holds, per simulated block, the vector block paired during water splitting or -1
/// (an empty vector means none).
BlockMatching matchSimulatedBlocks(const std::vector<Polygon>& vectorBlocks, const SimulatedCity& city,
                                   const Grid<int>& blockOfCell, const std::vector<int>& preMatched,
                                   const Progress& progress = {}, const BlockMatchingOptions& options = {});

}  // namespace urbanvec::vectorize
