// Spec §3 E3: the "double the undeveloped parcels" heuristic (thesis §3.4.3, paper §3.4.1: "after the
// initial round of land use assignments").
#include "urbanvec/vectorize/undeveloped_parcels.hpp"

#include <cmath>

namespace urbanvec::vectorize::parcels {

double undevelopedShare(const SimBlockSummary& sim) {
  return sim.area > 0.0 ? sim.undevelopedArea / sim.area : 0.0;
}

bool needsUndevelopedExtras(const SimBlockSummary& sim, const UndevelopedOptions& options) {
  return undevelopedShare(sim) > options.triggerShare;
}

int undevelopedExtraParcels(const SimBlockSummary& sim, int undevelopedParcels,
                            const UndevelopedOptions& options) {
  if (!needsUndevelopedExtras(sim, options) || undevelopedParcels <= 0) return 0;
  return static_cast<int>(std::lround(undevelopedParcels * (options.multiplier - 1.0)));
}

}  // namespace urbanvec::vectorize::parcels
