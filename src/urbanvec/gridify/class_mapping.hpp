// From source tags to the land-use classes of the grid (issue 2 §2 "Class mapping"; the tables are in
// docs/gridify.md "Class mapping").
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/landuse.hpp"

namespace urbanvec::gridify {

using Tags = std::map<std::string, std::string>;

/// Which highway=* values are roads of which class (overridable with -primary-highways and
/// -secondary-highways). Values in neither list (footway, path, steps, track, ...) are not roads.
struct RoadClassMapping {
  std::vector<std::string> primary{"motorway", "motorway_link", "trunk", "trunk_link", "primary", "primary_link"};
  std::vector<std::string> secondary{"secondary", "secondary_link", "tertiary", "tertiary_link", "unclassified",
                                     "residential", "living_street"};
};

/// The road class of a highway value (case-insensitive), or nothing when it is not a road.
std::optional<LandUse> roadClassFor(const std::string& highway, const RoadClassMapping& mapping);

/// The class of a land-use area from its OSM tags (landuse, leisure, amenity, shop, office, tourism,
/// natural, waterway, military, aeroway, railway), or nothing when the tags name no land use we map.
std::optional<LandUse> areaUseForTags(const Tags& tags);

/// The class a building carries itself (building=house -> residential, building=retail ->
/// commercial, or the shop/office/amenity tags on it); nothing for building=yes and the like.
std::optional<LandUse> buildingUseForTags(const Tags& tags);

/// A land-use class from a free value: a class name (landUseName / parseLandUse), else the value read
/// as a landuse=* tag, then as a building=* tag. Nothing when none applies.
std::optional<LandUse> useFromValue(const std::string& value);

/// Parses OSM's building:levels ("4", "3.5", "2;3" -> the first number); nothing when unparsable or <= 0.
std::optional<double> parseLevels(const std::string& value);

/// Parses the OSM driver's other_tags field: "key"=>"value","k2"=>"v2".
Tags parseHstore(const std::string& text);

}  // namespace urbanvec::gridify
