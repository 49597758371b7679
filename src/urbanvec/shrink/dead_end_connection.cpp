// Step 5 (spec §B.6): connect fringe paths (dead ends) within the m-degree neighbourhood.
#include "urbanvec/shrink/dead_end_connection.hpp"

#include <algorithm>
#include <limits>
#include <set>
#include <unordered_map>

namespace urbanvec::shrink {
namespace {

/// Distinct neighbours of node n over the edges `use` accepts.
int neighbourCount(const PlanarGraph& graph, int n, const std::vector<char>& skeletonEdge,
                   bool skeletonOnly) {
  std::set<int> seen;
  for (int e : graph.node(n).edges)
    if (!skeletonOnly || skeletonEdge[static_cast<size_t>(e)]) seen.insert(graph.otherEnd(e, n));
  return static_cast<int>(seen.size());
}

}  // namespace

std::vector<CityWay> connectDeadEnds(const City& city, const StreetGraph& g,
                                     const std::vector<char>& inSkeleton, int mDegree,
                                     std::int64_t firstNewId, DeadEndStats* stats) {
  DeadEndStats local;
  const PlanarGraph& graph = g.graph;
  std::vector<char> skeletonEdge(graph.edgeCount(), 0);
  // A segment is in the skeleton when any street along it is (two ways may share a segment).
  std::set<std::pair<int, int>> skeletonPairs;
  for (size_t e = 0; e < graph.edgeCount(); ++e)
    if (inSkeleton[static_cast<size_t>(g.edgeWay[e])]) {
      const PlanarGraph::Edge& edge = graph.edge(static_cast<int>(e));
      skeletonPairs.insert({std::min(edge.a, edge.b), std::max(edge.a, edge.b)});
    }
  for (size_t e = 0; e < graph.edgeCount(); ++e) {
    const PlanarGraph::Edge& edge = graph.edge(static_cast<int>(e));
    skeletonEdge[e] = skeletonPairs.count({std::min(edge.a, edge.b), std::max(edge.a, edge.b)}) ? 1 : 0;
  }
  std::vector<int> degree(graph.nodeCount(), 0);
  for (size_t n = 0; n < graph.nodeCount(); ++n)
    degree[n] = neighbourCount(graph, static_cast<int>(n), skeletonEdge, true);

  std::vector<CityWay> added;
  std::int64_t nextId = firstNewId;
  const double inf = std::numeric_limits<double>::infinity();
  struct Label {
    double distance;
    int previous;  ///< node in the layer before
    int edge;
  };
  for (size_t start = 0; start < graph.nodeCount(); ++start) {
    const int src = static_cast<int>(start);
    if (degree[start] != 1 || neighbourCount(graph, src, skeletonEdge, false) <= 1) continue;
    ++local.deadEnds;
    // Layered Bellman-Ford: layer k holds the shortest walks of exactly k non-skeleton segments that
    // stop at the first skeleton node they meet.
    std::vector<std::unordered_map<int, Label>> layer(static_cast<size_t>(mDegree) + 1);
    layer[0][src] = {0.0, -1, -1};
    double best = inf;
    int bestNode = -1, bestLayer = -1;
    for (int k = 1; k <= mDegree; ++k) {
      std::vector<int> frontier;
      for (const auto& [n, label] : layer[static_cast<size_t>(k - 1)]) frontier.push_back(n);
      std::sort(frontier.begin(), frontier.end());
      for (int u : frontier) {
        if (u != src && degree[static_cast<size_t>(u)] > 0) continue;  // reached the skeleton: stop there
        const double du = layer[static_cast<size_t>(k - 1)][u].distance;
        for (int e : graph.node(u).edges) {
          if (skeletonEdge[static_cast<size_t>(e)]) continue;
          const int v = graph.otherEnd(e, u);
          if (v == src) continue;
          const double dv = du + graph.edgeLength(e);
          auto& slot = layer[static_cast<size_t>(k)];
          auto it = slot.find(v);
          if (it == slot.end() || dv < it->second.distance) slot[v] = {dv, u, e};
        }
      }
      for (const auto& [v, label] : layer[static_cast<size_t>(k)])
        if (degree[static_cast<size_t>(v)] > 0 &&
            (label.distance < best || (label.distance == best && v < bestNode))) {
          best = label.distance, bestNode = v, bestLayer = k;
        }
    }
    if (bestNode < 0) {
      ++local.remaining;
      continue;
    }
    std::vector<int> nodes{bestNode}, edges;
    for (int k = bestLayer, n = bestNode; k > 0; --k) {
      const Label& label = layer[static_cast<size_t>(k)].at(n);
      edges.push_back(label.edge);
      n = label.previous;
      nodes.push_back(n);
    }
    std::reverse(nodes.begin(), nodes.end());
    std::reverse(edges.begin(), edges.end());
    CityWay way;
    way.osmId = nextId--;
    way.highway = city.streets[static_cast<size_t>(g.edgeWay[static_cast<size_t>(edges.front())])].highway;
    for (int n : nodes) way.nodes.push_back(g.cityNode[static_cast<size_t>(n)]);
    for (int e : edges) skeletonEdge[static_cast<size_t>(e)] = 1;
    for (int n : nodes) degree[static_cast<size_t>(n)] = neighbourCount(graph, n, skeletonEdge, true);
    added.push_back(std::move(way));
    ++local.connected;
  }
  if (stats) *stats = local;
  return added;
}

}  // namespace urbanvec::shrink
