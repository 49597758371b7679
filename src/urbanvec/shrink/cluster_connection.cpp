// Steps 3 & 4 (spec §B.5): connect important-street clusters by A* with the impDistBalance cost and
// remove the unimportant clusters (noImpClusters); clusters are the flood-fill components of §C.6.
#include "urbanvec/shrink/cluster_connection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "urbanvec/core/union_find.hpp"

namespace urbanvec::shrink {
namespace {

void uniteWay(UnionFind& uf, const StreetGraph& g, const CityWay& way) {
  for (size_t i = 1; i < way.nodes.size(); ++i)
    uf.unite(g.graphNode[static_cast<size_t>(way.nodes[i - 1])],
             g.graphNode[static_cast<size_t>(way.nodes[i])]);
}

}  // namespace

std::vector<char> connectClusters(const City& city, const StreetGraph& g, const Selection& selection,
                                  const std::vector<StreetImportance>& importance,
                                  const ConnectionOptions& options, ConnectionStats* stats) {
  ConnectionStats local;
  const size_t nWays = city.streets.size();
  std::vector<char> in(nWays, 0);
  for (size_t w = 0; w < nWays; ++w) in[w] = selection.selected[w] ? 1 : 0;
  UnionFind uf(g.graph.nodeCount());
  for (size_t w = 0; w < nWays; ++w)
    if (in[w]) uniteWay(uf, g, city.streets[w]);

  // Clusters (§C.6) with their centroid, sorted by distance to the bounding-box centre (§B.5 2).
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  for (size_t n = 0; n < g.graph.nodeCount(); ++n) {
    const Vec2 p = g.graph.node(static_cast<int>(n)).p;
    minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
    maxY = std::max(maxY, p.y);
  }
  const Vec2 centre{(minX + maxX) / 2, (minY + maxY) / 2};
  struct Cluster {
    int root;
    int rep;  ///< lowest graph node
    Vec2 sum;
    int count = 0;
    double distance = 0.0;
  };
  std::map<int, Cluster> byRoot;
  std::vector<char> counted(g.graph.nodeCount(), 0);
  for (size_t w = 0; w < nWays; ++w) {
    if (!in[w]) continue;
    for (int cn : city.streets[w].nodes) {
      const int n = g.graphNode[static_cast<size_t>(cn)];
      if (counted[static_cast<size_t>(n)]) continue;
      counted[static_cast<size_t>(n)] = 1;
      const int root = uf.find(n);
      auto it = byRoot.find(root);
      if (it == byRoot.end()) it = byRoot.emplace(root, Cluster{root, n, {}, 0, 0.0}).first;
      it->second.rep = std::min(it->second.rep, n);
      it->second.sum += g.graph.node(n).p;
      ++it->second.count;
    }
  }
  std::vector<Cluster> clusters;
  for (auto& [root, c] : byRoot) {
    c.distance = distance(c.sum / c.count, centre);
    clusters.push_back(c);
  }
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const Cluster& a, const Cluster& b) { return a.distance < b.distance; });
  local.clusters = static_cast<int>(clusters.size());

  const double alpha = options.impDistBalance;
  auto cost = [&](int e) -> double {
    const int way = g.edgeWay[static_cast<size_t>(e)];
    if (in[static_cast<size_t>(way)]) return 0.0;
    const PlanarGraph::Edge& edge = g.graph.edge(e);
    if (uf.find(edge.a) == uf.find(edge.b)) return 0.0;
    const double d = g.graph.edgeLength(e);
    const double w = std::max(selection.scores[static_cast<size_t>(way)].impW, 1e-9);
    return alpha * d / w + (1.0 - alpha) * d;
  };
  std::vector<int> processed;  // representatives of the clusters handled so far
  for (const Cluster& c : clusters) {
    bool reached = processed.empty();
    for (size_t k = 0; k < processed.size() && !reached; ++k) {
      if (uf.find(processed[k]) == uf.find(c.rep)) {
        reached = true;
        break;
      }
      bool seenRoot = false;  // try each earlier group once
      for (size_t j = 0; j < k; ++j) seenRoot = seenRoot || uf.find(processed[j]) == uf.find(processed[k]);
      if (seenRoot) continue;
      const auto path = g.graph.shortestPath(processed[k], c.rep, cost);
      if (!path) continue;
      reached = true;
      ++local.joined;
      for (int e : *path) {
        const int way = g.edgeWay[static_cast<size_t>(e)];
        if (in[static_cast<size_t>(way)]) continue;
        in[static_cast<size_t>(way)] = 2;
        ++local.connectorWays;
        uniteWay(uf, g, city.streets[static_cast<size_t>(way)]);
      }
    }
    if (!reached) ++local.unreachable;
    processed.push_back(c.rep);
  }

  // Step 4: components left apart without an important street go (noImpClusters).
  std::map<int, std::pair<bool, double>> component;  // root -> (has important street, length)
  for (size_t w = 0; w < nWays; ++w) {
    if (!in[w]) continue;
    auto& entry = component[uf.find(g.graphNode[static_cast<size_t>(city.streets[w].nodes.front())])];
    entry.first = entry.first || importance[w].important;
    entry.second += selection.scores[w].length;
  }
  local.components = static_cast<int>(component.size());
  if (options.removeUnimportantClusters && component.size() > 1) {
    bool anyImportant = false;
    int longest = -1;
    double longestLength = -1.0;
    for (const auto& [root, entry] : component) {
      anyImportant = anyImportant || entry.first;
      if (entry.second > longestLength) longestLength = entry.second, longest = root;
    }
    std::map<int, bool> keep;
    for (const auto& [root, entry] : component) keep[root] = anyImportant ? entry.first : root == longest;
    for (size_t w = 0; w < nWays; ++w) {
      if (!in[w]) continue;
      if (keep[uf.find(g.graphNode[static_cast<size_t>(city.streets[w].nodes.front())])]) continue;
      in[w] = 0;
      ++local.removedWays;
    }
    for (const auto& [root, k] : keep)
      if (!k) ++local.removedClusters, --local.components;
  }
  if (stats) *stats = local;
  return in;
}

}  // namespace urbanvec::shrink
