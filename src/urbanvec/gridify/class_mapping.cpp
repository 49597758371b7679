// Class mapping (issue 2 §2 "Class mapping (documented, overridable by option)"; docs/gridify.md).
#include "urbanvec/gridify/class_mapping.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace urbanvec::gridify {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

const std::string* find(const Tags& tags, const char* key) {
  auto it = tags.find(key);
  return it == tags.end() || it->second.empty() ? nullptr : &it->second;
}

using Table = std::map<std::string, LandUse>;

const Table& landuseTable() {
  static const Table t{
      {"residential", LandUse::Residential}, {"commercial", LandUse::Commercial},
      {"retail", LandUse::Commercial},       {"industrial", LandUse::Industrial},
      {"port", LandUse::Industrial},         {"depot", LandUse::Industrial},
      {"quarry", LandUse::Industrial},       {"garages", LandUse::Residential},
      {"grass", LandUse::Park},              {"recreation_ground", LandUse::Park},
      {"village_green", LandUse::Park},      {"forest", LandUse::Park},
      {"meadow", LandUse::Park},             {"allotments", LandUse::Park},
      {"flowerbed", LandUse::Park},          {"orchard", LandUse::Park},
      {"vineyard", LandUse::Park},           {"farmland", LandUse::Park},
      {"cemetery", LandUse::Reserved},       {"military", LandUse::Reserved},
      {"railway", LandUse::Reserved},        {"religious", LandUse::Reserved},
      {"education", LandUse::Reserved},      {"institutional", LandUse::Reserved},
      {"basin", LandUse::Water},             {"reservoir", LandUse::Water},
      {"construction", LandUse::Unused},     {"brownfield", LandUse::Unused},
      {"greenfield", LandUse::Unused},
  };
  return t;
}

const Table& leisureTable() {
  static const Table t{
      {"park", LandUse::Park},          {"garden", LandUse::Park},         {"pitch", LandUse::Park},
      {"playground", LandUse::Park},    {"sports_centre", LandUse::Park},  {"stadium", LandUse::Park},
      {"golf_course", LandUse::Park},   {"nature_reserve", LandUse::Park}, {"track", LandUse::Park},
      {"dog_park", LandUse::Park},      {"common", LandUse::Park},         {"recreation_ground", LandUse::Park},
      {"swimming_pool", LandUse::Park}, {"marina", LandUse::Water},
  };
  return t;
}

/// Public institutions whose grounds are not parcels for sale: reserved. Other amenities: commercial.
const Table& amenityTable() {
  static const Table t{
      {"school", LandUse::Reserved},        {"university", LandUse::Reserved},
      {"college", LandUse::Reserved},       {"kindergarten", LandUse::Reserved},
      {"hospital", LandUse::Reserved},      {"place_of_worship", LandUse::Reserved},
      {"grave_yard", LandUse::Reserved},    {"prison", LandUse::Reserved},
      {"townhall", LandUse::Reserved},      {"police", LandUse::Reserved},
      {"fire_station", LandUse::Reserved},  {"parking", LandUse::Reserved},
      {"bus_station", LandUse::Reserved},   {"ferry_terminal", LandUse::Reserved},
  };
  return t;
}

const Table& buildingTable() {
  static const Table t{
      {"house", LandUse::Residential},       {"detached", LandUse::Residential},
      {"apartments", LandUse::Residential},  {"residential", LandUse::Residential},
      {"terrace", LandUse::Residential},     {"semidetached_house", LandUse::Residential},
      {"dormitory", LandUse::Residential},   {"bungalow", LandUse::Residential},
      {"villa", LandUse::Residential},       {"commercial", LandUse::Commercial},
      {"retail", LandUse::Commercial},       {"office", LandUse::Commercial},
      {"hotel", LandUse::Commercial},        {"supermarket", LandUse::Commercial},
      {"kiosk", LandUse::Commercial},        {"industrial", LandUse::Industrial},
      {"warehouse", LandUse::Industrial},    {"factory", LandUse::Industrial},
      {"manufacture", LandUse::Industrial},  {"church", LandUse::Reserved},
      {"cathedral", LandUse::Reserved},      {"chapel", LandUse::Reserved},
      {"school", LandUse::Reserved},         {"hospital", LandUse::Reserved},
      {"university", LandUse::Reserved},     {"public", LandUse::Reserved},
      {"government", LandUse::Reserved},     {"civic", LandUse::Reserved},
      {"train_station", LandUse::Reserved},  {"military", LandUse::Reserved},
  };
  return t;
}

std::optional<LandUse> lookup(const Table& table, const std::string* value) {
  if (!value) return std::nullopt;
  auto it = table.find(lower(*value));
  if (it == table.end()) return std::nullopt;
  return it->second;
}

}  // namespace

std::optional<LandUse> roadClassFor(const std::string& highway, const RoadClassMapping& mapping) {
  const std::string v = lower(highway);
  if (v.empty()) return std::nullopt;
  if (std::find(mapping.primary.begin(), mapping.primary.end(), v) != mapping.primary.end())
    return LandUse::PrimaryRoad;
  if (std::find(mapping.secondary.begin(), mapping.secondary.end(), v) != mapping.secondary.end())
    return LandUse::SecondaryRoad;
  return std::nullopt;
}

std::optional<LandUse> areaUseForTags(const Tags& tags) {
  if (const std::string* natural = find(tags, "natural")) {
    const std::string n = lower(*natural);
    if (n == "water" || n == "bay") return LandUse::Water;
    if (n == "wood" || n == "scrub" || n == "grassland" || n == "heath" || n == "beach") return LandUse::Park;
  }
  if (const std::string* waterway = find(tags, "waterway")) {
    const std::string w = lower(*waterway);
    if (w == "riverbank" || w == "dock" || w == "canal") return LandUse::Water;
  }
  if (auto u = lookup(landuseTable(), find(tags, "landuse"))) return u;
  if (auto u = lookup(leisureTable(), find(tags, "leisure"))) return u;
  if (find(tags, "military") || find(tags, "aeroway") || find(tags, "railway")) return LandUse::Reserved;
  if (auto u = lookup(amenityTable(), find(tags, "amenity"))) return u;
  if (find(tags, "amenity") || find(tags, "shop") || find(tags, "office")) return LandUse::Commercial;
  if (const std::string* tourism = find(tags, "tourism")) {
    const std::string t = lower(*tourism);
    if (t == "hotel" || t == "hostel" || t == "guest_house" || t == "museum") return LandUse::Commercial;
  }
  return std::nullopt;
}

std::optional<LandUse> buildingUseForTags(const Tags& tags) {
  if (auto u = lookup(buildingTable(), find(tags, "building"))) return u;
  if (auto u = lookup(amenityTable(), find(tags, "amenity"))) return u;
  if (find(tags, "shop") || find(tags, "office") || find(tags, "amenity")) return LandUse::Commercial;
  if (const std::string* tourism = find(tags, "tourism"))
    if (lower(*tourism) == "hotel") return LandUse::Commercial;
  return std::nullopt;
}

std::optional<LandUse> useFromValue(const std::string& value) {
  if (value.empty()) return std::nullopt;
  if (auto u = parseLandUse(value)) return u;
  if (auto u = lookup(landuseTable(), &value)) return u;
  if (auto u = lookup(buildingTable(), &value)) return u;
  return std::nullopt;
}

std::optional<double> parseLevels(const std::string& value) {
  if (value.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || !(v > 0.0) || v > 500.0) return std::nullopt;
  return v;
}

Tags parseHstore(const std::string& text) {
  Tags tags;
  size_t i = 0;
  auto readQuoted = [&](std::string& out) {
    while (i < text.size() && text[i] != '"') ++i;
    if (i >= text.size()) return false;
    ++i;
    out.clear();
    while (i < text.size() && text[i] != '"') {
      if (text[i] == '\\' && i + 1 < text.size()) ++i;
      out += text[i++];
    }
    if (i >= text.size()) return false;
    ++i;
    return true;
  };
  while (i < text.size()) {
    std::string key, value;
    if (!readQuoted(key)) break;
    if (!readQuoted(value)) break;
    tags[key] = value;
  }
  return tags;
}

}  // namespace urbanvec::gridify
