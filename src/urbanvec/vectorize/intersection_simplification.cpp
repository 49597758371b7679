// Stage B5 (spec §3 B5) with its [INFERENCE] choices: a dead end is a degree-1 neighbour of the
// intersection; a close node is contracted (the intersection takes over its other links), and a close
// node that is itself an intersection (the paper's "of one another") is merged at the average
// position. Intersections here are road nodes with three or more links; perimeter nodes are never
// removed.
#include "urbanvec/vectorize/intersection_simplification.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec::vectorize {

namespace {

bool isRoad(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

}  // namespace

IntersectionSimplificationStats simplifyIntersections(RoadGraph& graph,
                                                      const IntersectionSimplificationOptions& options,
                                                      const Progress& progress) {
  IntersectionSimplificationStats stats;
  const double cosLimit = std::cos(options.deadEndAngle * M_PI / 180.0);
  const size_t n = graph.nodes.size();
  // 1. Dead ends angled within deadEndAngle of another road.
  for (size_t i = 0; i < n; ++i) {
    if (!isRoad(graph.nodes[i])) continue;
    // The links that count: all (the documents), or only those to road nodes.
    auto counted = [&](int j) { return !options.deadEndRoadsOnly || isRoad(graph.nodes[j]); };
    auto countedLinks = [&] {
      const std::vector<std::int32_t>& links = graph.nodes[i].links;
      return static_cast<size_t>(std::count_if(links.begin(), links.end(), counted));
    };
    bool changed = true;
    while (changed && countedLinks() > 2) {
      changed = false;
      const std::vector<std::int32_t> links = graph.nodes[i].links;
      for (int d : links) {
        const RoadNode& dn = graph.nodes[d];
        if (dn.links.size() != 1 || dn.type == NodeType::Perimeter) continue;
        const Vec2 ud = dn.p - graph.nodes[i].p;
        for (int o : links) {
          if (o == d || !counted(o)) continue;
          const Vec2 uo = graph.nodes[o].p - graph.nodes[i].p;
          const double ld = length(ud), lo = length(uo);
          if (ld == 0 || lo == 0 || dot(ud, uo) / (ld * lo) > cosLimit) {
            stats.removedLinks.push_back({graph.nodes[i].p, dn.p});
            graph.removeNode(d);
            ++stats.deadEndsRemoved;
            changed = true;
            break;
          }
        }
        if (changed) break;
      }
    }
  }
  reportProgress(progress, 0.5, "intersection simplification");
  // 2. Nodes too close to an intersection.
  for (size_t i = 0; i < n; ++i) {
    if (!isRoad(graph.nodes[i]) || graph.nodes[i].links.size() < 3) continue;
    bool changed = true;
    while (changed) {
      changed = false;
      const std::vector<std::int32_t> links = graph.nodes[i].links;
      for (int c : links) {
        const RoadNode& cn = graph.nodes[c];
        if (!isRoad(cn)) continue;
        const double limit =
            cn.type == NodeType::Primary ? options.primaryDistance : options.secondaryDistance;
        if (distance(cn.p, graph.nodes[i].p) >= limit) continue;
        const bool isIntersection = cn.links.size() >= 3;
        if (isIntersection) {
          graph.nodes[i].p = (graph.nodes[i].p + cn.p) * 0.5;
          ++stats.intersectionsMerged;
        } else {
          ++stats.nodesContracted;
        }
        if (cn.type == NodeType::Primary) graph.nodes[i].type = NodeType::Primary;
        const std::vector<std::int32_t> others = cn.links;
        graph.removeNode(c);
        for (int o : others)
          if (o != static_cast<int>(i)) graph.link(static_cast<int>(i), o);
        changed = true;
        break;
      }
    }
  }
  graph.compact();
  updateIntersectionFlags(graph);
  graph.sortLinksClockwise();
  reportProgress(progress, 1.0, "intersection simplification");
  return stats;
}

}  // namespace urbanvec::vectorize
