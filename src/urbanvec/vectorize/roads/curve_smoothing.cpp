// Stage B6 (spec §3 B6) with its [INFERENCE] choices: the interior angle is measured at a degree-2
// road node that is not an intersection; nodes are inserted once, before the passes, by splitting
// each adjacent link into equal parts (a link between two bends takes the larger count); the passes
// follow the B2 rules (same-type neighbours, at least two, intersections, dead ends and perimeter
// nodes fixed).
#include "urbanvec/vectorize/roads/curve_smoothing.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/vectorize/roads/road_graph_build.hpp"
#include "urbanvec/vectorize/roads/road_smoothing.hpp"

namespace urbanvec::vectorize {

int curveInsertionCount(double degrees, const CurveSmoothingOptions& options) {
  if (degrees < options.angleThreeNodes) return 3;
  if (degrees < options.angleTwoNodes) return 2;
  if (degrees < options.angleOneNode) return 1;
  return 0;
}

CurveSmoothingStats smoothCurves(RoadGraph& graph, const CurveSmoothingOptions& options,
                                 const Progress& progress) {
  CurveSmoothingStats stats;
  updateIntersectionFlags(graph);
  const size_t n = graph.nodes.size();
  std::vector<int> perSide(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const RoadNode& m = graph.nodes[i];
    if (!m.alive || m.type == NodeType::Perimeter || m.intersection || m.links.size() != 2) continue;
    const Vec2 a = graph.nodes[m.links[0]].p - m.p, b = graph.nodes[m.links[1]].p - m.p;
    const double la = length(a), lb = length(b);
    if (la == 0 || lb == 0) continue;
    const double degrees = std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0)) * 180.0 / M_PI;
    perSide[i] = curveInsertionCount(degrees, options);
    stats.bends += perSide[i] > 0;
  }
  for (size_t a = 0; a < n; ++a) {
    if (!graph.nodes[a].alive) continue;
    const std::vector<std::int32_t> links = graph.nodes[a].links;
    for (int b : links) {
      if (b >= static_cast<int>(n) || b < static_cast<int>(a)) continue;
      const int k = std::max(perSide[a], perSide[b]);
      if (k == 0) continue;
      const Vec2 pa = graph.nodes[a].p, pb = graph.nodes[b].p;
      const Vec2 placedA = graph.nodes[a].placed, placedB = graph.nodes[b].placed;
      const NodeType type = linkType(graph, static_cast<int>(a), b);
      graph.unlink(static_cast<int>(a), b);
      int prev = static_cast<int>(a);
      for (int s = 1; s <= k; ++s) {
        const double t = static_cast<double>(s) / (k + 1);
        const int id = graph.addNode(pa + (pb - pa) * t, type);
        graph.nodes[id].placed = placedA + (placedB - placedA) * t;
        graph.link(prev, id);
        prev = id;
        ++stats.nodesInserted;
      }
      graph.link(prev, b);
    }
  }
  reportProgress(progress, 0.2, "curve smoothing");
  updateIntersectionFlags(graph);
  const std::vector<char> movable = smoothableRoadNodes(graph, false);
  for (int pass = 0; pass < options.passes; ++pass) {
    averagePass(graph, movable, options.reach, options.coverCells, options.coverRadius, options.threads);
    ++stats.passes;
    reportProgress(progress, 0.2 + 0.8 * (pass + 1) / options.passes, "curve smoothing");
  }
  graph.sortLinksClockwise(options.threads);
  reportProgress(progress, 1.0, "curve smoothing");
  return stats;
}

}  // namespace urbanvec::vectorize
