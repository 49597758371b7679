// Stage B2 (spec §3 B2) with its [INFERENCE] choices: Jacobi update p' = mean(p, same-type
// neighbours); connection nodes are the secondary nodes whose patch touches primary; the second
// straightening uses each arm's first neighbour.
#include "urbanvec/vectorize/roads/road_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/parallel.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"
#include "urbanvec/vectorize/roads/straightening.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

double smoothingShiftLimit(NodeType type, double reach) {
  if (reach <= 0.0) return std::numeric_limits<double>::infinity();
  const double placementToCell = type == NodeType::Primary ? std::sqrt(0.5) : 0.0;
  return std::max(0.0, reach - placementToCell);
}

namespace {

/// Moves shorter than this (pw) are undone entirely rather than halved again.
constexpr double kSmallestMove = 0.05;

/// The road links (no perimeter) of `graph` at the node positions `pos`, bucketed by the unit cells
/// of a w x h frame at `origin` their bounding boxes overlap (kBucket cells square, clamped to the
/// frame), to find the links near a point.
class LinkBuckets {
 public:
  LinkBuckets(const RoadGraph& graph, const std::vector<Vec2>& pos, int w, int h, const Vec2& origin)
      : origin_(origin),
        w_(std::max(1, (w + kBucket - 1) / kBucket)),
        h_(std::max(1, (h + kBucket - 1) / kBucket)),
        start_(static_cast<size_t>(w_) * h_ + 1, 0) {
    // Counting pass, then a fill pass into one flat array.
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::int32_t> fill;
      if (pass == 1) {
        for (size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        links_.resize(start_.back());
        fill.assign(start_.begin(), start_.end() - 1);
      }
      for (size_t i = 0; i < graph.nodes.size(); ++i) {
        const RoadNode& n = graph.nodes[i];
        if (!n.alive || n.type == NodeType::Perimeter) continue;
        for (int j : n.links) {
          if (j < static_cast<int>(i) || graph.nodes[j].type == NodeType::Perimeter) continue;
          const Vec2 a = pos[i], b = pos[static_cast<size_t>(j)];
          for (int y = cy(std::min(a.y, b.y)); y <= cy(std::max(a.y, b.y)); ++y)
            for (int x = cx(std::min(a.x, b.x)); x <= cx(std::max(a.x, b.x)); ++x) {
              const size_t bucket = static_cast<size_t>(y) * w_ + x;
              if (pass == 0)
                ++start_[bucket + 1];
              else
                links_[fill[bucket]++] = {static_cast<std::int32_t>(i), j};
            }
        }
      }
    }
  }
  /// Calls f(a, b) for each link that may lie within r of p, until f returns true; true if one did.
  template <class F>
  bool anyNear(const Vec2& p, double r, F f) const {
    for (int y = cy(p.y - r); y <= cy(p.y + r); ++y)
      for (int x = cx(p.x - r); x <= cx(p.x + r); ++x) {
        const size_t bucket = static_cast<size_t>(y) * w_ + x;
        for (std::int32_t k = start_[bucket]; k < start_[bucket + 1]; ++k)
          if (f(links_[k].first, links_[k].second)) return true;
      }
    return false;
  }

 private:
  /// Bucket side, in cells: 4 keeps the index small and a 1.5-cell query within 2 x 2 buckets.
  static constexpr int kBucket = 4;
  int cx(double v) const {
    return std::clamp(static_cast<int>(std::floor((v - origin_.x) / kBucket)), 0, w_ - 1);
  }
  int cy(double v) const {
    return std::clamp(static_cast<int>(std::floor((v - origin_.y) / kBucket)), 0, h_ - 1);
  }
  Vec2 origin_;
  int w_, h_;
  std::vector<std::int32_t> start_;
  std::vector<std::pair<std::int32_t, std::int32_t>> links_;
};

/// Nodes per work item of the parallel loops below: a pass over a node costs well under a microsecond.
constexpr size_t kNodeChunk = 2048;

/// The road cells within `radius` of the old links of the nodes in [begin, end) that move, at risk of
/// being uncovered (a link covers them by less than `largest` to spare of `r`), sorted and unique.
std::vector<std::int64_t> riskCells(const RoadGraph& graph, const std::vector<char>& movable,
                                    const std::vector<Vec2>& next, const std::vector<Vec2>& old,
                                    const Grid<std::uint8_t>& cells, double radius, double r, double largest,
                                    size_t begin, size_t end) {
  std::vector<std::int64_t> out;
  for (size_t i = begin; i < end; ++i) {
    if (!movable[i] || next[i] == old[i]) continue;
    for (int j : graph.nodes[i].links) {
      if (graph.nodes[j].type == NodeType::Perimeter) continue;
      const Vec2 a = old[i], b = old[static_cast<size_t>(j)];
      forEachCellNearSegment(cells, a, b, radius, [&](int col, int row, double d) {
        if (isRoadCode(cells.at(col, row)) && d + largest > r)
          out.push_back(static_cast<std::int64_t>(row) * cells.width + col);
      });
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Undoes (sets next[i] back to the current position) the moves in `next` that would leave a road
/// cell of `cells` farther than `radius` from every road link that covered it, until none does. The
/// search for cells at risk runs on `workers` threads (each chunk's cells merged in order); the undo
/// sweeps, whose order matters, on this one.
void undoUncoveringMoves(const RoadGraph& graph, const std::vector<char>& movable, std::vector<Vec2>& next,
                         const Grid<std::uint8_t>& cells, double radius, size_t workers) {
  const double r = radius + 1e-9;
  std::vector<Vec2> old(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) old[i] = graph.nodes[i].p;
  // Moving a link's ends by at most `largest` changes a point's distance to it by at most that much:
  // only the cells a moved node's links covered by less of a margin are at risk.
  double largest = 0.0;
  for (size_t i = 0; i < next.size(); ++i) largest = std::max(largest, length(next[i] - old[i]));
  if (largest == 0.0) return;
  const LinkBuckets before(graph, old, cells.width, cells.height, frameOffset(cells));
  // Each chunk's cells sorted and unique, then merged in chunk order.
  const size_t n = graph.nodes.size();
  std::vector<std::vector<std::int64_t>> parts((n + kNodeChunk - 1) / kNodeChunk);
  runChunks(workers, n, kNodeChunk, [&](size_t begin, size_t end, size_t) {
    parts[begin / kNodeChunk] = riskCells(graph, movable, next, old, cells, radius, r, largest, begin, end);
  });
  std::vector<std::int64_t> candidates;
  for (const std::vector<std::int64_t>& part : parts) {
    const size_t middle = candidates.size();
    candidates.insert(candidates.end(), part.begin(), part.end());
    std::inplace_merge(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(middle),
                       candidates.end());
  }
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  auto centreOf = [&](std::int64_t k) {
    return patchCentre(cells, static_cast<int>(k % cells.width), static_cast<int>(k / cells.width));
  };
  auto atRisk = [&](std::int64_t k) {
    const Vec2 c = centreOf(k);
    return !before.anyNear(c, r,
                           [&](int a, int b) { return distanceToSegment(c, old[a], old[b]) + largest <= r; });
  };
  std::vector<char> keep(candidates.size(), 0);
  runChunks(workers, candidates.size(), kNodeChunk, [&](size_t begin, size_t end, size_t) {
    for (size_t k = begin; k < end; ++k) keep[k] = atRisk(candidates[k]);
  });
  size_t kept = 0;
  for (size_t k = 0; k < candidates.size(); ++k)
    if (keep[k]) candidates[kept++] = candidates[k];
  candidates.resize(kept);
  // A link's new position lies within `largest` of its old one, so the old index finds it.
  auto coveredNow = [&](const Vec2& c) {
    return before.anyNear(c, r + largest,
                          [&](int a, int b) { return distanceToSegment(c, next[a], next[b]) <= r; });
  };
  for (bool undone = !candidates.empty(); undone;) {
    undone = false;
    for (std::int64_t k : candidates) {
      const Vec2 c = centreOf(k);
      if (coveredNow(c)) continue;
      // Halve the moves of the ends of every link that covered it, down to none: its old links cover
      // it again at the latest.
      std::vector<int> ends;  // a link lies in several buckets: each end is cut back once per cell
      before.anyNear(c, r, [&](int a, int b) {
        if (distanceToSegment(c, old[a], old[b]) <= r) ends.insert(ends.end(), {a, b});
        return false;
      });
      std::sort(ends.begin(), ends.end());
      ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
      for (int e : ends)
        if (!(next[e] == old[e])) {
          next[e] = length(next[e] - old[e]) > kSmallestMove ? (old[e] + next[e]) * 0.5 : old[e];
          undone = true;
        }
    }
  }
}

}  // namespace

void averagePass(RoadGraph& graph, const std::vector<char>& movable, double reach,
                 const Grid<std::uint8_t>* coverCells, double coverRadius, int threads) {
  const size_t workers = workerCount(threads);
  std::vector<Vec2> next(graph.nodes.size());
  runChunks(workers, graph.nodes.size(), kNodeChunk, [&](size_t begin, size_t end, size_t) {
    for (size_t i = begin; i < end; ++i) {
      const RoadNode& n = graph.nodes[i];
      next[i] = n.p;
      if (!movable[i]) continue;
      Vec2 sum = n.p;
      int count = 1;
      for (int j : n.links)
        if (graph.nodes[j].type == n.type) {
          sum += graph.nodes[j].p;
          ++count;
        }
      next[i] = sum / count;
      const double maxShift = smoothingShiftLimit(n.type, reach);
      const Vec2 shift = next[i] - n.placed;
      const double distance = length(shift);
      if (distance > maxShift) next[i] = n.placed + shift * (maxShift / distance);
    }
  });
  if (coverCells) undoUncoveringMoves(graph, movable, next, *coverCells, coverRadius, workers);
  for (size_t i = 0; i < graph.nodes.size(); ++i) graph.nodes[i].p = next[i];
}

std::vector<char> smoothableRoadNodes(const RoadGraph& graph, bool fixConnections) {
  std::vector<char> movable(graph.nodes.size(), 0);
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const RoadNode& n = graph.nodes[i];
    movable[i] = n.alive && n.type != NodeType::Perimeter && !n.intersection && n.links.size() >= 2 &&
                 !(fixConnections && n.psConnection) && graph.sameTypeDegree(static_cast<int>(i)) >= 2;
  }
  return movable;
}

RoadSmoothingStats smoothRoads(RoadGraph& graph, const RoadSmoothingOptions& options,
                               const Progress& progress) {
  RoadSmoothingStats stats;
  updateIntersectionFlags(graph);
  const std::vector<char> movable = smoothableRoadNodes(graph, true);
  for (char m : movable) stats.nodesMoved += m;
  for (int pass = 0; pass < options.passes; ++pass) {
    averagePass(graph, movable, options.reach, options.coverCells, options.coverRadius, options.threads);
    reportProgress(progress, 0.8 * (pass + 1) / std::max(1, options.passes), "road smoothing");
  }
  if (options.perimeterPasses > 0) {
    std::vector<char> perimeter(graph.nodes.size(), 0);
    for (size_t i = 0; i < graph.nodes.size(); ++i) {
      const RoadNode& n = graph.nodes[i];
      perimeter[i] = n.alive && n.type == NodeType::Perimeter &&
                     graph.sameTypeDegree(static_cast<int>(i)) == 2 && n.links.size() == 2;
    }
    for (int pass = 0; pass < options.perimeterPasses; ++pass)
      averagePass(graph, perimeter, 0.0, nullptr, 1.5, options.threads);
  }
  stats.intersectionsMoved = straightenNearStraightPairs(graph, options.straightAngle);
  graph.sortLinksClockwise(options.threads);
  reportProgress(progress, 1.0, "road smoothing");
  return stats;
}

}  // namespace urbanvec::vectorize
