// Stage B5 (spec §3 B5) with its [INFERENCE] choices: a dead end is a degree-1 neighbour of the
// intersection; a close node is contracted (the intersection takes over its other links), and a close
// node that is itself an intersection (the paper's "of one another") is merged at the average
// position. Intersections here are road nodes with three or more links; perimeter nodes are never
// removed.
#include "urbanvec/vectorize/roads/intersection_simplification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>

#include "urbanvec/vectorize/roads/road_network.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

namespace {

bool isRoad(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

/// How many road links pass within `radius` of each cell centre, kept up to date while B5 contracts,
/// so a contraction that would leave a covered road cell with none is seen before it is made.
class LinkCover {
 public:
  LinkCover(const RoadGraph& graph, const Grid<std::uint8_t>& cells, double radius)
      : cells_(cells), radius_(radius), count_(cells.cells.size(), 0) {
    for (size_t a = 0; a < graph.nodes.size(); ++a) {
      if (!isRoad(graph.nodes[a])) continue;
      for (int b : graph.nodes[a].links)
        if (b > static_cast<int>(a) && isRoad(graph.nodes[b])) add(graph.nodes[a].p, graph.nodes[b].p, 1);
    }
  }
  /// Adds `delta` to the count of every cell within the radius of segment ab.
  void add(const Vec2& a, const Vec2& b, int delta) {
    forEachCellNearSegment(cells_, a, b, radius_, [&](int col, int row, double) {
      count_[static_cast<size_t>(row) * cells_.width + col] += delta;
    });
  }
  /// Whether a road cell within the radius of segment ab has no link left.
  bool uncoveredNear(const Vec2& a, const Vec2& b) const {
    bool uncovered = false;
    forEachCellNearSegment(cells_, a, b, radius_, [&](int col, int row, double) {
      const size_t i = static_cast<size_t>(row) * cells_.width + col;
      uncovered = uncovered || (isRoadCode(cells_.cells[i]) && count_[i] <= 0);
    });
    return uncovered;
  }

 private:
  const Grid<std::uint8_t>& cells_;
  double radius_;
  std::vector<std::int32_t> count_;
};

/// The road nodes linked to `a` or `b` (each once, `a` and `b` left out): the neighbours of the node
/// B5 makes of the two.
std::vector<int> mergedNeighbours(const RoadGraph& graph, int a, int b) {
  std::vector<int> out;
  for (int end : {a, b})
    for (int z : graph.nodes[end].links)
      if (z != a && z != b && isRoad(graph.nodes[z]) && std::find(out.begin(), out.end(), z) == out.end())
        out.push_back(z);
  return out;
}

/// The road links of node `a` (to road nodes), as segments from `from` (a's position, or where it
/// will be) to each neighbour, leaving out the nodes in `skip`.
std::vector<std::array<Vec2, 2>> roadLinks(const RoadGraph& graph, int a, const Vec2& from,
                                           std::initializer_list<int> skip) {
  std::vector<std::array<Vec2, 2>> out;
  for (int b : graph.nodes[a].links)
    if (isRoad(graph.nodes[b]) && std::find(skip.begin(), skip.end(), b) == skip.end())
      out.push_back({from, graph.nodes[b].p});
  return out;
}

}  // namespace

IntersectionSimplificationStats simplifyIntersections(RoadGraph& graph,
                                                      const IntersectionSimplificationOptions& options,
                                                      const Progress& progress) {
  IntersectionSimplificationStats stats;
  const double cosLimit = std::cos(options.deadEndAngle * M_PI / 180.0);
  const size_t n = graph.nodes.size();
  // 1. Dead ends angled within deadEndAngle of another road (none when it is 0: cos 0 = 1 is not a
  // safe bound for rounded cosines of parallel links).
  for (size_t i = 0; i < n && options.deadEndAngle > 0.0; ++i) {
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
  std::optional<LinkCover> cover;
  if (options.coverCells) cover.emplace(graph, *options.coverCells, options.coverRadius);
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
        if (cover) {
          // The links of both ends go; the merged node, where it will stand, links to the union of
          // their neighbours. Keep the two nodes when that leaves a road cell without a link.
          const Vec2 merged = isIntersection ? (graph.nodes[i].p + cn.p) * 0.5 : graph.nodes[i].p;
          auto gone = roadLinks(graph, c, cn.p, {});
          const auto ofIntersection = roadLinks(graph, static_cast<int>(i), graph.nodes[i].p, {c});
          gone.insert(gone.end(), ofIntersection.begin(), ofIntersection.end());
          std::vector<std::array<Vec2, 2>> after;
          for (int z : mergedNeighbours(graph, static_cast<int>(i), c))
            after.push_back({merged, graph.nodes[z].p});
          for (const auto& l : gone) cover->add(l[0], l[1], -1);
          for (const auto& l : after) cover->add(l[0], l[1], 1);
          bool uncovers = false;
          for (const auto& l : gone) uncovers = uncovers || cover->uncoveredNear(l[0], l[1]);
          if (uncovers) {
            for (const auto& l : after) cover->add(l[0], l[1], -1);
            for (const auto& l : gone) cover->add(l[0], l[1], 1);
            ++stats.contractionsKept;
            continue;
          }
        }
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
