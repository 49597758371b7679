// Steps 3 & 4 of the shrinking pipeline (spec §B.5): join the clusters of selected streets with A* on
// the full city graph (impDistBalance cost), then delete clusters left apart that hold no important
// street.
#pragma once

#include <vector>

#include "urbanvec/shrink/indirect_streets.hpp"
#include "urbanvec/shrink/shrink_options.hpp"
#include "urbanvec/shrink/street_graph.hpp"
#include "urbanvec/shrink/street_selection.hpp"

namespace urbanvec::shrink {

struct ConnectionStats {
  int clusters = 0;         ///< clusters of the selected streets (§C.6 flood fill)
  int joined = 0;           ///< clusters joined to the ones before them by a path
  int unreachable = 0;      ///< clusters no path reaches
  int connectorWays = 0;    ///< streets added by the paths
  int removedClusters = 0;  ///< clusters deleted (noImpClusters)
  int removedWays = 0;
  int components = 0;  ///< components left
};

/// Per street: 0 not in the skeleton, 1 selected, 2 added as a connector. Clusters are processed by
/// increasing distance of their centroid to the centre of the streets' bounding box; each is joined
/// to an earlier one by the cheapest path, where an edge costs 0 when its street is already in the
/// skeleton or both its ends are in one cluster, else alpha * d / impW + (1 - alpha) * d (the spec's
/// [INFERENCE] reading, in metres). With removeUnimportantClusters, components without an important
/// street are deleted, except the largest one when no component has an important street.
std::vector<char> connectClusters(const City& city, const StreetGraph& graph, const Selection& selection,
                                  const std::vector<StreetImportance>& importance,
                                  const ConnectionOptions& options, ConnectionStats* stats = nullptr);

}  // namespace urbanvec::shrink
