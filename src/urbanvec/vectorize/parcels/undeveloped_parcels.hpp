// Stage E3 of the vectorizer: undeveloped "negative" parcels (spec §3 E3, Q21; thesis §3.4.3, paper
// §3.4.1). When more than 25% of the simulated block is undeveloped, the number of undeveloped parcels
// made by the first land-use round is doubled by further E2 splits, then land use is assigned again.
#pragma once

#include "urbanvec/vectorize/parcels/parcel_input.hpp"

namespace urbanvec::vectorize::parcels {

struct UndevelopedOptions {
  /// Extra parcels are made when the undeveloped share of the simulated block exceeds this (spec
  /// §5.4: "> 25%"), unitless.
  double triggerShare = 0.25;
  /// The undeveloped parcel count is multiplied by this (spec §5.4: ×2).
  double multiplier = 2.0;
  /// [INFERENCE] The heuristic makes up for undeveloped land the simulation lists no parcels for
  /// ("the simulation does not output undeveloped parcels"). When the input does list parcels of
  /// use unused (cadastral plots without a use), their land already has its parcels: it counts
  /// towards neither the trigger nor the doubling. false = the documents' rule on all unused land.
  bool skipListedUnusedParcels = true;
};

/// Undeveloped area / simulated block area (0 for an empty block).
double undevelopedShare(const SimBlockSummary& sim);

/// The undeveloped area no listed parcel covers / simulated block area (0 for an empty block).
double unlistedUndevelopedShare(const SimBlockSummary& sim);

/// Parcels of use unused listed by the simulation in the block.
int listedUnusedParcels(const SimBlockSummary& sim);

/// Whether the block gets extra undeveloped parcels.
bool needsUndevelopedExtras(const SimBlockSummary& sim, const UndevelopedOptions& options);

/// How many extra splits turn `undevelopedParcels` (less the listed unused parcels when
/// skipListedUnusedParcels) into multiplier × as many (0 when not triggered).
int undevelopedExtraParcels(const SimBlockSummary& sim, int undevelopedParcels,
                            const UndevelopedOptions& options);

}  // namespace urbanvec::vectorize::parcels
