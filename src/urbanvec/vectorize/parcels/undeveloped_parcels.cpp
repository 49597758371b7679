// Spec §3 E3: the "double the undeveloped parcels" heuristic (thesis §3.4.3, paper §3.4.1: "after the
// initial round of land use assignments").
#include "urbanvec/vectorize/parcels/undeveloped_parcels.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec::vectorize::parcels {

double undevelopedShare(const SimBlockSummary& sim) {
  return sim.area > 0.0 ? sim.undevelopedArea / sim.area : 0.0;
}

double unlistedUndevelopedShare(const SimBlockSummary& sim) {
  double listed = 0.0;
  for (const SimParcel& p : sim.parcels)
    if (p.use == LandUse::Unused) listed += p.cells;
  return sim.area > 0.0 ? std::fmax(0.0, sim.undevelopedArea - listed) / sim.area : 0.0;
}

int listedUnusedParcels(const SimBlockSummary& sim) {
  int n = 0;
  for (const SimParcel& p : sim.parcels) n += p.use == LandUse::Unused;
  return n;
}

bool needsUndevelopedExtras(const SimBlockSummary& sim, const UndevelopedOptions& options) {
  const double share =
      options.skipListedUnusedParcels ? unlistedUndevelopedShare(sim) : undevelopedShare(sim);
  return share > options.triggerShare;
}

int undevelopedExtraParcels(const SimBlockSummary& sim, int undevelopedParcels,
                            const UndevelopedOptions& options) {
  if (!needsUndevelopedExtras(sim, options)) return 0;
  const int doubled = options.skipListedUnusedParcels
                          ? std::max(0, undevelopedParcels - listedUnusedParcels(sim))
                          : undevelopedParcels;
  if (doubled <= 0) return 0;
  return static_cast<int>(std::lround(doubled * (options.multiplier - 1.0)));
}

}  // namespace urbanvec::vectorize::parcels
