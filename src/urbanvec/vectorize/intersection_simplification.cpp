// Stage B5 (spec §3 B5) with its [INFERENCE] choices: a dead end is a degree-1 neighbour of the
// intersection; a close node is contracted (the intersection takes over its other links), and a close
// node that is itself an intersection (the paper's "of one another") is merged at the average
// position. Intersections here are road nodes with three or more links; perimeter nodes are never
// removed.
#include "urbanvec/vectorize/intersection_simplification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "urbanvec/vectorize/road_network.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

namespace {

bool isRoad(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

/// A node contracted into an intersection, as it was, and the nodes it linked besides the intersection.
struct Contraction {
  int into;
  RoadNode node;
  std::vector<std::int32_t> others;
};

/// Puts back the contractions whose old links covered a road cell of `cells` that no road link covers
/// now (within `radius`), while the links they replaced still exist. Returns how many.
std::size_t undoUncoveringContractions(RoadGraph& graph, const std::vector<Contraction>& contractions,
                                       const Grid<std::uint8_t>& cells, double radius) {
  const int w = cells.width, h = cells.height;
  std::vector<std::uint8_t> covered(static_cast<size_t>(w) * h, 0);
  auto cover = [&](const Vec2& a, const Vec2& b) {
    forEachCellNearSegment(w, h, a, b, radius, [&](int col, int row, double) {
      covered[static_cast<size_t>(row) * w + col] = 1;
    });
  };
  for (size_t a = 0; a < graph.nodes.size(); ++a) {
    if (!isRoad(graph.nodes[a])) continue;
    for (int b : graph.nodes[a].links)
      if (b > static_cast<int>(a) && isRoad(graph.nodes[b])) cover(graph.nodes[a].p, graph.nodes[b].p);
  }
  std::vector<char> undone(contractions.size(), 0);
  std::size_t count = 0;
  for (bool changed = true; changed;) {
    changed = false;
    // Latest first: an earlier contraction's links may only exist again once a later one is undone.
    for (size_t k = contractions.size(); k-- > 0;) {
      const Contraction& c = contractions[k];
      if (undone[k] || !graph.nodes[c.into].alive) continue;
      const Vec2 into = graph.nodes[c.into].p;
      bool restorable = true;
      for (int o : c.others) restorable = restorable && graph.nodes[o].alive && graph.linked(c.into, o);
      if (!restorable) continue;
      bool uncovers = false;
      auto check = [&](const Vec2& a, const Vec2& b) {
        forEachCellNearSegment(w, h, a, b, radius, [&](int col, int row, double) {
          const size_t i = static_cast<size_t>(row) * w + col;
          uncovers = uncovers || (isRoadCode(cells.cells[i]) && !covered[i]);
        });
      };
      check(c.node.p, into);
      for (int o : c.others) check(c.node.p, graph.nodes[o].p);
      if (!uncovers) continue;
      RoadNode back = c.node;
      back.links.clear();
      graph.nodes.push_back(back);
      const int id = static_cast<int>(graph.nodes.size()) - 1;
      graph.link(c.into, id);
      cover(c.node.p, into);
      for (int o : c.others) {
        graph.unlink(c.into, o);
        graph.link(id, o);
        if (isRoad(graph.nodes[o])) cover(c.node.p, graph.nodes[o].p);
      }
      undone[k] = 1;
      ++count;
      changed = true;
    }
  }
  return count;
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
  std::vector<Contraction> contractions;
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
          if (options.coverCells) contractions.push_back({static_cast<int>(i), cn, {}});
        }
        if (cn.type == NodeType::Primary) graph.nodes[i].type = NodeType::Primary;
        const std::vector<std::int32_t> others = cn.links;
        graph.removeNode(c);
        for (int o : others)
          if (o != static_cast<int>(i)) {
            // A link the intersection already had is not the contracted node's to give back.
            if (!isIntersection && options.coverCells && !graph.linked(static_cast<int>(i), o))
              contractions.back().others.push_back(o);
            graph.link(static_cast<int>(i), o);
          }
        changed = true;
        break;
      }
    }
  }
  if (options.coverCells && !contractions.empty())
    stats.contractionsUndone =
        undoUncoveringContractions(graph, contractions, *options.coverCells, options.coverRadius);
  graph.compact();
  updateIntersectionFlags(graph);
  graph.sortLinksClockwise();
  reportProgress(progress, 1.0, "intersection simplification");
  return stats;
}

}  // namespace urbanvec::vectorize
