// Node-moving road stages on several threads with the result of one thread (issue 21): items (an
// intersection to place, the chains of a node to straighten) run in index order on one thread, each
// reading the positions the earlier ones left. Here every worker runs items on its own copy of the
// graph against the positions committed so far, recording what the item read (ReadFootprint); the
// items are then committed in index order, and an item is run again on the committed graph only when
// a node written since its copy was synchronised lies in its footprint. The graph's topology must not
// change within a run: only node positions are written.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

/// What an item read of the node positions, enough to tell whether another node's move changes it.
struct ReadFootprint {
  /// Nodes whose positions, or whose neighbours' positions, the item read directly; every node it
  /// moved is among them.
  std::vector<int> nodes;
  /// NodeIndex::within queries (centre, radius) and every node they returned (the item may read the
  /// positions of those nodes and of their neighbours).
  std::vector<std::pair<Vec2, double>> queries;
  std::vector<int> hits;
};

/// NodeIndex::anyWithin, recording the query and the nodes visited in `footprint` when it is set. The
/// nodes the scan did not reach were not read: the answer does not depend on them (a node moving into
/// the query's disc is caught by the recorded query).
template <class Visit>
bool recordedAnyWithin(const NodeIndex& index, const Vec2& p, double r, ReadFootprint* footprint,
                       Visit&& visit) {
  if (!footprint) return index.anyWithin(p, r, visit);
  footprint->queries.emplace_back(p, r);
  return index.anyWithin(p, r, [&](int k) {
    footprint->hits.push_back(k);
    return visit(k);
  });
}

class SpeculativeMoves {
 public:
  /// One item: run it on `graph` (moving node positions only), querying `index` (built over `graph`)
  /// through recordedAnyWithin with `footprint`, which is null when nothing needs recording. An item run
  /// again replaces what its earlier run produced (its statistics included).
  using Item = std::function<void(std::size_t item, RoadGraph& graph, const NodeIndex& index,
                                  ReadFootprint* footprint)>;

  /// `workers` threads (1 = plain serial runs on `graph`); every NodeIndex has buckets of `indexBucket`
  /// cells over the positions `graph` has now.
  SpeculativeMoves(RoadGraph& graph, std::size_t workers, double indexBucket);
  ~SpeculativeMoves();
  SpeculativeMoves(const SpeculativeMoves&) = delete;
  SpeculativeMoves& operator=(const SpeculativeMoves&) = delete;

  /// Runs items 0 .. n-1 with the result of running them one after another in that order on the
  /// graph. `tick` as runParallel's (progress, on the calling thread).
  void run(std::size_t n, const Item& item, const std::function<void(std::size_t)>& tick = {});

  /// Items run again because a node in their footprint moved after their copy was synchronised.
  std::size_t reruns() const { return reruns_; }

 private:
  struct Worker;
  struct Proposal;
  void commit(Proposal& proposal, std::size_t item, const Item& run);
  bool stillValid(const Proposal& proposal);

  RoadGraph& graph_;
  std::unique_ptr<NodeIndex> index_;
  std::vector<Vec2> committed_;                   ///< graph_'s positions after the last commit
  std::vector<std::pair<int, Vec2>> log_;         ///< every committed write, in commit order
  std::vector<std::unique_ptr<Worker>> workers_;  ///< empty with one thread
  std::vector<std::uint32_t> stamp_;              ///< footprint marks of stillValid
  std::uint32_t epoch_ = 0;
  std::size_t reruns_ = 0;
};

}  // namespace urbanvec::vectorize
