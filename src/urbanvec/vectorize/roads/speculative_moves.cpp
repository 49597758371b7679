#include "urbanvec/vectorize/roads/speculative_moves.hpp"

#include <algorithm>
#include <condition_variable>
#include <limits>
#include <mutex>

#include "urbanvec/core/parallel.hpp"

namespace urbanvec::vectorize {

namespace {
constexpr std::size_t kItemsAhead = 2;
}  // namespace

/// A thread's copy of the graph, its index, and the positions of the copy before the item it runs.
struct SpeculativeMoves::Worker {
  RoadGraph graph;
  std::unique_ptr<NodeIndex> index;
  std::vector<Vec2> positions;
  std::size_t synced = 0;  ///< log entries applied to the copy
};

/// An item run on a worker's copy: its footprint, the positions it wrote and how far the copy was
/// synchronised when it ran.
struct SpeculativeMoves::Proposal {
  bool ready = false;
  std::size_t synced = 0;
  ReadFootprint footprint;
  std::vector<std::pair<int, Vec2>> writes;
};

SpeculativeMoves::SpeculativeMoves(RoadGraph& graph, std::size_t workers, double indexBucket)
    : graph_(graph) {
  index_ = std::make_unique<NodeIndex>(graph_, indexBucket);
  // Each worker holds a copy of the graph, and the commits are serial: beyond a few workers the copies
  // cost memory (about 80 MB each at 4096² cells) and buy nothing. The output does not depend on it.
  constexpr std::size_t kMostWorkers = 4;
  workers = std::min(workers, kMostWorkers);
  if (workers < 2) return;
  committed_.resize(graph_.nodes.size());
  for (std::size_t i = 0; i < graph_.nodes.size(); ++i) committed_[i] = graph_.nodes[i].p;
  stamp_.assign(graph_.nodes.size(), 0);
  for (std::size_t w = 0; w < workers; ++w) {
    auto worker = std::make_unique<Worker>();
    worker->graph = graph_;
    worker->index = std::make_unique<NodeIndex>(worker->graph, indexBucket);  // the same buckets as index_
    worker->positions = committed_;
    workers_.push_back(std::move(worker));
  }
}

SpeculativeMoves::~SpeculativeMoves() = default;

bool SpeculativeMoves::stillValid(const Proposal& proposal) {
  if (proposal.synced == log_.size()) return true;
  // Marks on the nodes whose positions, or whose neighbours' positions, the item read.
  if (++epoch_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
  for (int k : proposal.footprint.nodes) stamp_[k] = epoch_;
  for (int k : proposal.footprint.hits) stamp_[k] = epoch_;
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto& [p, r] : proposal.footprint.queries) {
    x0 = std::min(x0, p.x - r);
    y0 = std::min(y0, p.y - r);
    x1 = std::max(x1, p.x + r);
    y1 = std::max(y1, p.y + r);
  }
  for (std::size_t e = proposal.synced; e < log_.size(); ++e) {
    const int w = log_[e].first;
    if (stamp_[w] == epoch_) return false;
    for (int q : graph_.nodes[w].links)
      if (stamp_[q] == epoch_) return false;
    // A node that was no hit of a query may have moved into it: it would be one now.
    const Vec2 now = committed_[w];
    if (now.x < x0 || now.x > x1 || now.y < y0 || now.y > y1) continue;
    for (const auto& [p, r] : proposal.footprint.queries)
      if (distance(now, p) <= r) return false;
  }
  return true;
}

void SpeculativeMoves::commit(Proposal& proposal, std::size_t item, const Item& run) {
  if (!stillValid(proposal)) {
    ++reruns_;
    proposal.footprint = ReadFootprint();
    run(item, graph_, *index_, &proposal.footprint);
    proposal.writes.clear();
    for (int k : proposal.footprint.nodes)
      if (!(graph_.nodes[k].p == committed_[k])) {
        proposal.writes.emplace_back(k, graph_.nodes[k].p);
        committed_[k] = graph_.nodes[k].p;  // listed once
      }
  }
  for (const auto& [k, p] : proposal.writes) {
    graph_.nodes[k].p = p;
    committed_[k] = p;
    log_.emplace_back(k, p);
  }
  proposal = Proposal();  // frees its memory; `ready` is no longer needed
}

void SpeculativeMoves::run(std::size_t n, const Item& item, const std::function<void(std::size_t)>& tick) {
  if (workers_.empty()) {
    for (std::size_t i = 0; i < n; ++i) {
      item(i, graph_, *index_, nullptr);
      if (tick) tick(1);
    }
    return;
  }
  std::vector<Proposal> proposals(n);
  std::size_t next = 0;  // the first item not committed
  std::mutex mutex;
  std::condition_variable committed;
  bool failed = false;
  // A worker starts an item at most kItemsAhead items per worker past the first one not committed: runs
  // further ahead see positions that are mostly stale by their commit (on the 1024^2 mosaic at load 4,
  // 650-720 B7 steps ran again without the bound, 30-50 with it).
  const std::size_t ahead = kItemsAhead * workers_.size();
  runParallel(
      workers_.size(), n,
      [&](std::size_t i, std::size_t w) {
        Worker& worker = *workers_[w];
        Proposal proposal;
        {
          std::unique_lock<std::mutex> lock(mutex);
          committed.wait(lock, [&] { return failed || i < next + ahead; });
          if (failed) return;  // an earlier item threw: runParallel rethrows it
          for (; worker.synced < log_.size(); ++worker.synced) {
            const auto& [k, p] = log_[worker.synced];
            worker.graph.nodes[k].p = p;
            worker.positions[k] = p;
          }
          proposal.synced = worker.synced;
        }
        try {
          item(i, worker.graph, *worker.index, &proposal.footprint);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex);
          failed = true;
          committed.notify_all();
          throw;
        }
        // The item's moves (each node once), then the copy back to the positions it ran on.
        for (int k : proposal.footprint.nodes) {
          Vec2& p = worker.graph.nodes[k].p;
          if (p == worker.positions[k]) continue;
          proposal.writes.emplace_back(k, p);
          p = worker.positions[k];
        }
        proposal.ready = true;
        std::lock_guard<std::mutex> lock(mutex);
        proposals[i] = std::move(proposal);
        try {
          for (; next < n && proposals[next].ready; ++next) commit(proposals[next], next, item);
        } catch (...) {
          failed = true;
          committed.notify_all();
          throw;
        }
        committed.notify_all();
      },
      tick);
  for (; next < n; ++next) commit(proposals[next], next, item);
}

}  // namespace urbanvec::vectorize
