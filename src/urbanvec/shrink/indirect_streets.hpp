// Step 1 of the shrinking pipeline (spec §B.3): the important streets — members of a place, the
// nearest street of every node of a non-street landmark (proxStrThreshold), and the streets with a
// node inside a `bounding` area.
#pragma once

#include <vector>

#include "urbanvec/shrink/city.hpp"
#include "urbanvec/shrink/shrink_options.hpp"

namespace urbanvec::shrink {

struct StreetImportance {
  bool important = false;
  bool indirect = false;  ///< added by §B.3, not a member of the place
  double appearW = 0.0;   ///< the highest appearW of the places that make it important
  int place = -1;         ///< index of that place
};

struct IndirectStats {
  int direct = 0;               ///< streets named as members
  int nearest = 0;              ///< streets added as a landmark's nearest street
  int insideBounding = 0;       ///< streets added for a node inside a bounding area
  int placesWithoutStreet = 0;  ///< non-street places with no street within the threshold
};

std::vector<StreetImportance> findImportantStreets(const City& city, const std::vector<Place>& places,
                                                   const SelectionOptions& options,
                                                   IndirectStats* stats = nullptr);

}  // namespace urbanvec::shrink
