// Stage B7 (issue 20, extending spec §3 B1 and its "optional improvement", after B6): see
// through_roads.hpp. Arms and lines are fitted to the nodes' placements (the cells they were made
// for), not to their smoothed positions, so the lines are those of the cells; intersections are
// visited in node order and every step reads the positions the earlier ones left; on several threads
// the steps run speculatively and are committed in that order (SpeculativeMoves), with the same result.
#include "urbanvec/vectorize/roads/through_roads.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/core/parallel.hpp"
#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"
#include "urbanvec/vectorize/roads/speculative_moves.hpp"
#include "urbanvec/vectorize/roads/straightening.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

double digitalLineBand(const Vec2& d) {
  return 0.5 * (std::fabs(d.x) + std::fabs(d.y));
}

namespace {

/// Placements are cell centres and corners: a distance equal to a radius up to rounding counts as within.
constexpr double kPlacementRounding = 1e-9;

bool consistentWithLine(const std::vector<Vec2>& placements, const Vec2& centre, const Vec2& direction,
                        double slack) {
  // A digital line's cells reach the band's edge exactly (every other cell of a 45-degree staircase), so
  // the edge is inside up to the rounding of the cross product.
  constexpr double kRounding = 1e-9;
  const double band = digitalLineBand(direction) + slack + kRounding;
  for (const Vec2& p : placements)
    if (std::fabs(cross(direction, p - centre)) > band) return false;
  return true;
}

/// True when a road cell's centre lies within r of p.
bool nearRoadCell(const Grid<std::uint8_t>& cells, const Vec2& p, double r) {
  bool found = false;
  forEachCellNearSegment(cells, p, p, r,
                         [&](int col, int row, double) { found = found || isRoadCode(cells.at(col, row)); });
  return found;
}

/// How far a node of this type may lie from its placement and still be on its cells (pw).
double placementReach(NodeType type, double reach) {
  return reach + (type == NodeType::Primary ? std::sqrt(0.5) : 0.0);
}

bool isRoad(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

bool isChainEnd(const RoadGraph& graph, int i) {
  const RoadNode& n = graph.nodes[i];
  return n.intersection || n.links.size() != 2;
}

/// Where the stage may move nodes: the node index for neighbourhood queries and the longest link.
struct Surroundings {
  const NodeIndex& index;
  double longestLink = 0.0;  ///< padded by how far nodes may move
  double coverQuery = 0.0;   ///< radius around a cell holding an end of every link within coverRadius
  ReadFootprint* footprint = nullptr;  ///< what the item reads, when it runs speculatively (-threads)
};

/// The road cells within `radius` of the links of the moved nodes (cell indices, sorted).
std::vector<std::int64_t> cellsNearLinks(const RoadGraph& graph, const Grid<std::uint8_t>& cells,
                                         const std::vector<int>& moved, double radius) {
  std::vector<std::int64_t> out;
  for (int m : moved)
    for (int q : graph.nodes[m].links)
      if (graph.nodes[m].type != NodeType::Perimeter && graph.nodes[q].type != NodeType::Perimeter)
        forEachCellNearSegment(cells, graph.nodes[m].p, graph.nodes[q].p, radius,
                               [&](int col, int row, double) {
                                 if (isRoadCode(cells.at(col, row)))
                                   out.push_back(static_cast<std::int64_t>(row) * cells.width + col);
                               });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// True when one of the cells is farther than `radius` from every link.
bool anyUncovered(const RoadGraph& graph, const Grid<std::uint8_t>& cells, const Surroundings& around,
                  const std::vector<std::int64_t>& candidates, double radius) {
  for (std::int64_t k : candidates) {
    const Vec2 c = patchCentre(cells, static_cast<int>(k % cells.width), static_cast<int>(k / cells.width));
    bool covered = false;
    for (int a : recordedWithin(around.index, c, around.coverQuery, around.footprint)) {
      if (graph.nodes[a].type == NodeType::Perimeter) continue;  // perimeter links are no roads
      for (int b : graph.nodes[a].links)
        if (graph.nodes[b].type != NodeType::Perimeter &&
            distanceToSegment(c, graph.nodes[a].p, graph.nodes[b].p) <= radius) {
          covered = true;
          break;
        }
      if (covered) break;
    }
    if (!covered) return true;
  }
  return false;
}

bool movedLinksCross(const RoadGraph& graph, const Surroundings& around, const std::vector<int>& moved);

/// True when the moves just made must be undone: a moved link crosses another, or a road cell the
/// moved nodes' links covered before (`covered`) is no longer covered.
bool rejectMoves(const RoadGraph& graph, const ThroughRoadOptions& options, const Surroundings& around,
                 const std::vector<int>& moved, const std::vector<std::int64_t>& covered,
                 ThroughRoadStats& stats) {
  if (movedLinksCross(graph, around, moved)) {
    ++stats.crossingsAvoided;
    return true;
  }
  if (options.cells && anyUncovered(graph, *options.cells, around, covered, options.coverRadius)) {
    ++stats.uncoveringAvoided;
    return true;
  }
  return false;
}

/// True when a link of a moved node crosses another link (links sharing a node do not cross).
bool movedLinksCross(const RoadGraph& graph, const Surroundings& around, const std::vector<int>& moved) {
  for (int m : moved) {
    const Vec2 a = graph.nodes[m].p;
    for (int q : graph.nodes[m].links) {
      const Vec2 b = graph.nodes[q].p;
      for (int c :
           recordedWithin(around.index, a, distance(a, b) + around.longestLink + 1.0, around.footprint))
        for (int d : graph.nodes[c].links) {
          if (c == m || c == q || d == m || d == q) continue;
          if (segmentsCross(a, b, graph.nodes[c].p, graph.nodes[d].p)) return true;
        }
    }
  }
  return false;
}

/// Puts the positions of `nodes` back.
void restore(RoadGraph& graph, const std::vector<int>& nodes, const std::vector<Vec2>& positions) {
  for (std::size_t k = 0; k < nodes.size(); ++k) graph.nodes[nodes[k]].p = positions[k];
}

/// One road leaving an intersection: its nodes within the window (the last may be the next
/// intersection or dead end, which is fitted but not moved) and the line fitted to the placements of
/// those beyond the inner radius, and of the road beyond the window while it stays straight
/// (ThroughRoadOptions::fitReach).
struct Arm {
  std::vector<int> nodes;
  std::size_t movable = 0;  ///< nodes[0, movable) may be moved
  std::vector<Vec2> fitPlacements;
  bool fitted = false;
  Vec2 centre, direction;  ///< direction points away from the intersection
};

Arm buildArm(const RoadGraph& graph, int at, int next, const ThroughRoadOptions& options) {
  Arm arm;
  const Vec2 origin = graph.nodes[at].placed;
  const std::vector<int> chain = followChain(graph, at, next);
  std::size_t beyond = chain.size();  // the first chain node past the window, when the chain goes on
  for (std::size_t c = 0; c < chain.size(); ++c) {
    const int k = chain[c];
    const RoadNode& n = graph.nodes[k];
    if (k == at || !isRoad(n)) break;
    if (distance(n.placed, origin) > options.window) {
      beyond = c;
      break;
    }
    arm.nodes.push_back(k);
    if (isChainEnd(graph, k)) break;
    arm.movable = arm.nodes.size();
  }
  std::vector<Vec2>& placements = arm.fitPlacements;
  for (int k : arm.nodes)
    if (distance(graph.nodes[k].placed, origin) >= options.innerRadius)
      placements.push_back(graph.nodes[k].placed);
  if (placements.size() < 2) return arm;
  fitLine(placements, arm.centre, arm.direction);
  arm.fitted = consistentWithLine(placements, arm.centre, arm.direction, options.slack);
  // A straight arm's line is fitted on as much of its road as stays straight (fitReach); its pairing
  // test below still combines the placements within the window only, so a road that runs on past the
  // window into another one's cells (two primaries sharing a band) does not break a pair.
  // Only a road straight all the way (to its next end, or fitReach) is: one that starts to curve
  // beyond the window keeps the window's fit, as the curve's first cells still fit some line.
  std::vector<Vec2> longer = placements;
  Vec2 centre, direction;
  bool straight = true;
  for (std::size_t c = beyond; arm.fitted && c < chain.size(); ++c) {
    const RoadNode& n = graph.nodes[chain[c]];
    if (chain[c] == at || !isRoad(n) || distance(n.placed, origin) > options.fitReach) break;
    longer.push_back(n.placed);
    fitLine(longer, centre, direction);
    if (!consistentWithLine(longer, centre, direction, options.slack)) {
      straight = false;
      break;
    }
    if (isChainEnd(graph, chain[c])) break;
  }
  if (straight && longer.size() > placements.size()) {
    arm.centre = centre;
    arm.direction = direction;
  }
  if (dot(arm.direction, arm.centre - origin) < 0) arm.direction = arm.direction * -1.0;
  return arm;
}

/// The least-squares point of lines (centre, unit direction); false when they are (nearly) parallel.
bool leastSquaresCrossing(const std::vector<std::pair<Vec2, Vec2>>& lines, Vec2& out) {
  double a = 0, b = 0, c = 0, rx = 0, ry = 0;
  for (const auto& [centre, d] : lines) {
    // (I - d d^T) p = (I - d d^T) centre, summed.
    const double m00 = 1 - d.x * d.x, m01 = -d.x * d.y, m11 = 1 - d.y * d.y;
    a += m00;
    b += m01;
    c += m11;
    rx += m00 * centre.x + m01 * centre.y;
    ry += m01 * centre.x + m11 * centre.y;
  }
  const double det = a * c - b * b;
  if (det < 0.04 * static_cast<double>(lines.size() * lines.size())) return false;  // ~11.5 degrees
  out = Vec2((c * rx - b * ry) / det, (a * ry - b * rx) / det);
  return true;
}

/// straightChain on the placements of a road between the nodes e0 and e1 (drawn from a to b), or on
/// those farther than innerRadius from the placement of an end that is an intersection: a crossing's
/// cells bulge around its node, as the arms' fits leave them out. `scratch` is working space.
bool straightBetween(const RoadGraph& graph, const std::vector<Vec2>& placements, int e0, int e1,
                     const Vec2& a, const Vec2& b, const ThroughRoadOptions& options,
                     std::vector<Vec2>& scratch) {
  if (straightChain(placements, a, b, options)) return true;
  scratch.clear();
  for (const Vec2& p : placements) {
    bool crossing = false;
    for (int e : {e0, e1})
      crossing = crossing || (graph.nodes[e].links.size() >= 3 &&
                              distance(p, graph.nodes[e].placed) <= options.innerRadius + kPlacementRounding);
    if (!crossing) scratch.push_back(p);
  }
  return scratch.size() >= 2 && scratch.size() < placements.size() && straightChain(scratch, a, b, options);
}

void placeIntersection(RoadGraph& graph, int at, const ThroughRoadOptions& options,
                       const Surroundings& around, ThroughRoadStats& stats) {
  if (around.footprint) around.footprint->nodes.push_back(at);
  RoadNode& node = graph.nodes[at];
  const std::vector<std::int32_t> links = node.links;
  std::vector<Arm> arms;
  for (int next : links) arms.push_back(buildArm(graph, at, next, options));
  // Pairs of fitted arms close to opposite, straightest first; each arm in one pair at most, and the
  // pair only when the placements of both arms are consistent with one straight line.
  const double pairCos = -std::cos(options.pairAngle * M_PI / 180.0);
  struct Pair {
    double cosine;
    std::size_t a, b;
    Vec2 centre, direction;
  };
  std::vector<Pair> candidates;
  for (std::size_t a = 0; a < arms.size(); ++a)
    for (std::size_t b = a + 1; b < arms.size(); ++b) {
      if (!arms[a].fitted || !arms[b].fitted) continue;
      const double c = dot(arms[a].direction, arms[b].direction);
      if (c > pairCos) continue;
      candidates.push_back({c, a, b, {}, {}});
    }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Pair& x, const Pair& y) { return x.cosine < y.cosine; });
  std::vector<char> paired(arms.size(), 0);
  std::vector<Pair> pairs;
  for (Pair p : candidates) {
    if (paired[p.a] || paired[p.b]) continue;
    std::vector<Vec2> placements = arms[p.a].fitPlacements;
    placements.insert(placements.end(), arms[p.b].fitPlacements.begin(), arms[p.b].fitPlacements.end());
    fitLine(placements, p.centre, p.direction);
    if (!consistentWithLine(placements, p.centre, p.direction, options.slack)) continue;
    paired[p.a] = paired[p.b] = 1;
    pairs.push_back(p);
  }
  stats.pairs += pairs.size();
  if (pairs.empty()) return;

  // The node: the crossing of the pair lines; with one pair, the point of its line nearest (least
  // squares) to the other arms' lines, so the through road stays straight and the stems meet it.
  Vec2 target = node.p;
  if (pairs.size() >= 2) {
    std::vector<std::pair<Vec2, Vec2>> lines;
    for (const Pair& p : pairs) lines.push_back({p.centre, p.direction});
    if (!leastSquaresCrossing(lines, target)) return;
  } else {
    const Pair& p = pairs[0];
    double num = 0, den = 0;
    for (std::size_t s = 0; s < arms.size(); ++s) {
      if (paired[s] || !arms[s].fitted) continue;
      const Vec2 n(-arms[s].direction.y, arms[s].direction.x);
      const double off = dot(n, p.centre - arms[s].centre), along = dot(n, p.direction);
      num += off * along;
      den += along * along;
    }
    const double t = den > 0.04 ? -num / den : dot(node.p - p.centre, p.direction);
    target = p.centre + p.direction * t;
  }
  // Bounded by the cells: the node stays within reach of a cell of the crossing (its own placement or
  // one of its arms' nodes), as smoothing keeps nodes within reach of theirs.
  bool inReach = false;
  if (options.cells) {
    inReach = nearRoadCell(*options.cells, target, options.reach);
  } else {
    inReach = distance(target, node.placed) <= smoothingShiftLimit(node.type, options.reach);
    for (const Arm& arm : arms)
      for (int k : arm.nodes)
        inReach = inReach || distance(target, graph.nodes[k].placed) <=
                                 smoothingShiftLimit(graph.nodes[k].type, options.reach);
  }
  if (!inReach) {
    ++stats.outOfReach;
    return;
  }
  // Every node that may move: the crossing and its arms' movable nodes (for the coverage check).
  std::vector<int> mayMove{at};
  for (const Arm& arm : arms)
    mayMove.insert(mayMove.end(), arm.nodes.begin(), arm.nodes.begin() + arm.movable);
  if (around.footprint)
    around.footprint->nodes.insert(around.footprint->nodes.end(), mayMove.begin(), mayMove.end());
  const std::vector<std::int64_t> covered =
      options.cells ? cellsNearLinks(graph, *options.cells, mayMove, options.coverRadius)
                    : std::vector<std::int64_t>();
  std::vector<int> moved{at};
  std::vector<Vec2> before{node.p};
  node.p = target;

  // Approaches: each arm's nodes near the node go onto the straight line from the node to the arm's
  // first node left in place (its next end, or the first node beyond the window), so a through road
  // runs straight and a stem meets the crossing at its own angle without a hook. When a node would
  // leave the reach of the cells, the straight piece is shortened (anchored one node nearer) until
  // all fit. Positions along the line never go back, so the arm cannot fold.
  std::vector<Vec2> onLine, cells, scratch;
  for (Arm& arm : arms) {
    if (arm.movable == 0) continue;
    const std::vector<int> chain = followChain(graph, at, arm.nodes[0]);
    for (std::size_t count = arm.movable; count >= 1; --count) {
      const int anchor = chain[std::min(count, chain.size() - 1)];
      if (anchor == at) break;
      const Vec2 ab = graph.nodes[anchor].p - target;
      const double len2 = dot(ab, ab);
      if (len2 == 0) break;
      onLine.clear();
      double along = 0.0;
      bool inReach = true;
      for (std::size_t m = 0; m < count && inReach; ++m) {
        const RoadNode& n = graph.nodes[arm.nodes[m]];
        along = std::clamp(dot(n.p - target, ab) / len2, along, 1.0);
        onLine.push_back(target + ab * along);
        inReach = options.cells
                      ? distance(onLine.back(), n.placed) <= placementReach(n.type, options.reach) &&
                            nearRoadCell(*options.cells, onLine.back(), options.reach)
                      : distance(onLine.back(), n.placed) <= smoothingShiftLimit(n.type, options.reach);
      }
      if (!inReach) continue;
      if (options.straightApproachesOnly) {
        // Only an approach whose cells are straight is drawn straight (the straight-road rule, from the
        // crossing to the anchor): a road curving into a crossing keeps its curve.
        cells.assign(1, node.placed);
        for (std::size_t m = 0; m < count; ++m) cells.push_back(graph.nodes[arm.nodes[m]].placed);
        cells.push_back(graph.nodes[anchor].placed);
        if (!straightBetween(graph, cells, at, anchor, target, graph.nodes[anchor].p, options, scratch))
          continue;
      }
      for (std::size_t m = 0; m < count; ++m) {
        moved.push_back(arm.nodes[m]);
        before.push_back(graph.nodes[arm.nodes[m]].p);
        graph.nodes[arm.nodes[m]].p = onLine[m];
      }
      ++stats.approaches;
      break;
    }
  }
  // A move that would make roads cross (the output has no crossings but at nodes) or uncover a road
  // cell is not made.
  if (rejectMoves(graph, options, around, moved, covered, stats)) {
    restore(graph, moved, before);
    return;
  }
  ++stats.nodesPlaced;
}

/// Straight roads from node i (B7's second part): every chain from i to a higher-numbered end whose
/// placements lie in the band of the straight line joining its (placed) ends, or of their own line with
/// the ends near it (straightChain), is drawn on the segment between its ends.
void straightenChainsFrom(RoadGraph& graph, std::size_t i, const ThroughRoadOptions& options,
                          const Surroundings& around, ThroughRoadStats& stats) {
  std::vector<Vec2> placements, outer;
  const std::vector<std::int32_t> links = graph.nodes[i].links;
  for (int next : links) {
    const std::vector<int> chain = followChain(graph, static_cast<int>(i), next);
    const int end = chain.back();
    if (end <= static_cast<int>(i) || chain.size() < 2) continue;  // each chain once; loops skipped
    bool road = true;
    placements.assign(1, graph.nodes[i].placed);
    for (int k : chain) {
      road = road && isRoad(graph.nodes[k]);
      placements.push_back(graph.nodes[k].placed);
    }
    if (!road) continue;
    if (around.footprint) {  // the positions of i, the chain and their neighbours are read from here on
      around.footprint->nodes.push_back(static_cast<int>(i));
      around.footprint->nodes.insert(around.footprint->nodes.end(), chain.begin(), chain.end());
    }
    const Vec2 a = graph.nodes[i].p, b = graph.nodes[end].p;
    if (!straightBetween(graph, placements, static_cast<int>(i), end, a, b, options, outer)) continue;
    const Vec2 ab = b - a;
    double along = 0.0;
    const std::vector<int> moved(chain.begin(), chain.end() - 1);
    const std::vector<std::int64_t> covered =
        options.cells ? cellsNearLinks(graph, *options.cells, moved, options.coverRadius)
                      : std::vector<std::int64_t>();
    std::vector<Vec2> before;
    for (int k : moved) {
      RoadNode& node = graph.nodes[k];
      before.push_back(node.p);
      along = std::clamp(dot(node.p - a, ab) / dot(ab, ab), along, 1.0);
      node.p = a + ab * along;
    }
    if (rejectMoves(graph, options, around, moved, covered, stats)) {
      restore(graph, moved, before);
      continue;
    }
    ++stats.straightChains;
  }
}

void addStats(ThroughRoadStats& to, const ThroughRoadStats& s) {
  to.intersections += s.intersections;
  to.pairs += s.pairs;
  to.nodesPlaced += s.nodesPlaced;
  to.outOfReach += s.outOfReach;
  to.approaches += s.approaches;
  to.straightChains += s.straightChains;
  to.crossingsAvoided += s.crossingsAvoided;
  to.uncoveringAvoided += s.uncoveringAvoided;
}

}  // namespace

bool consistentWithSegment(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b, double slack) {
  const Vec2 ab = b - a;
  const double len = length(ab);
  if (len == 0) return false;
  return consistentWithLine(placements, a, ab / len, slack);
}

bool straightChain(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b,
                   const ThroughRoadOptions& options) {
  if (consistentWithSegment(placements, a, b, options.slack)) return true;
  if (!(options.endOffset > 0.0) || placements.size() < 2) return false;
  // The placements form a digital straight line of their own fitted line, and the ends the road is
  // drawn between lie near it: within endOffset of the band.
  Vec2 centre, direction;
  fitLine(placements, centre, direction);
  const double ends = options.endOffset * digitalLineBand(direction) + options.slack;
  return consistentWithLine(placements, centre, direction, options.slack) &&
         std::fabs(cross(direction, a - centre)) <= ends && std::fabs(cross(direction, b - centre)) <= ends;
}

ThroughRoadStats straightenThroughRoads(RoadGraph& graph, const ThroughRoadOptions& options,
                                        const Progress& progress) {
  ThroughRoadStats stats;
  if (!options.enabled) {
    reportProgress(progress, 1.0, "through roads");
    return stats;
  }
  updateIntersectionFlags(graph);
  const std::size_t n = graph.nodes.size();
  // Intersections are placed one after another in node order, then the straight roads drawn, each move
  // checked against the positions the earlier ones left: on several threads, speculatively with the same
  // result (SpeculativeMoves).
  SpeculativeMoves moves(graph, workerCount(options.threads), 4.0);
  double longestLink = 0.0;
  for (const RoadNode& node : graph.nodes)
    if (node.alive)
      for (int q : node.links) longestLink = std::max(longestLink, distance(node.p, graph.nodes[q].p));
  // Moves only shorten or keep links near the window's size; a link within coverRadius of a cell has
  // an end within coverRadius + its length of it.
  const double coverQuery = longestLink + 2.0 * options.window + options.coverRadius;
  // Nodes move by a few pw at most; the neighbourhood queries look that much farther.
  longestLink += 2.0 * (options.reach + options.window);
  auto surroundings = [&](const NodeIndex& index, ReadFootprint* footprint) {
    return Surroundings{index, longestLink, coverQuery, footprint};
  };
  std::vector<int> items;
  for (std::size_t i = 0; i < n; ++i) {
    const RoadNode& node = graph.nodes[i];
    if (isRoad(node) && node.intersection && node.links.size() >= 3) items.push_back(static_cast<int>(i));
  }
  std::vector<ThroughRoadStats> itemStats(items.size());
  const Progress placing = subProgress(progress, 0.0, 0.6);
  ProgressTicker ticker(placing, "through roads", items.size());
  moves.run(
      items.size(),
      [&](std::size_t k, RoadGraph& g, const NodeIndex& index, ReadFootprint* footprint) {
        itemStats[k] = ThroughRoadStats();
        ++itemStats[k].intersections;
        placeIntersection(g, items[k], options, surroundings(index, footprint), itemStats[k]);
      },
      [&](std::size_t done) { ticker.tick(done); });
  ticker.finish();

  // Straight roads: the chains from every road node that ends chains, in node order.
  items.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (isRoad(graph.nodes[i]) && isChainEnd(graph, static_cast<int>(i)))
      items.push_back(static_cast<int>(i));
  for (const ThroughRoadStats& s : itemStats) addStats(stats, s);
  itemStats.assign(items.size(), ThroughRoadStats());
  moves.run(items.size(), [&](std::size_t k, RoadGraph& g, const NodeIndex& index, ReadFootprint* footprint) {
    itemStats[k] = ThroughRoadStats();
    straightenChainsFrom(g, static_cast<std::size_t>(items[k]), options, surroundings(index, footprint),
                         itemStats[k]);
  });
  for (const ThroughRoadStats& s : itemStats) addStats(stats, s);
  graph.sortLinksClockwise(options.threads);
  reportProgress(progress, 1.0, "through roads");
  return stats;
}

}  // namespace urbanvec::vectorize
