// Stage A4.1–A4.7 (spec §3 A4); the [INFERENCE] resolutions used are the spec's Q2–Q5 defaults.
#include "urbanvec/vectorize/roads/road_graph_build.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/core/landuse.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

NodeType linkType(const RoadGraph& graph, int a, int b) {
  const NodeType ta = graph.nodes[a].type, tb = graph.nodes[b].type;
  if (ta == NodeType::Perimeter || tb == NodeType::Perimeter) return NodeType::Perimeter;
  if (ta == tb) return ta;
  return NodeType::Secondary;
}

std::size_t simplifyIntersectionClusters(RoadGraph& graph, bool collapseTwoLinkClusters,
                                         double maxClusterRadius) {
  updateIntersectionFlags(graph);
  const size_t n = graph.nodes.size();
  std::vector<char> seen(n, 0);
  std::vector<int> cluster, stack, outside;
  std::size_t merged = 0;
  for (size_t s = 0; s < n; ++s) {
    if (!graph.nodes[s].alive || !graph.nodes[s].intersection || seen[s]) continue;
    cluster.clear();
    stack.assign(1, static_cast<int>(s));
    seen[s] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      cluster.push_back(i);
      for (int j : graph.nodes[i].links)
        if (graph.nodes[j].intersection && !seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
    }
    if (cluster.size() < 2) continue;
    std::sort(cluster.begin(), cluster.end());
    outside.clear();
    Vec2 sum;
    bool anyPrimary = false, anyConnection = false;
    for (int i : cluster) {
      sum += graph.nodes[i].p;
      anyPrimary |= graph.nodes[i].type == NodeType::Primary;
      anyConnection |= graph.nodes[i].psConnection;
      for (int j : graph.nodes[i].links)
        if (!std::binary_search(cluster.begin(), cluster.end(), j)) outside.push_back(j);
    }
    std::sort(outside.begin(), outside.end());
    outside.erase(std::unique(outside.begin(), outside.end()), outside.end());
    if (outside.size() == 2 && !collapseTwoLinkClusters) continue;
    const Vec2 mean = sum / static_cast<double>(cluster.size());
    // A cluster reaching farther than maxClusterRadius from its mean is several junctions joined by
    // short roads; it keeps its nodes.
    if (maxClusterRadius > 0.0 && std::any_of(cluster.begin(), cluster.end(), [&](int i) {
          return distance(graph.nodes[i].p, mean) > maxClusterRadius + 1e-9;
        }))
      continue;
    const NodeType type = anyPrimary ? NodeType::Primary : graph.nodes[cluster.front()].type;
    const int m = graph.addNode(mean, type);
    seen.push_back(1);
    graph.nodes[m].psConnection = anyConnection;
    for (int i : cluster) graph.removeNode(i);
    for (int j : outside) graph.link(m, j);
    ++merged;
  }
  updateIntersectionFlags(graph);
  return merged;
}

std::size_t subdivideLongLinks(RoadGraph& graph, double maxLinkLength) {
  std::size_t added = 0;
  const size_t n = graph.nodes.size();
  for (size_t a = 0; a < n; ++a) {
    if (!graph.nodes[a].alive) continue;
    const std::vector<std::int32_t> links = graph.nodes[a].links;
    for (int b : links) {
      if (b < static_cast<int>(a) && b < static_cast<int>(n)) continue;  // each original link once
      const Vec2 pa = graph.nodes[a].p, pb = graph.nodes[b].p;
      const double len = distance(pa, pb);
      if (len < maxLinkLength) continue;
      const int parts = static_cast<int>(std::floor(len / maxLinkLength)) + 1;
      const NodeType type = linkType(graph, static_cast<int>(a), b);
      graph.unlink(static_cast<int>(a), b);
      int prev = static_cast<int>(a);
      for (int k = 1; k < parts; ++k) {
        const int m = graph.addNode(pa + (pb - pa) * (static_cast<double>(k) / parts), type);
        graph.link(prev, m);
        prev = m;
        ++added;
      }
      graph.link(prev, b);
    }
  }
  return added;
}

RoadGraphBuild buildRoadGraph(Grid<std::uint8_t>& cells, const RoadGraphOptions& options,
                              const Progress& progress) {
  const int w = cells.width, h = cells.height;
  const auto primary = static_cast<std::uint8_t>(LandUse::PrimaryRoad);
  const auto secondary = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
  auto is = [&](int c, int r, std::uint8_t code) { return cells.inside(c, r) && cells.at(c, r) == code; };
  RoadGraphBuild out;
  RoadGraph& g = out.graph;

  // A4.1 node placement.
  Grid<std::int32_t> nodeOf(w, h, -1);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const std::uint8_t v = cells.at(c, r);
      if (v == secondary) {
        const int id = g.addNode(patchCentre(cells, c, r), NodeType::Secondary, c, r);
        nodeOf.at(c, r) = id;
        g.nodes[id].psConnection =
            is(c, r - 1, primary) || is(c + 1, r, primary) || is(c, r + 1, primary) || is(c - 1, r, primary);
      } else if (v == primary && is(c + 1, r, primary) && is(c + 1, r + 1, primary) &&
                 is(c, r + 1, primary)) {
        const Vec2 p = options.primaryNodeAtCorner
                           ? Vec2(cells.frameDx + c + 1.0, cells.frameDy + h - r - 1.0)
                           : patchCentre(cells, c + 1, r + 1);
        nodeOf.at(c, r) = g.addNode(p, NodeType::Primary, c, r);
      }
    }
  reportProgress(progress, 0.25, "road graph");

  // A4.2 linking: same-type nodes of 4-connected patches (Q5).
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const int a = nodeOf.at(c, r);
      if (a < 0) continue;
      if (c + 1 < w && nodeOf.at(c + 1, r) >= 0 && g.nodes[nodeOf.at(c + 1, r)].type == g.nodes[a].type)
        g.link(a, nodeOf.at(c + 1, r));
      if (r + 1 < h && nodeOf.at(c, r + 1) >= 0 && g.nodes[nodeOf.at(c, r + 1)].type == g.nodes[a].type)
        g.link(a, nodeOf.at(c, r + 1));
      if (options.linkPrimaryKnightSteps && g.nodes[a].type == NodeType::Primary) {
        const int steps[4][2] = {{1, 2}, {-1, 2}, {2, 1}, {-2, 1}};
        for (const auto& step : steps) {
          const int c2 = c + step[0], r2 = r + step[1];
          if (!nodeOf.inside(c2, r2)) continue;
          const int b = nodeOf.at(c2, r2);
          if (b < 0 || g.nodes[b].type != NodeType::Primary) continue;
          bool bridged = false;  // a window overlapping both already joins them
          for (int y = std::max(r, r2) - 1; y <= std::min(r, r2) + 1 && !bridged; ++y)
            for (int x = std::max(c, c2) - 1; x <= std::min(c, c2) + 1 && !bridged; ++x)
              bridged = (x != c || y != r) && (x != c2 || y != r2) && nodeOf.inside(x, y) &&
                        nodeOf.at(x, y) >= 0 && g.nodes[nodeOf.at(x, y)].type == NodeType::Primary;
          if (!bridged) g.link(a, b);
        }
      }
      if (options.linkPrimaryDiagonals && g.nodes[a].type == NodeType::Primary && r + 1 < h) {
        for (int dc : {-1, 1}) {
          const int c2 = c + dc;
          if (c2 < 0 || c2 >= w) continue;
          const int b = nodeOf.at(c2, r + 1);
          if (b < 0 || g.nodes[b].type != NodeType::Primary) continue;
          if (nodeOf.at(c2, r) < 0 && nodeOf.at(c, r + 1) < 0) g.link(a, b);
        }
      }
    }
  reportProgress(progress, 0.45, "road graph");

  // A4.3 2x2 short-cycle elimination: the node is the NW patch; follow S, E, N, W.
  auto nonRoad = [&](int c, int r) { return !cells.inside(c, r) || !isRoadCode(cells.at(c, r)); };
  for (int r = 0; r + 1 < h; ++r)
    for (int c = 0; c + 1 < w; ++c) {
      const int nw = nodeOf.at(c, r);
      if (nw < 0 || !g.nodes[nw].alive) continue;
      if (options.twoByTwoSecondaryOnly && g.nodes[nw].type != NodeType::Secondary) continue;
      const int sw = nodeOf.at(c, r + 1), se = nodeOf.at(c + 1, r + 1), ne = nodeOf.at(c + 1, r);
      if (sw < 0 || se < 0 || ne < 0) continue;
      if (!g.linked(nw, sw) || !g.linked(sw, se) || !g.linked(se, ne) || !g.linked(ne, nw)) continue;
      // The patch of the square whose two outside 4-neighbours are both not road, in NW, NE, SE, SW order.
      const int square[4][4] = {{c, r, nw, 0}, {c + 1, r, ne, 1}, {c + 1, r + 1, se, 2}, {c, r + 1, sw, 3}};
      bool opened = false;
      for (const auto& s : square) {
        const int pc = s[0], pr = s[1];
        const int outC = pc == c ? pc - 1 : pc + 1, outR = pr == r ? pr - 1 : pr + 1;
        if (nonRoad(outC, pr) && nonRoad(pc, outR)) {
          g.removeNode(s[2]);
          nodeOf.at(pc, pr) = -1;
          cells.at(pc, pr) = kRemovedRoad;
          opened = true;
          break;
        }
      }
      ++(opened ? out.squaresOpened : out.squaresLeft);
    }
  reportProgress(progress, 0.6, "road graph");

  // A4.4 intersections and clusters; A4.5 the graph is already an unconstrained adjacency list.
  out.clustersMerged =
      simplifyIntersectionClusters(g, options.collapseTwoLinkClusters, options.maxClusterRadius);
  reportProgress(progress, 0.8, "road graph");
  // A4.6 long links, A4.7 clockwise order.
  out.nodesInserted = subdivideLongLinks(g, options.maxLinkLength);
  g.compact();
  updateIntersectionFlags(g);
  g.sortLinksClockwise();
  reportProgress(progress, 1.0, "road graph");
  return out;
}

}  // namespace urbanvec::vectorize
