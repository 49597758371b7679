// Stage B3 (spec §3 B3) with its [INFERENCE] choices: merging adds a link (nodes are not collapsed);
// each perimeter end links to the nearest road node that has no perimeter link yet; afterwards flags,
// clockwise order and long links are redone.
#include "urbanvec/vectorize/roads/road_connection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>

#include "urbanvec/vectorize/roads/road_graph_build.hpp"
#include "urbanvec/vectorize/roads/straightening.hpp"
#include "urbanvec/vectorize/roads/through_roads.hpp"

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

/// The placements of the street arriving at connection node c: c's, then those of the nodes from
/// its single secondary link on through two-link secondary nodes, up to `window` from c and
/// including the first node of another kind (an intersection, whose cells may belong to the other
/// street; `junction` tells the caller); empty when c has no single secondary link.
std::vector<Vec2> streetPlacements(const RoadGraph& graph, int c, double window, bool& junction) {
  junction = false;
  int next = -1;
  for (int m : graph.nodes[c].links)
    if (graph.nodes[m].type == NodeType::Secondary) {
      if (next >= 0) return {};
      next = m;
    }
  if (next < 0) return {};
  std::vector<Vec2> out{graph.nodes[c].placed};
  int prev = c, cur = next;
  while (distance(graph.nodes[cur].placed, graph.nodes[c].placed) <= window) {
    out.push_back(graph.nodes[cur].placed);
    if (graph.degree(cur) != 2) {
      junction = graph.degree(cur) > 2;
      break;
    }
    const auto& links = graph.nodes[cur].links;
    const int after = links[0] == prev ? links[1] : links[0];
    if (graph.nodes[after].type != NodeType::Secondary || after == c) break;
    prev = cur;
    cur = after;
  }
  return out;
}

constexpr double kRounding = 1e-9;  // a staircase's cells lie exactly on the band's edge

/// How far the points lie from a line of their fitted (total least squares) direction, moved to the
/// middle of their residuals (a digital line's cells are within the band of some line; the fit need
/// not centre it), minus the band (|cos t| + |sin t|) / 2 of that direction: <= 0 when they are
/// consistent with a digital straight line.
double lineOffset(const std::vector<Vec2>& points) {
  Vec2 centre, direction;
  fitLine(points, centre, direction);
  double lo = 0.0, hi = 0.0;
  for (const Vec2& q : points) {
    const double r = cross(direction, q - centre);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  return (hi - lo) / 2 - digitalLineBand(direction);
}

/// Connection nodes that continue each other across a primary road (RoadConnectionOptions::
/// crossingAngle), each with the primary node both link to; -1 for nodes without such a partner.
std::vector<int> crossingNodes(const RoadGraph& graph, const NodeIndex& primaries,
                               const RoadConnectionOptions& options, std::size_t& pairs) {
  std::vector<int> target(graph.nodes.size(), -1);
  if (!(options.crossingAngle > 0.0)) return target;
  const double cosLimit = std::cos(options.crossingAngle * M_PI / 180.0);
  std::vector<int> ends;
  std::vector<std::vector<Vec2>> street(graph.nodes.size());
  std::vector<char> trim(graph.nodes.size(), 0);  // the street's last placement is an intersection's
  std::vector<Vec2> dir(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const RoadNode& s = graph.nodes[i];
    if (!s.alive || !s.psConnection || s.type != NodeType::Secondary) continue;
    bool junction = false;
    street[i] = streetPlacements(graph, static_cast<int>(i), options.crossingWindow, junction);
    trim[i] = junction && street[i].size() > 2;
    if (street[i].empty()) continue;
    const Vec2 d = street[i].front() - street[i].back();
    if (length(d) < 1.0) continue;
    dir[i] = d / length(d);
    ends.push_back(static_cast<int>(i));
  }
  std::vector<char> isEnd(graph.nodes.size(), 0);
  for (int a : ends) isEnd[a] = 1;
  const NodeIndex endIndex(graph, options.crossingReach, [&](int i) { return isEnd[i] != 0; });
  // Each end's best partner: ahead of it, the streets' directions within crossingAngle of opposite,
  // and the cells of both streets together consistent with one straight line (B7's rule: within
  // (|cos t| + |sin t|) / 2 of a line, lineOffset <= 0); the straightest (smallest offset) wins.
  std::vector<int> best(graph.nodes.size(), -1);
  std::vector<double> bestOffset(graph.nodes.size(), 0.0);
  std::vector<Vec2> both;
  for (int a : ends) {
    const Vec2 pa = graph.nodes[a].placed;
    for (int b : endIndex.within(graph.nodes[a].p, options.crossingReach)) {
      if (b == a) continue;
      const Vec2 ab = graph.nodes[b].placed - pa;
      if (dot(dir[a], ab) <= 0.0 || dot(dir[b], ab) >= 0.0 || -dot(dir[a], dir[b]) < cosLimit) continue;
      // The smallest half-range of residuals, with or without each street's intersection cell.
      double offset = std::numeric_limits<double>::infinity();
      for (int ta = 0; ta <= trim[a]; ++ta)
        for (int tb = 0; tb <= trim[b]; ++tb) {
          both.assign(street[a].begin(), street[a].end() - ta);
          both.insert(both.end(), street[b].begin(), street[b].end() - tb);
          offset = std::min(offset, lineOffset(both));
        }
      if (offset > kRounding) continue;
      if (best[a] < 0 || offset < bestOffset[a]) {
        bestOffset[a] = offset;
        best[a] = b;
      }
    }
  }
  for (int a : ends) {
    const int b = best[a];
    if (b < a || best[b] != a) continue;  // mutual, each pair once
    const Vec2 pa = graph.nodes[a].p, pb = graph.nodes[b].p;
    // The primary node nearest the line between them, strictly between them.
    int p = -1;
    double pd = 1.0;  // pw: a node on the primary's centreline the street passes over
    for (int q : primaries.within((pa + pb) * 0.5, distance(pa, pb) / 2 + 1.0)) {
      const Vec2 pq = graph.nodes[q].p;
      if (distance(pq, pa) < 0.5 || distance(pq, pb) < 0.5) continue;
      const double d = distanceToSegment(pq, pa, pb);
      if (d < pd) {
        pd = d;
        p = q;
      }
    }
    if (p < 0) continue;
    target[a] = target[b] = p;
    ++pairs;
  }
  return target;
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
    const std::vector<int> crossing = crossingNodes(graph, primaries, options, stats.crossings);
    const size_t n = graph.nodes.size();
    for (size_t i = 0; i < n; ++i) {
      const RoadNode& s = graph.nodes[i];
      if (!s.alive || !s.psConnection || s.type != NodeType::Secondary) continue;
      const int p = crossing[i] >= 0 ? crossing[i] : primaries.nearest(s.p, options.maxConnectionDistance);
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
