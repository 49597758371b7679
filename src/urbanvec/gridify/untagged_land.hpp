// The use of untagged land (issue 20, "Land use where the map has none"): a block of the street
// network inside the mapped area that carries no land-use tag takes the use its buildings (with their
// shop/amenity/building tags) suggest, else the use its bounding streets suggest, else a default;
// land outside the street network's urban extent (faces open to the grid's border) stays unused.
// Plain data in, so any command can reuse the rule: gridify gathers the evidence per block.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "urbanvec/core/landuse.hpp"

namespace urbanvec::gridify {

struct UntaggedLandOptions {
  /// Off = untagged land stays unused (gridify's rule before issue 20).
  bool enabled = true;
  /// A block counts as untagged when at most this share (0..1) of its cells lies under a land-use
  /// polygon (any tag, also explicit construction/brownfield).
  double maxTaggedShare = 0.1;
  /// Street classes (OSM highway values) and the use their blocks take; a block whose bounding
  /// streets of these classes make at least minStreetShare of its bounding street length takes the
  /// use with the longest length. An industrial estate's service roads are a user's addition
  /// (e.g. -street-use service=industrial with -service-roads).
  std::vector<std::pair<std::string, LandUse>> streetUses = {{"residential", LandUse::Residential},
                                                             {"living_street", LandUse::Residential}};
  double minStreetShare = 0.5;
  /// The use of an untagged block inside the urban extent with no building and no telling street;
  /// Unused leaves it empty.
  LandUse defaultUse = LandUse::Residential;
};

/// What gridify knows about one block (a face of the street network minus water).
struct BlockEvidence {
  std::size_t cells = 0;        ///< land cells of the block
  std::size_t taggedCells = 0;  ///< of those, under a land-use polygon
  bool external = false;        ///< open to the grid's border: outside the urban extent
  /// Footprint area (m²) of the buildings whose point lies in the block, by their use (their own tag,
  /// else the building default).
  std::map<LandUse, double> buildingArea;
  /// Length (m) of street centreline along the block's edge, by street class.
  std::map<std::string, double> streetLength;
};

/// Which rule gave a block its use.
enum class UntaggedRule { Tagged, Outside, Buildings, Streets, Default };

/// The use untagged land of the block takes, and the rule that gave it; nothing (with Tagged or
/// Outside) when the block is tagged, external, or the inference is off.
std::pair<std::optional<LandUse>, UntaggedRule> inferUntaggedUse(const BlockEvidence& block,
                                                                 const UntaggedLandOptions& options);

}  // namespace urbanvec::gridify
