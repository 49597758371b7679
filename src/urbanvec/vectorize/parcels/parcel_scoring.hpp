// Stage E5 of the vectorizer: scoring of one generate-and-test iteration (spec §3 E5, §4.3; thesis
// §3.4.3 "Scoring of Results"): cost = cu + cd + cs; the lowest of the block's tries is kept.
#pragma once

#include <vector>

#include "urbanvec/vectorize/parcels/land_use_assignment.hpp"

namespace urbanvec::vectorize::parcels {

/// Normalization of the size term (spec §4.3 "scale caveat").
enum class SizeCostNormalization {
  None,              ///< faithful: cs in cells²
  SimBlockArea,      ///< cs / simulated block area
  MeanSimParcelArea  ///< cs / mean simulated parcel area
};

struct ScoringOptions {
  /// Default: faithful (spec §6 "Cost normalization of cs: none").
  SizeCostNormalization sizeNormalization = SizeCostNormalization::None;
};

struct Cost {
  double use = 0.0;       ///< cu = Σ_i |us_i − u_i| over candidate uses (+ undeveloped when active)
  double distance = 0.0;  ///< cd = Σ_parcels d_assigned / BBD
  double size = 0.0;      ///< cs = Σ_parcels |a − a_i|, a_i = nearest simulated parcel of the same use
  double total() const { return use + distance + size; }
};

/// Scores one assignment. Undeveloped parcels enter cu only (spec §4.3 [INFERENCE]).
Cost scoreParcels(const std::vector<UseParcel>& parcels, const std::vector<UseChoice>& uses, double blockArea,
                  double blockDiagonal, const UseModel& model, const SimBlockSummary& sim,
                  const ScoringOptions& options);

}  // namespace urbanvec::vectorize::parcels
