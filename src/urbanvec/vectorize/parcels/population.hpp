// Stage E6 of the vectorizer: population assignment (spec §3 E6, Q25, §11.7; thesis §3.4.3
// "Population Assignment"). Per land use, vector parcels are mapped one-to-one to simulated parcels
// (grouping the two smallest vector parcels while there are more of them), each simulated parcel's
// population goes to its vector parcel or group (by area), unmapped simulated parcels are spread over
// the use's vector parcels by area, and a use without vector parcels is ignored (and counted).
#pragma once

#include <vector>

#include "urbanvec/vectorize/parcels/land_use_assignment.hpp"

namespace urbanvec::vectorize::parcels {

struct PopulationResult {
  std::vector<double> population;  ///< per parcel, people; 0 for undeveloped parcels
  double simPopulation = 0.0;      ///< total of the simulated parcels
  double ignoredPopulation = 0.0;  ///< population of uses with no vector parcel
  int ignoredUses = 0;             ///< uses with simulated population but no vector parcel
};

PopulationResult assignPopulation(const std::vector<UseParcel>& parcels, const std::vector<UseChoice>& uses,
                                  const SimBlockSummary& sim);

}  // namespace urbanvec::vectorize::parcels
