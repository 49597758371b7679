// Stage B2 (spec §3 B2) with its [INFERENCE] choices: Jacobi update p' = mean(p, same-type
// neighbours); connection nodes are the secondary nodes whose patch touches primary; the second
// straightening uses each arm's first neighbour.
#include "urbanvec/vectorize/road_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanvec/vectorize/straightening.hpp"

namespace urbanvec::vectorize {

double smoothingShiftLimit(NodeType type, double reach) {
  if (reach <= 0.0) return std::numeric_limits<double>::infinity();
  const double placementToCell = type == NodeType::Primary ? std::sqrt(0.5) : 0.0;
  return std::max(0.0, reach - placementToCell);
}

void averagePass(RoadGraph& graph, const std::vector<char>& movable, double reach) {
  std::vector<Vec2> next(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
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
    averagePass(graph, movable, options.reach);
    reportProgress(progress, 0.8 * (pass + 1) / std::max(1, options.passes), "road smoothing");
  }
  if (options.perimeterPasses > 0) {
    std::vector<char> perimeter(graph.nodes.size(), 0);
    for (size_t i = 0; i < graph.nodes.size(); ++i) {
      const RoadNode& n = graph.nodes[i];
      perimeter[i] = n.alive && n.type == NodeType::Perimeter &&
                     graph.sameTypeDegree(static_cast<int>(i)) == 2 && n.links.size() == 2;
    }
    for (int pass = 0; pass < options.perimeterPasses; ++pass) averagePass(graph, perimeter, 0.0);
  }
  stats.intersectionsMoved = straightenNearStraightPairs(graph, options.straightAngle);
  graph.sortLinksClockwise();
  reportProgress(progress, 1.0, "road smoothing");
  return stats;
}

}  // namespace urbanvec::vectorize
