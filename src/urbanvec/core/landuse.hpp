// The nine land-use classes of the gridded input (CONVENTIONS.md "Gridded input"; spec §2.1).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace urbanvec {

enum class LandUse : std::uint8_t {
  Unused = 0,
  Water = 1,
  SecondaryRoad = 2,
  PrimaryRoad = 3,
  Residential = 4,
  Commercial = 5,
  Industrial = 6,
  Park = 7,
  Reserved = 8,
};

/// The raster value written for "no data" in landuse.tif; read back as Unused.
constexpr std::uint8_t kLandUseNodata = 255;
constexpr int kLandUseClassCount = 9;

/// Lower-case class name as used in CSV tables and output fields ("residential", "secondary_road").
std::string_view landUseName(LandUse use);
/// Parses a class name (case-insensitive; "secondary road", "secondary_road" and "secondary" accepted
/// for roads). Returns nothing for an unknown name.
std::optional<LandUse> parseLandUse(std::string_view name);
/// The class of a raster byte; nodata and values above 8 are Unused.
LandUse landUseFromCode(int code);

inline bool isRoad(LandUse u) { return u == LandUse::SecondaryRoad || u == LandUse::PrimaryRoad; }
/// Residential, commercial, industrial or park: land that a parcel is developed for.
inline bool isDeveloped(LandUse u) {
  return u == LandUse::Residential || u == LandUse::Commercial || u == LandUse::Industrial ||
         u == LandUse::Park;
}

}  // namespace urbanvec
