// Stage B3 (spec §3 B3) with its [INFERENCE] choices: merging adds a link (nodes are not collapsed);
// each perimeter end links to the nearest road node that has no perimeter link yet; afterwards flags,
// clockwise order and long links are redone.
#include "urbanvec/vectorize/roads/road_connection.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "urbanvec/vectorize/roads/road_graph_build.hpp"

namespace urbanvec::vectorize {

namespace {

std::int64_t patchKey(std::int64_t col, std::int64_t row) {
  // Unsigned shift: a window at the grid border has row -1.
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(row) << 32) ^ static_cast<std::uint32_t>(col));
}

/// True when b is within `hops` primary links of a.
bool nearInPrimaryGraph(const RoadGraph& graph, int a, int b, int hops) {
  std::vector<int> frontier{a}, seen{a};
  for (int h = 0; h < hops && !frontier.empty(); ++h) {
    std::vector<int> next;
    for (int n : frontier)
      for (int m : graph.nodes[n].links) {
        if (graph.nodes[m].type != NodeType::Primary) continue;
        if (m == b) return true;
        if (std::find(seen.begin(), seen.end(), m) != seen.end()) continue;
        seen.push_back(m);
        next.push_back(m);
      }
    frontier = std::move(next);
  }
  return false;
}

}  // namespace

RoadConnectionStats connectRoads(RoadGraph& graph, const RoadConnectionOptions& options,
                                 const Progress& progress) {
  RoadConnectionStats stats;
  {
    const NodeIndex primaries(graph, 4.0, [&](int i) { return graph.nodes[i].type == NodeType::Primary; });
    // A primary node stands for the 2x2 window whose north-west patch it was placed for (A4.1).
    std::unordered_map<std::int64_t, int> primaryOfWindow;
    for (size_t i = 0; i < graph.nodes.size(); ++i) {
      const RoadNode& p = graph.nodes[i];
      if (p.alive && p.type == NodeType::Primary && p.col >= 0)
        primaryOfWindow.emplace(patchKey(p.col, p.row), static_cast<int>(i));
    }
    const size_t n = graph.nodes.size();
    for (size_t i = 0; i < n; ++i) {
      const RoadNode& s = graph.nodes[i];
      if (!s.alive || !s.psConnection || s.type != NodeType::Secondary) continue;
      const int p = primaries.nearest(s.p, options.maxConnectionDistance);
      if (p < 0) {
        ++stats.unconnected;
        continue;
      }
      graph.link(static_cast<int>(i), p);
      ++stats.connections;
      if (!options.linkEverySide || s.col < 0) continue;
      // The primary nodes of the windows covering each 4-neighbour patch, one side at a time.
      std::vector<int> linked{p};
      const int sideCols[4] = {0, 1, 0, -1}, sideRows[4] = {-1, 0, 1, 0};
      for (int side = 0; side < 4; ++side) {
        const int qc = graph.nodes[i].col + sideCols[side], qr = graph.nodes[i].row + sideRows[side];
        int best = -1;
        double bestDistance = options.maxConnectionDistance;
        for (int wr = qr - 1; wr <= qr; ++wr)
          for (int wc = qc - 1; wc <= qc; ++wc) {
            const auto it = primaryOfWindow.find(patchKey(wc, wr));
            if (it == primaryOfWindow.end() || !graph.nodes[it->second].alive) continue;
            const double d = distance(graph.nodes[it->second].p, graph.nodes[i].p);
            if (d <= bestDistance) {
              bestDistance = d;
              best = it->second;
            }
          }
        if (best < 0) continue;
        const bool sameRoad = std::any_of(linked.begin(), linked.end(), [&](int q) {
          return q == best || nearInPrimaryGraph(graph, q, best, 3);
        });
        if (sameRoad) continue;
        graph.link(static_cast<int>(i), best);
        linked.push_back(best);
        ++stats.connections;
        ++stats.bridges;
      }
    }
  }
  reportProgress(progress, 0.4, "primary/secondary connection");
  stats.clustersMerged =
      simplifyIntersectionClusters(graph, options.collapseTwoLinkClusters, options.maxClusterRadius);
  reportProgress(progress, 0.6, "primary/secondary connection");

  // Perimeter ends to road nodes, each road node taking at most one perimeter.
  std::vector<char> hasPerimeter(graph.nodes.size(), 0);
  for (size_t i = 0; i < graph.nodes.size(); ++i)
    if (graph.nodes[i].alive && graph.nodes[i].type != NodeType::Perimeter)
      for (int j : graph.nodes[i].links) hasPerimeter[i] |= graph.nodes[j].type == NodeType::Perimeter;
  const NodeIndex roads(graph, 4.0, [&](int i) { return graph.nodes[i].type != NodeType::Perimeter; });
  const size_t n = graph.nodes.size();
  for (size_t i = 0; i < n; ++i) {
    const RoadNode& e = graph.nodes[i];
    if (!e.alive || e.type != NodeType::Perimeter || e.links.size() != 1) continue;
    const int r = roads.nearest(e.p, options.maxPerimeterDistance, [&](int j) { return !hasPerimeter[j]; });
    if (r < 0) {
      ++stats.perimeterEndsLeft;
      continue;
    }
    graph.link(static_cast<int>(i), r);
    hasPerimeter[r] = 1;
    ++stats.perimeterEndsLinked;
  }
  subdivideLongLinks(graph, options.maxLinkLength);
  graph.compact();
  updateIntersectionFlags(graph);
  graph.sortLinksClockwise();
  reportProgress(progress, 1.0, "primary/secondary connection");
  return stats;
}

}  // namespace urbanvec::vectorize
