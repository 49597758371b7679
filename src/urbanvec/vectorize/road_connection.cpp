// Stage B3 (spec §3 B3) with its [INFERENCE] choices: merging adds a link (nodes are not collapsed);
// each perimeter end links to the nearest road node that has no perimeter link yet; afterwards flags,
// clockwise order and long links are redone.
#include "urbanvec/vectorize/road_connection.hpp"

#include "urbanvec/vectorize/road_graph_build.hpp"

namespace urbanvec::vectorize {

RoadConnectionStats connectRoads(RoadGraph& graph, const RoadConnectionOptions& options,
                                 const Progress& progress) {
  RoadConnectionStats stats;
  {
    const NodeIndex primaries(graph, 4.0, [&](int i) { return graph.nodes[i].type == NodeType::Primary; });
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
    }
  }
  reportProgress(progress, 0.4, "primary/secondary connection");
  stats.clustersMerged = simplifyIntersectionClusters(graph, options.collapseTwoLinkClusters);
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
