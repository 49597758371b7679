// The road graph shared by every road stage of the vectorizer (spec §2.2 "Node", A4.5 "unconstrained
// adjacency list"). Positions are in the internal frame of spec §0: x = col, y = H - row, in patch
// widths (pw). Nodes are removed by tombstoning and the vectors are compacted between stages, so a
// stage can delete freely without invalidating the ids it is iterating over.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::vectorize {

enum class NodeType : std::uint8_t { Primary, Secondary, Perimeter };

struct RoadNode {
  Vec2 p;
  /// Where the node was created (the grid placement for A4 nodes, the spot on the polyline for nodes
  /// inserted later). Smoothing (B2, B6) keeps p within a bounded distance of it.
  Vec2 placed;
  NodeType type = NodeType::Secondary;
  bool alive = true;
  /// Set by updateIntersectionFlags (A4.4 definition) and kept by the stages that merge clusters.
  bool intersection = false;
  /// A secondary node whose patch was 4-adjacent to a primary patch (B2 "primary/secondary
  /// connection" node, B3 merge candidate).
  bool psConnection = false;
  /// The patch the node was placed for (A4.1); -1 for nodes created later.
  std::int32_t col = -1;
  std::int32_t row = -1;
  /// Linked node ids; sorted clockwise from due north after sortLinksClockwise (A4.7).
  std::vector<std::int32_t> links;
};

class RoadGraph {
 public:
  std::vector<RoadNode> nodes;

  int addNode(const Vec2& p, NodeType type, int col = -1, int row = -1);
  bool linked(int a, int b) const;
  /// Adds the link a-b unless it exists or a == b.
  void link(int a, int b);
  void unlink(int a, int b);
  /// Unlinks the node from all neighbours and tombstones it.
  void removeNode(int a);
  int degree(int a) const { return static_cast<int>(nodes[a].links.size()); }
  size_t aliveCount() const;
  size_t linkCount() const;
  /// Drops tombstoned nodes and renumbers the rest, keeping their order.
  void compact();
  /// Sorts every node's links by azimuth atan2(dx, dy), clockwise from due north (A4.7), on `threads`
  /// workers (0 = all cores; each node's sort is its own).
  void sortLinksClockwise(int threads = 1);
  /// Neighbours of `a` that have the same type as `a`.
  int sameTypeDegree(int a) const;
};

/// Azimuth of b seen from a, clockwise from due north, in [0, 2*pi).
double azimuth(const Vec2& a, const Vec2& b);

/// A4.4 intersection definition: more than two links, or linked only to other intersections
/// (evaluated to a fixed point).
void updateIntersectionFlags(RoadGraph& graph);

/// The chain of nodes from `start` along its link to `next`, through nodes of degree 2, up to and
/// including the first node that is an intersection, a dead end or `start` itself (a loop). With
/// `throughFlagged`, degree-2 nodes flagged as intersections (A4.4: linked only to intersections) are
/// walked through too: the chain ends only where the number of links is not 2.
std::vector<int> followChain(const RoadGraph& graph, int start, int next, bool throughFlagged = false);

/// Uniform-grid bucket index over node positions for "nearest node" and "nodes within r" queries
/// in O(1) expected time per query (no O(n^2) searches on large grids).
class NodeIndex {
 public:
  /// Indexes the alive nodes accepted by `accept` (all alive nodes when empty).
  NodeIndex(const RoadGraph& graph, double bucketSize, const std::function<bool(int)>& accept = {});
  /// The nearest indexed node to p within maxDistance that passes `filter`, or -1.
  int nearest(const Vec2& p, double maxDistance, const std::function<bool(int)>& filter = {}) const;
  /// Indexed nodes within r of p.
  std::vector<int> within(const Vec2& p, double r) const;
  /// Visits the indexed nodes within r of p, those in p's bucket first, until `visit` returns true;
  /// true when it did. For checks that only ask whether any node qualifies: no list, no sort, and the
  /// scan stops at the first hit (which is most often in p's own bucket).
  template <class Visit>
  bool anyWithin(const Vec2& p, double r, Visit&& visit) const {
    if (ids_.empty()) return false;
    const int x0 = bucketX(p.x - r), x1 = bucketX(p.x + r), y0 = bucketY(p.y - r), y1 = bucketY(p.y + r);
    const int home = bucketY(p.y) * nx_ + bucketX(p.x);
    auto bucket = [&](int b) {
      for (int k = offsets_[b]; k < offsets_[b + 1]; ++k)
        if (distance(graph_.nodes[ids_[k]].p, p) <= r && visit(ids_[k])) return true;
      return false;
    };
    if (bucket(home)) return true;
    for (int by = y0; by <= y1; ++by)
      for (int bx = x0; bx <= x1; ++bx) {
        const int b = by * nx_ + bx;
        if (b != home && bucket(b)) return true;
      }
    return false;
  }

 private:
  const RoadGraph& graph_;
  double bucket_;
  double minX_ = 0, minY_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::int32_t> offsets_;
  std::vector<std::int32_t> ids_;
  int bucketX(double x) const;
  int bucketY(double y) const;
};

}  // namespace urbanvec::vectorize
