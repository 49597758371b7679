// The use of untagged land (issue 20): see untagged_land.hpp.
#include "urbanvec/gridify/untagged_land.hpp"

namespace urbanvec::gridify {

namespace {

/// The key with the largest value (the first in key order on ties); nothing when all are <= 0.
template <class K>
std::optional<K> largest(const std::map<K, double>& values) {
  std::optional<K> best;
  double most = 0.0;
  for (const auto& [key, value] : values)
    if (value > most) {
      most = value;
      best = key;
    }
  return best;
}

}  // namespace

std::pair<std::optional<LandUse>, UntaggedRule> inferUntaggedUse(const BlockEvidence& block,
                                                                 const UntaggedLandOptions& options) {
  if (!options.enabled) return {std::nullopt, UntaggedRule::Tagged};
  if (block.external) return {std::nullopt, UntaggedRule::Outside};
  if (block.cells == 0 ||
      static_cast<double>(block.taggedCells) > options.maxTaggedShare * static_cast<double>(block.cells))
    return {std::nullopt, UntaggedRule::Tagged};
  if (const std::optional<LandUse> use = largest(block.buildingArea)) return {*use, UntaggedRule::Buildings};
  double total = 0.0;
  std::map<LandUse, double> byUse;
  for (const auto& [street, metres] : block.streetLength) {
    total += metres;
    for (const auto& [cls, use] : options.streetUses)
      if (cls == street) byUse[use] += metres;
  }
  if (const std::optional<LandUse> use = largest(byUse); use && byUse[*use] >= options.minStreetShare * total)
    return {*use, UntaggedRule::Streets};
  if (options.defaultUse == LandUse::Unused) return {std::nullopt, UntaggedRule::Default};
  return {options.defaultUse, UntaggedRule::Default};
}

}  // namespace urbanvec::gridify
