// Spec §3 E5 and the §4.3 reconstruction of the cost terms (thesis §3.4.3). OCR doubts: the sum over
// uses in cu is UNCERTAIN (the text writes "cu_i + cd + cs"); cs may have lost a normalizer, hence the
// option.
#include "urbanvec/vectorize/parcels/parcel_scoring.hpp"

#include <cmath>

namespace urbanvec::vectorize::parcels {

Cost scoreParcels(const std::vector<UseParcel>& parcels, const std::vector<UseChoice>& uses, double blockArea,
                  double blockDiagonal, const UseModel& model, const SimBlockSummary& sim,
                  const ScoringOptions& options) {
  Cost cost;
  const size_t n = model.uses.size();
  std::vector<double> assigned(n, 0.0);
  double undeveloped = 0.0;
  for (size_t k = 0; k < parcels.size(); ++k) {
    if (uses[k].undeveloped) {
      undeveloped += parcels[k].area;
      continue;
    }
    const int i = model.indexOf(uses[k].use);
    if (i < 0) continue;
    assigned[i] += parcels[k].area;
    // The nearest simulated parcel of the assigned use gives both d_i and a_i.
    const SimParcel* nearest = nullptr;
    double best = 1e300;
    for (const SimParcel* p : model.parcelsOfUse[i]) {
      const double d = distance(parcels[k].centre, p->centre);
      if (d < best) {
        best = d;
        nearest = p;
      }
    }
    if (!nearest) continue;
    if (blockDiagonal > 0.0) cost.distance += best / blockDiagonal;
    cost.size += std::fabs(parcels[k].area - nearest->cells);
  }
  for (size_t i = 0; i < n; ++i)
    cost.use += std::fabs(model.simShare[i] - (blockArea > 0.0 ? assigned[i] / blockArea : 0.0));
  if (model.undevelopedActive)
    cost.use += std::fabs(model.simUndevelopedShare - (blockArea > 0.0 ? undeveloped / blockArea : 0.0));
  if (options.sizeNormalization == SizeCostNormalization::SimBlockArea && sim.area > 0.0) {
    cost.size /= sim.area;
  } else if (options.sizeNormalization == SizeCostNormalization::MeanSimParcelArea && !sim.parcels.empty()) {
    double total = 0.0;
    for (const SimParcel& p : sim.parcels) total += p.cells;
    if (total > 0.0) cost.size /= total / static_cast<double>(sim.parcels.size());
  }
  return cost;
}

}  // namespace urbanvec::vectorize::parcels
