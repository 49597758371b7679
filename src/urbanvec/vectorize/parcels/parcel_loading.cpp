// Stage A5 (spec §3 A5), with the [INFERENCE] rule that a parcel whose block (first patch's, or the
// majority's) is none is attached to nothing and counted.
#include "urbanvec/vectorize/parcels/parcel_loading.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <unordered_map>

namespace urbanvec::vectorize {

std::string peopleText(double people) {
  char text[64];
  std::snprintf(text, sizeof text, "%.1f", people);
  std::string s = text;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  if (s == "-0") s = "0";
  return s + (s == "1" ? " person" : " people");
}

std::string unattachedParcelsWarning(const ParcelLoading& loading, bool majorityBlock) {
  if (loading.unattached == 0) return {};
  static const char* const land[4] = {"open land (unused cells)", "road", "water", "reserved land"};
  std::string s = std::to_string(loading.unattached) + " input parcels (" +
                  peopleText(loading.unattachedPopulation) + ")" +
                  (majorityBlock ? " lie mostly" : " have their first cell");
  int kinds = 0, only = 0;
  for (int k = 0; k < 4; ++k)
    if (loading.unattachedOn[k] > 0) ++kinds, only = k;
  if (kinds == 1) {
    s += std::string(" on ") + land[only] + " outside every block";
  } else {
    s += " outside every block (";
    bool first = true;
    for (int k = 0; k < 4; ++k)
      if (loading.unattachedOn[k] > 0) {
        s += (first ? "" : ", ") + std::to_string(loading.unattachedOn[k]) + " on " + land[k];
        first = false;
      }
    s += ")";
  }
  s += ": no block takes them, so they are left out of the parcels layer";
  // peopleText rounds: "no population is lost" only when there is none at all.
  if (loading.unattachedPopulation > 0.0)
    s += " with their " + peopleText(loading.unattachedPopulation);
  else
    s += " and no population is lost";
  return s;
}

ParcelLoading loadParcels(const VectorizeInput& input, const Grid<std::int32_t>& blockOf,
                          std::vector<SimBlock>& blocks, const Progress& progress,
                          const ParcelLoadingOptions& options) {
  ParcelLoading out;
  const Grid<std::int32_t>& ids = input.parcelIds;
  if (ids.size() == 0) {
    reportProgress(progress, 1.0, "parcels");
    return out;
  }
  const int w = ids.width, h = ids.height;
  std::unordered_map<std::int32_t, int> indexOf;
  for (int i = 0; i < w * h; ++i) {
    const std::int32_t id = ids.cells[i];
    if (id <= 0) continue;
    auto [it, isNew] = indexOf.try_emplace(id, static_cast<int>(out.parcels.size()));
    if (isNew) {
      SimParcel p;
      p.id = id;
      out.parcels.push_back(p);
    }
    out.parcels[it->second].patches.push_back(i);
  }
  std::unordered_map<std::int32_t, const ParcelRecord*> record;
  for (const ParcelRecord& r : input.parcelTable) record[r.id] = &r;
  const bool hasDensity = input.density.size() == ids.size();
  for (SimParcel& p : out.parcels) {
    p.area = static_cast<double>(p.patches.size());
    Vec2 sum;
    double people = 0;
    std::array<int, kLandUseClassCount> votes{};
    for (int i : p.patches) {
      sum += patchCentre(input.landUse, i % w, i / w);
      if (hasDensity) people += input.density.cells[i];
      const std::uint8_t u = input.landUse.cells[i];
      if (u < kLandUseClassCount) ++votes[u];
    }
    p.center = sum / p.area;
    auto it = record.find(p.id);
    if (it != record.end()) {
      p.use = it->second->use;
      p.population = it->second->population;
    } else {
      // Majority use of its patches; on a tie the lower class code wins.
      int best = 0;
      for (int u = 1; u < kLandUseClassCount; ++u)
        if (votes[u] > votes[best]) best = u;
      p.use = static_cast<LandUse>(best);
      p.population = people;
      ++out.derivedFromRaster;
    }
    p.simBlock = blockOf.cells[p.patches.front()];
    if (options.majorityBlock) {
      std::vector<std::int32_t> in;
      in.reserve(p.patches.size());
      for (int i : p.patches) in.push_back(blockOf.cells[i]);
      std::sort(in.begin(), in.end());
      const auto count = [&](std::int32_t block) {
        const auto range = std::equal_range(in.begin(), in.end(), block);
        return range.second - range.first;
      };
      // Strictly more patches than the first patch's block; among equals a block before none, then
      // the lower block index.
      const std::int32_t first = p.simBlock;
      auto most = count(first);
      for (auto run = in.begin(); run != in.end();) {
        const auto end = std::upper_bound(run, in.end(), *run);
        if (end - run > most || (end - run == most && p.simBlock < 0 && p.simBlock != first && *run >= 0)) {
          most = end - run;
          p.simBlock = *run;
        }
        run = end;
      }
    }
    if (p.simBlock < 0) {
      ++out.unattached;
      out.unattachedPopulation += p.population;
      // Only open land, road, water and reserved land lie outside every block (A2).
      // Under the documents' rule the first cell is the one outside every block.
      std::array<int, 4> land{};
      for (int i : p.patches) {
        if (blockOf.cells[i] >= 0 || (!options.majorityBlock && i != p.patches.front())) continue;
        const std::uint8_t u = input.landUse.cells[i];
        ++land[isRoadCode(u)                                       ? 1
               : u == static_cast<std::uint8_t>(LandUse::Water)    ? 2
               : u == static_cast<std::uint8_t>(LandUse::Reserved) ? 3
                                                                   : 0];
      }
      ++out.unattachedOn[std::max_element(land.begin(), land.end()) - land.begin()];
    }
  }
  std::sort(out.parcels.begin(), out.parcels.end(),
            [](const SimParcel& a, const SimParcel& b) { return a.id < b.id; });
  for (size_t k = 0; k < out.parcels.size(); ++k)
    if (out.parcels[k].simBlock >= 0) blocks[out.parcels[k].simBlock].parcels.push_back(static_cast<int>(k));
  reportProgress(progress, 1.0, "parcels");
  return out;
}

}  // namespace urbanvec::vectorize
