// Step 5 of the shrinking pipeline (spec §B.6): connect the dead ends the skeleton introduced through
// at most m segments of the full city, as brand-new ways.
#pragma once

#include <vector>

#include "urbanvec/shrink/street_graph.hpp"

namespace urbanvec::shrink {

struct DeadEndStats {
  int deadEnds = 0;  ///< skeleton dead ends that were not dead ends in the city
  int connected = 0;
  int remaining = 0;  ///< no skeleton node within m segments
};

/// `inSkeleton`: per street, nonzero when it is in the skeleton. For every skeleton dead end (one
/// neighbour) that had more in the full city, in node order, finds the shortest path (Euclidean
/// length) of at most mDegree segments, avoiding skeleton segments, to another skeleton node, and
/// returns it as a new way (ids -1, -2, ... from `firstNewId` downwards; highway of its first
/// segment's street). A path ends at the first skeleton node it meets, so its interior nodes get
/// degree 2 and no new dead end appears.
std::vector<CityWay> connectDeadEnds(const City& city, const StreetGraph& graph,
                                     const std::vector<char>& inSkeleton, int mDegree,
                                     std::int64_t firstNewId = -1, DeadEndStats* stats = nullptr);

}  // namespace urbanvec::shrink
