// Vectorizer part 3 (spec §1 stages D6, E1-E6): per block, the spine, then the best of `tries`
// generate-and-test iterations of E1-E5, then population (E6). Blocks are independent and run in
// parallel; each draws from its own generator seeded deriveSeed(seed, blockId), so the output does not
// depend on the thread count. Also the quality checkers of the issue (tiling, validity, frontage,
// counts, land-use shares, population).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/parcels/land_use_assignment.hpp"
#include "urbanvec/vectorize/parcels/parcel_input.hpp"
#include "urbanvec/vectorize/parcels/parcel_scoring.hpp"
#include "urbanvec/vectorize/parcels/regular_subdivision.hpp"
#include "urbanvec/vectorize/parcels/spine_subdivision.hpp"
#include "urbanvec/vectorize/parcels/spines.hpp"
#include "urbanvec/vectorize/parcels/undeveloped_parcels.hpp"

namespace urbanvec::vectorize::parcels {

struct ParcelsOptions {
  SpineOptions spine;                        ///< D6 (`-spine-method`)
  SpineSubdivisionOptions spineSubdivision;  ///< E1
  RegularSubdivisionOptions regular;         ///< E2
  UndevelopedOptions undeveloped;            ///< E3
  LandUseOptions landUse;                    ///< E4
  ScoringOptions scoring;                    ///< E5
  /// Generate-and-test iterations per block; the lowest cost is kept (spec §5.4: 50; `-tries`).
  int tries = 50;
  /// Anytime search (issue 21, beyond the documents): a block stops trying once its best result is
  /// complete (no parcel short of the target) and has not improved for this many tries in a row
  /// (`-patience`). 0 = always run all `tries` (the paper's search). docs/performance.md has the curve
  /// of the mean best cost against tries and what each patience saves and costs.
  int patience = 0;
  /// [INFERENCE, beyond the documents] When every try ends short of its target, up to this many
  /// rounds of `relaxedTries` tries follow, each halving the size (constraint 1) and rectangularity
  /// (constraint 3) thresholds of the round before; road access (constraint 2) is never relaxed. The
  /// report's relaxed_rules says how many rounds the kept result needed. 0 = the documents' rules.
  int relaxationRounds = 2;
  int relaxedTries = 10;
  /// Run seed (`-seed`); block b uses deriveSeed(seed, b.seedStream or else b.blockId).
  std::uint64_t seed = 0;
  /// Worker threads; 0 = all cores. Does not change the output.
  int threads = 0;
};

/// Throws InvalidOption naming the option when a value is out of range.
void validateParcelsOptions(const ParcelsOptions& options);

/// D6 + E1-E6 for one block, on the caller's GEOS context (one per thread).
BlockParcels parcelBlock(const ParcelBlock& block, const ParcelsOptions& options, const geos::Context& geos);

struct ParcelsResult {
  std::vector<BlockParcels> blocks;  ///< same order as the input
};

/// All blocks, in parallel. Progress is reported from the calling thread only.
ParcelsResult vectorizeParcels(const std::vector<ParcelBlock>& blocks, const ParcelsOptions& options,
                               const Progress& progress = {});

// ---- Quality checkers (issue 5 "Quality"; spec §11.6-11.7) ----

/// How exactly a block's parcels tile it (spec §11.6 check 32).
struct TilingCheck {
  double blockArea = 0.0;    ///< cells²
  double parcelArea = 0.0;   ///< Σ parcel areas, cells²
  double gapArea = 0.0;      ///< area(block − ∪ parcels), cells²
  double overlapArea = 0.0;  ///< Σ areas − area(∪ parcels), cells²
  double outsideArea = 0.0;  ///< area(∪ parcels − block), cells²
  int invalidParcels = 0;    ///< parcels failing GEOSisValid
};
TilingCheck checkTiling(const Polygon& block, const std::vector<VectorParcel>& parcels,
                        const geos::Context& geos);

/// L1 distance between the area shares of uses of the simulated block and of the vector parcels;
/// 0 = identical, 2 = disjoint. Shares follow Eq. 3.3: below `undevelopedSwitch` they are shares of
/// developed land (undeveloped land gets no parcels then, spec E4), at or above it shares of all land
/// with undeveloped as a use.
double useShareDistance(const SimBlockSummary& sim, const std::vector<VectorParcel>& parcels,
                        double undevelopedSwitch = LandUseOptions{}.undevelopedSwitch);

/// Totals over a run, for the acceptance figures.
struct ParcelsQuality {
  int blocks = 0;
  int parcels = 0;
  int invalidParcels = 0;
  double worstGapRatio = 0.0;        ///< max over blocks of gap / block area
  double worstOverlapRatio = 0.0;    ///< max over blocks of (overlap + outside) / block area
  int developedWithoutFrontage = 0;  ///< developed parcels whose longest frontage < the minimum
  int developedParcels = 0;
  int shortfallBlocks = 0;            ///< blocks with fewer parcels than their target
  double meanUseShareDistance = 0.0;  ///< mean over blocks with simulated parcels
  double simPopulation = 0.0, outputPopulation = 0.0, ignoredPopulation = 0.0;
  int ignoredUses = 0;
  /// |output − (sim − ignored)| / sim (0 when sim is 0)
  double populationError() const {
    return simPopulation > 0.0
               ? std::fabs(outputPopulation - (simPopulation - ignoredPopulation)) / simPopulation
               : 0.0;
  }
};
ParcelsQuality assessParcels(const std::vector<ParcelBlock>& blocks, const ParcelsResult& result,
                             const ParcelsOptions& options);

}  // namespace urbanvec::vectorize::parcels
