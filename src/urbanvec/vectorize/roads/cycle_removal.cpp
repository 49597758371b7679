// Stage B4 (spec §3 B4) with the [INFERENCE] face-based cycle definition of Q10, and its "undeveloped
// only" flag on when a land-use grid is given (faces enclosing developed land keep their roads).
// [INFERENCE] A qualifying face whose cycle has fewer than two chain ends (an isolated ring or a loop
// hanging from one node) has no "segment between intersections"; its longest link is removed, which
// opens the cycle without dropping road.
#include "urbanvec/vectorize/roads/cycle_removal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/landuse.hpp"
#include "urbanvec/core/parallel.hpp"
#include "urbanvec/vectorize/roads/road_checks.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

namespace {

struct RoadAdjacency {
  std::vector<std::int32_t> offsets;  ///< per node, into `to`
  std::vector<std::int32_t> to;       ///< road neighbours, clockwise (graph must be sorted)
};

RoadAdjacency roadAdjacency(const RoadGraph& g) {
  RoadAdjacency a;
  a.offsets.assign(g.nodes.size() + 1, 0);
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    a.offsets[i + 1] = a.offsets[i];
    const RoadNode& n = g.nodes[i];
    if (!n.alive || n.type == NodeType::Perimeter) continue;
    for (int j : n.links)
      if (g.nodes[j].type != NodeType::Perimeter) {
        a.to.push_back(j);
        ++a.offsets[i + 1];
      }
  }
  return a;
}

/// Walks all faces; returns, per bounded face, its cycle as a node sequence.
/// True when a cell centre inside the face (internal frame: x = col + 0.5, y = H - row - 0.5) holds
/// developed land.
bool enclosesDevelopedLand(const RoadGraph& g, const std::vector<int>& face,
                           const Grid<std::uint8_t>& landUse, bool anyLand) {
  Ring ring;
  ring.reserve(face.size() + 1);
  for (int n : face) ring.push_back(g.nodes[n].p);
  ring.push_back(ring.front());
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  for (const Vec2& p : ring) {
    minX = std::min(minX, p.x), maxX = std::max(maxX, p.x);
    minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
  }
  const int dx = landUse.frameDx, h = landUse.frameDy + landUse.height;  // a window's frame (issue 22)
  for (int col = static_cast<int>(std::floor(minX)) - dx; col <= static_cast<int>(std::ceil(maxX)) - dx;
       ++col)
    for (int row = h - static_cast<int>(std::ceil(maxY)) - 1; row <= h - static_cast<int>(std::floor(minY));
         ++row) {
      if (!landUse.inside(col, row)) continue;
      const std::uint8_t code = landUse.at(col, row);
      if (anyLand ? isRoadCode(code) || code == kRemovedRoad : !isDeveloped(static_cast<LandUse>(code)))
        continue;
      const Vec2 centre(dx + col + 0.5, h - row - 0.5);
      // Even-odd ray cast.
      bool inside = false;
      for (size_t k = 0; k + 1 < ring.size(); ++k) {
        const Vec2 &a = ring[k], &b = ring[k + 1];
        if ((a.y > centre.y) != (b.y > centre.y) &&
            centre.x < a.x + (centre.y - a.y) * (b.x - a.x) / (b.y - a.y))
          inside = !inside;
      }
      if (inside) return true;
    }
  return false;
}

/// Walks all faces of the embedding the clockwise-sorted links give, as PlanarGraph::faces does (nodes in
/// index order, each node's links in rotation order, the leftmost turn at every node, the same shoelace
/// terms in the same order), but on the adjacency lists themselves: building a PlanarGraph of the whole
/// road graph (a polyline per link, a rotation per node) cost more than the walk (issue 21). Returns, per
/// face of twice signed area in [-1e-9, 2 maxFaceArea], its cycle as a node sequence.
std::vector<std::vector<int>> walkFaces(const RoadGraph& g, const RoadAdjacency& a, double maxFaceArea) {
  const std::size_t slots = a.to.size();
  std::vector<std::int32_t> originOf(slots), twin(slots, -1);
  for (std::size_t i = 0; i + 1 < a.offsets.size(); ++i)
    for (int k = a.offsets[i]; k < a.offsets[i + 1]; ++k) {
      originOf[k] = static_cast<std::int32_t>(i);
      const int j = a.to[k];
      if (static_cast<int>(i) >= j) continue;
      for (int back = a.offsets[j]; back < a.offsets[j + 1]; ++back)
        if (a.to[back] == static_cast<int>(i)) {
          twin[k] = back;
          twin[back] = k;
        }
    }
  for (std::size_t k = 0; k < slots; ++k)
    if (twin[k] < 0) throw internalError("cycle removal: a road link is not listed at both of its ends");
  auto linkOf = [&](int slot) { return std::min(slot, twin[slot]); };
  std::vector<char> done(slots, 0);
  std::vector<std::uint8_t> walked(slots, 0);  // per link (its lower slot), times this face walks it
  std::vector<int> face;
  std::vector<std::vector<int>> faces;
  for (std::size_t first = 0; first < slots; ++first) {
    if (done[first]) continue;
    face.clear();
    double twiceArea = 0.0;
    for (int h = static_cast<int>(first); !done[h];) {
      done[h] = 1;
      face.push_back(h);
      const Vec2& from = g.nodes[originOf[h]].p;
      const Vec2& to = g.nodes[a.to[h]].p;
      twiceArea += from.x * to.y - to.x * from.y;
      // Leftmost turn: at v, the link after v->u clockwise keeps the face on the left.
      const int v = a.to[h];
      const int degree = a.offsets[v + 1] - a.offsets[v];
      h = a.offsets[v] + (twin[h] - a.offsets[v] + 1) % degree;
    }
    // Outer faces of components are clockwise (negative area). A loop that smoothing has collapsed onto
    // a line encloses (almost) nothing but is still a cycle, so faces of about zero area count too;
    // the walk around a tree has an empty cycle and is dropped below.
    if (twiceArea < -1e-9 || twiceArea > 2 * maxFaceArea) continue;
    // Drop links walked both ways (dangling branches): what is left is the cycle, in walk order.
    for (int h : face) ++walked[linkOf(h)];
    std::vector<int> cycle;
    for (int h : face)
      if (walked[linkOf(h)] == 1) cycle.push_back(originOf[h]);
    for (int h : face) walked[linkOf(h)] = 0;
    if (cycle.size() >= 3) faces.push_back(std::move(cycle));
  }
  return faces;
}

}  // namespace

std::vector<std::vector<int>> boundedRoadFaces(const RoadGraph& graph) {
  return walkFaces(graph, roadAdjacency(graph), 1e300);
}

CycleRemovalStats removeShortCycles(RoadGraph& graph, const CycleRemovalOptions& options,
                                    const Progress& progress) {
  CycleRemovalStats stats;
  // The face walk needs a planar embedding; smoothing can make links cross (tiny twisted loops).
  if (options.planarizeFirst) stats.crossingsNoded = nodeCrossingsAndContractTinyLinks(graph);
  graph.sortLinksClockwise(options.threads);
  for (int round = 0; round < options.maxRounds; ++round) {
    const RoadAdjacency adj = roadAdjacency(graph);
    auto roadDegree = [&](int i) { return adj.offsets[i + 1] - adj.offsets[i]; };
    std::vector<std::vector<int>> faces =
        walkFaces(graph, adj,
                  options.keepLandCycles ? std::min(options.maxFaceArea, options.landlessFaceArea)
                                         : options.maxFaceArea);
    // Distinct-node count per face (and whether it keeps its roads, on the workers); smallest faces
    // first (deterministic).
    std::vector<int> distinctNodes(faces.size(), 0);
    std::vector<char> keeps(faces.size(), 0);
    runChunks(workerCount(options.threads), faces.size(), 256, [&](size_t begin, size_t end, size_t) {
      for (size_t f = begin; f < end; ++f) {
        std::vector<int> nodes = faces[f];
        std::sort(nodes.begin(), nodes.end());
        distinctNodes[f] = static_cast<int>(std::unique(nodes.begin(), nodes.end()) - nodes.begin());
        keeps[f] = distinctNodes[f] <= options.maxCycleNodes && options.landUse &&
                   enclosesDevelopedLand(graph, faces[f], *options.landUse, options.keepLandCycles);
      }
    });
    std::vector<std::pair<int, int>> order;
    for (size_t f = 0; f < faces.size(); ++f) {
      if (distinctNodes[f] > options.maxCycleNodes) continue;
      if (keeps[f]) {
        if (round == 0) ++stats.developedFacesKept;
        continue;
      }
      order.emplace_back(distinctNodes[f], static_cast<int>(f));
    }
    if (order.empty()) break;
    std::sort(order.begin(), order.end());
    ++stats.rounds;
    std::size_t removedThisRound = 0;
    for (const auto& [distinct, f] : order) {
      const std::vector<int>& cycle = faces[f];
      const size_t m = cycle.size();
      // Still intact? An earlier removal this round may have opened it already.
      bool intact = true;
      for (size_t k = 0; k < m && intact; ++k)
        intact = graph.nodes[cycle[k]].alive && graph.linked(cycle[k], cycle[(k + 1) % m]);
      if (!intact) continue;
      // Chain ends: cycle nodes whose road degree is not 2 (degrees taken from this round's start).
      std::vector<size_t> ends;
      for (size_t k = 0; k < m; ++k)
        if (roadDegree(cycle[k]) != 2 || graph.degree(cycle[k]) != 2) ends.push_back(k);
      if (ends.size() < 2) {
        size_t longest = 0;
        for (size_t k = 1; k < m; ++k)
          if (distance(graph.nodes[cycle[k]].p, graph.nodes[cycle[(k + 1) % m]].p) >
              distance(graph.nodes[cycle[longest]].p, graph.nodes[cycle[(longest + 1) % m]].p))
            longest = k;
        stats.removedLinks.push_back(
            {graph.nodes[cycle[longest]].p, graph.nodes[cycle[(longest + 1) % m]].p});
        graph.unlink(cycle[longest], cycle[(longest + 1) % m]);
        ++removedThisRound;
        continue;
      }
      // Chains between consecutive ends; pick (secondary first, then shortest).
      size_t bestStart = 0, bestLen = 0;
      double bestLength = 0;
      bool bestPrimary = true, found = false;
      for (size_t e = 0; e < ends.size(); ++e) {
        const size_t s = ends[e], t = ends[(e + 1) % ends.size()];
        const size_t len = (t + m - s) % m == 0 ? m : (t + m - s) % m;
        double chainLength = 0;
        bool primary = false;
        for (size_t k = 0; k < len; ++k) {
          const int u = cycle[(s + k) % m], v = cycle[(s + k + 1) % m];
          chainLength += distance(graph.nodes[u].p, graph.nodes[v].p);
          primary |= graph.nodes[u].type == NodeType::Primary && graph.nodes[v].type == NodeType::Primary;
        }
        if (!found || primary < bestPrimary || (primary == bestPrimary && chainLength < bestLength)) {
          found = true;
          bestPrimary = primary;
          bestLength = chainLength;
          bestStart = s;
          bestLen = len;
        }
      }
      for (size_t k = 0; k < bestLen; ++k)
        stats.removedLinks.push_back(
            {graph.nodes[cycle[(bestStart + k) % m]].p, graph.nodes[cycle[(bestStart + k + 1) % m]].p});
      if (bestLen == 1) {
        graph.unlink(cycle[bestStart], cycle[(bestStart + 1) % m]);
      } else {
        for (size_t k = 1; k < bestLen; ++k) graph.removeNode(cycle[(bestStart + k) % m]);
      }
      ++removedThisRound;
    }
    stats.segmentsRemoved += removedThisRound;
    reportProgress(progress, std::min(0.95, 0.2 * (round + 1)), "cycle removal");
    if (removedThisRound == 0) break;
  }
  graph.compact();
  updateIntersectionFlags(graph);
  graph.sortLinksClockwise(options.threads);
  reportProgress(progress, 1.0, "cycle removal");
  return stats;
}

}  // namespace urbanvec::vectorize
