// Step 0 of the shrinking pipeline (spec §B.2): clean the input city, street-tagged ways only.
#pragma once

#include "urbanvec/shrink/city.hpp"
#include "urbanvec/shrink/shrink_options.hpp"

namespace urbanvec::shrink {

struct CleaningStats {
  int waysIn = 0;
  int waysOut = 0;
  int nodesOutsideBounds = 0;  ///< street nodes dropped for lying outside the download bounds
  int emptyWays = 0;           ///< ways (or pieces) left with fewer than 2 nodes, removed
};

/// Removes repeated consecutive nodes; with removeOutsideBounds drops every node outside the download
/// bounds and cuts the way there (each run of inside nodes is kept as a way with the same OSM id, so
/// no segment crosses the boundary, §B.2 Fig. 29); removes ways with fewer than 2 nodes. Adds no
/// intersection (the thesis's "add intersection" is off: bridges must not connect).
CleaningStats cleanCity(City& city, const CleaningOptions& options);

}  // namespace urbanvec::shrink
