#include "urbanvec/core/landuse.hpp"

#include <algorithm>
#include <array>
#include <cctype>

namespace urbanvec {

namespace {
constexpr std::array<std::string_view, kLandUseClassCount> kNames = {
    "unused", "water", "secondary_road", "primary_road", "residential",
    "commercial", "industrial", "park", "reserved"};
}

std::string_view landUseName(LandUse use) { return kNames[static_cast<size_t>(use)]; }

std::optional<LandUse> parseLandUse(std::string_view name) {
  std::string key;
  for (char ch : name) {
    if (ch == ' ' || ch == '-') ch = '_';
    key.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(ch))));
  }
  while (!key.empty() && key.back() == '_') key.pop_back();
  if (key == "secondary") return LandUse::SecondaryRoad;
  if (key == "primary") return LandUse::PrimaryRoad;
  for (size_t i = 0; i < kNames.size(); ++i)
    if (key == kNames[i]) return static_cast<LandUse>(i);
  return std::nullopt;
}

LandUse landUseFromCode(int code) {
  if (code < 0 || code >= kLandUseClassCount) return LandUse::Unused;
  return static_cast<LandUse>(code);
}

}  // namespace urbanvec
