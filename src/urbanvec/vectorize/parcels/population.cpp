// Spec §3 E6 (thesis §3.4.3 "Population Assignment") with the [INFERENCE] choices of Q25: groups are
// formed by area, a group's centre is its area-weighted centroid, and the mapping takes the globally
// closest (vector unit, unmapped simulated parcel) pair first.
#include "urbanvec/vectorize/parcels/population.hpp"

#include <algorithm>
#include <tuple>

namespace urbanvec::vectorize::parcels {

namespace {

struct Unit {
  std::vector<size_t> members;
  double area = 0.0;
  Vec2 centre;
};

/// Spreads `people` over `members` in proportion to their area (equally when all are empty).
void spread(double people, const std::vector<size_t>& members, const std::vector<UseParcel>& parcels,
            std::vector<double>& population) {
  double total = 0.0;
  for (size_t m : members) total += parcels[m].area;
  for (size_t m : members)
    population[m] +=
        total > 0.0 ? people * parcels[m].area / total : people / static_cast<double>(members.size());
}

}  // namespace

PopulationResult assignPopulation(const std::vector<UseParcel>& parcels, const std::vector<UseChoice>& uses,
                                  const SimBlockSummary& sim) {
  PopulationResult result;
  result.population.assign(parcels.size(), 0.0);
  std::vector<LandUse> simUses;
  for (const SimParcel& p : sim.parcels) {
    result.simPopulation += p.population;
    if (std::find(simUses.begin(), simUses.end(), p.use) == simUses.end()) simUses.push_back(p.use);
  }
  std::sort(simUses.begin(), simUses.end());
  for (LandUse use : simUses) {
    std::vector<const SimParcel*> simParcels;
    double usePopulation = 0.0;
    for (const SimParcel& p : sim.parcels)
      if (p.use == use) {
        simParcels.push_back(&p);
        usePopulation += p.population;
      }
    std::vector<Unit> units;
    std::vector<size_t> allOfUse;
    for (size_t k = 0; k < parcels.size(); ++k)
      if (!uses[k].undeveloped && uses[k].use == use) {
        units.push_back({{k}, parcels[k].area, parcels[k].centre});
        allOfUse.push_back(k);
      }
    if (units.empty()) {
      if (usePopulation > 0.0) {
        result.ignoredPopulation += usePopulation;
        ++result.ignoredUses;
      }
      continue;
    }
    // GT: group the two smallest units until the counts match.
    while (units.size() > simParcels.size()) {
      std::stable_sort(units.begin(), units.end(),
                       [](const Unit& a, const Unit& b) { return a.area < b.area; });
      Unit merged;
      merged.members = units[0].members;
      merged.members.insert(merged.members.end(), units[1].members.begin(), units[1].members.end());
      merged.area = units[0].area + units[1].area;
      merged.centre = merged.area > 0.0
                          ? (units[0].centre * units[0].area + units[1].centre * units[1].area) / merged.area
                          : (units[0].centre + units[1].centre) * 0.5;
      units.erase(units.begin(), units.begin() + 2);
      units.push_back(std::move(merged));
    }
    // Greedy nearest pairs, globally closest first.
    std::vector<std::tuple<double, size_t, size_t>> pairs;
    for (size_t u = 0; u < units.size(); ++u)
      for (size_t s = 0; s < simParcels.size(); ++s)
        pairs.emplace_back(distance(units[u].centre, simParcels[s]->centre), u, s);
    std::sort(pairs.begin(), pairs.end());
    std::vector<char> unitMapped(units.size(), 0), simMapped(simParcels.size(), 0);
    for (const auto& [d, u, s] : pairs) {
      if (unitMapped[u] || simMapped[s]) continue;
      unitMapped[u] = simMapped[s] = 1;
      spread(simParcels[s]->population, units[u].members, parcels, result.population);
    }
    // LT: simulated parcels outside the mapped subset go to all of the use's parcels by area.
    for (size_t s = 0; s < simParcels.size(); ++s)
      if (!simMapped[s]) spread(simParcels[s]->population, allOfUse, parcels, result.population);
  }
  return result;
}

}  // namespace urbanvec::vectorize::parcels
