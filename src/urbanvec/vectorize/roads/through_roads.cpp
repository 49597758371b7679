// Stage B7 (issue 20, extending spec §3 B1 and its "optional improvement", after B6): see
// through_roads.hpp. Arms and lines are fitted to the nodes' placements (the cells they were made
// for), not to their smoothed positions, so the lines are those of the cells; intersections are
// visited in node order and every step reads the positions the earlier ones left; on several threads
// the steps run speculatively and are committed in that order (SpeculativeMoves), with the same result.
#include "urbanvec/vectorize/roads/through_roads.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "urbanvec/core/parallel.hpp"
#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/vectorize/roads/road_graph_build.hpp"
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

/// True when every point between a and b (sampled every quarter cell, the ends left out) lies within r of
/// a road cell.
bool segmentOnCells(const Grid<std::uint8_t>& cells, const Vec2& a, const Vec2& b, double r) {
  const int steps = static_cast<int>(std::ceil(distance(a, b) / 0.25));
  for (int s = 1; s < steps; ++s)
    if (!nearRoadCell(cells, a + (b - a) * (static_cast<double>(s) / steps), r)) return false;
  return true;
}

/// How far a node of this type may lie from its placement and still be on its cells (pw).
double placementReach(NodeType type, double reach) {
  return reach + (type == NodeType::Primary ? std::sqrt(0.5) : 0.0);
}

/// Whether an approach node may go to onLine, a point of the straight piece its approach is drawn on:
/// within reach of its placement (pw, or the smoothing limit without cells) and of a road cell. A node
/// of a chain (at most two links: a rebuilt cluster's arm is linked to its junction after its approach
/// is drawn) may leave its placement's reach, up to twice it (a wide square's cells would otherwise let
/// any piece through), when the whole piece runs on road cells (pieceOnCells): a
/// stem whose skeleton hooks through another road's band then meets the crossing at its own angle, and
/// the coverage check keeps every cell covered (issue 20).
bool approachInReach(const RoadNode& n, const Vec2& onLine, bool pieceOnCells,
                     const ThroughRoadOptions& options) {
  if (!options.cells) return distance(onLine, n.placed) <= smoothingShiftLimit(n.type, options.reach);
  const double shift = distance(onLine, n.placed), reach = placementReach(n.type, options.reach);
  return (shift <= reach || (pieceOnCells && n.links.size() <= 2 && shift <= 2.0 * reach)) &&
         nearRoadCell(*options.cells, onLine, options.reach);
}

/// True when the straight piece ab of an approach lies within reach of road cells all along
/// (approachInReach), and the rule is on.
bool pieceOnRoadCells(const Vec2& a, const Vec2& b, const ThroughRoadOptions& options) {
  return options.cells && options.stemThroughBands && segmentOnCells(*options.cells, a, b, options.reach);
}

bool isRoad(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

bool isChainEnd(const RoadGraph& graph, int i) {
  const RoadNode& n = graph.nodes[i];
  return n.intersection || n.links.size() != 2;
}

/// A bucket index over node positions that follows the nodes as they move (the junction clusters,
/// rebuilt one after another on one thread): its queries see where the nodes are now, so they need
/// look no farther than the longest link, however far earlier rebuilds moved their junctions.
class LiveIndex {
 public:
  LiveIndex(const RoadGraph& graph, double bucket) : graph_(graph), bucket_(bucket) {
    // Buckets over the nodes' bounding box, not from the origin: a window of a tiled run lies far from
    // (0, 0) in the grid's frame.
    double maxX = 0.0, maxY = 0.0;
    bool first = true;
    for (const RoadNode& node : graph.nodes) {
      minX_ = first ? node.p.x : std::min(minX_, node.p.x);
      minY_ = first ? node.p.y : std::min(minY_, node.p.y);
      maxX = first ? node.p.x : std::max(maxX, node.p.x);
      maxY = first ? node.p.y : std::max(maxY, node.p.y);
      first = false;
    }
    nx_ = static_cast<int>((maxX - minX_) / bucket_) + 1;
    ny_ = static_cast<int>((maxY - minY_) / bucket_) + 1;
    buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (std::size_t i = 0; i < graph.nodes.size(); ++i) update(static_cast<int>(i));
  }
  /// Files node k where it is now (alive) or nowhere (removed).
  void update(int k) {
    if (static_cast<std::size_t>(k) >= bucketOf_.size()) bucketOf_.resize(k + 1, -1);
    const int to = graph_.nodes[k].alive ? bucketAt(graph_.nodes[k].p) : -1;
    if (to == bucketOf_[k]) return;
    if (bucketOf_[k] >= 0) {
      std::vector<int>& from = buckets_[bucketOf_[k]];
      from.erase(std::find(from.begin(), from.end(), k));
    }
    if (to >= 0) buckets_[to].push_back(k);
    bucketOf_[k] = to;
  }
  /// NodeIndex::anyWithin over where the nodes are now.
  template <class Visit>
  bool anyWithin(const Vec2& p, double r, Visit&& visit) const {
    const int x0 = clampX(p.x - r), x1 = clampX(p.x + r), y0 = clampY(p.y - r), y1 = clampY(p.y + r);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int k : buckets_[static_cast<std::size_t>(y) * nx_ + x])
          if (distance(graph_.nodes[k].p, p) <= r && visit(k)) return true;
    return false;
  }

 private:
  const RoadGraph& graph_;
  double bucket_;
  double minX_ = 0.0, minY_ = 0.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
  std::vector<int> bucketOf_;
  int clampX(double x) const {
    return static_cast<int>(std::clamp(std::floor((x - minX_) / bucket_), 0.0, static_cast<double>(nx_ - 1)));
  }
  int clampY(double y) const {
    return static_cast<int>(std::clamp(std::floor((y - minY_) / bucket_), 0.0, static_cast<double>(ny_ - 1)));
  }
  int bucketAt(const Vec2& p) const { return clampY(p.y) * nx_ + clampX(p.x); }
};

/// Where the stage may move nodes: the node index for neighbourhood queries and the longest link.
struct Surroundings {
  const NodeIndex* index = nullptr;  ///< built before the moves (speculative steps)
  double longestLink = 0.0;          ///< padded by how far nodes may move
  double coverQuery = 0.0;           ///< radius around a cell holding an end of every link within coverRadius
  ReadFootprint* footprint = nullptr;  ///< what the item reads, when it runs speculatively (-threads)
  LiveIndex* live = nullptr;           ///< instead of `index`: where the nodes are now (junction clusters)
};

/// Visits the nodes within r of p until `visit` returns true (true when it did): where they are now
/// (live), or where `index` holds them (the caller pads r by how far nodes may have moved since).
template <class Visit>
bool anyNodeNear(const Surroundings& around, const Vec2& p, double r, Visit&& visit) {
  return around.live ? around.live->anyWithin(p, r, visit)
                     : recordedAnyWithin(*around.index, p, r, around.footprint, visit);
}

/// The length of the graph's longest link (pw).
double longestLink(const RoadGraph& graph) {
  double longest = 0.0;
  for (const RoadNode& node : graph.nodes)
    if (node.alive)
      for (int q : node.links) longest = std::max(longest, distance(node.p, graph.nodes[q].p));
  return longest;
}

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

/// The centres of the candidate cells farther than `radius` from every link (at most `limit` of them,
/// in the candidates' order).
std::vector<Vec2> uncoveredCells(const RoadGraph& graph, const Grid<std::uint8_t>& cells,
                                 const Surroundings& around, const std::vector<std::int64_t>& candidates,
                                 double radius, std::size_t limit) {
  std::vector<Vec2> out;
  for (std::int64_t k : candidates) {
    const Vec2 c = patchCentre(cells, static_cast<int>(k % cells.width), static_cast<int>(k / cells.width));
    const bool covered = anyNodeNear(around, c, around.coverQuery, [&](int a) {
      if (graph.nodes[a].type == NodeType::Perimeter) return false;  // perimeter links are no roads
      for (int b : graph.nodes[a].links)
        if (graph.nodes[b].type != NodeType::Perimeter &&
            distanceToSegment(c, graph.nodes[a].p, graph.nodes[b].p) <= radius)
          return true;
      return false;
    });
    if (!covered) {
      out.push_back(c);
      if (out.size() >= limit) break;
    }
  }
  return out;
}

/// True when one of the cells is farther than `radius` from every link.
bool anyUncovered(const RoadGraph& graph, const Grid<std::uint8_t>& cells, const Surroundings& around,
                  const std::vector<std::int64_t>& candidates, double radius) {
  return !uncoveredCells(graph, cells, around, candidates, radius, 1).empty();
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
      if (anyNodeNear(around, a, distance(a, b) + around.longestLink + 1.0, [&](int c) {
            for (int d : graph.nodes[c].links) {
              if (c == m || c == q || d == m || d == q) continue;
              if (segmentsCross(a, b, graph.nodes[c].p, graph.nodes[d].p)) return true;
            }
            return false;
          }))
        return true;
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
  std::vector<int> chain;   ///< followChain(at, next): the arm's nodes and the chain beyond them
  std::vector<Vec2> fitPlacements;
  bool fitted = false;
  Vec2 centre, direction;  ///< direction points away from the intersection
  Vec2 origin;             ///< the intersection's placement
};

Arm buildArm(const RoadGraph& graph, int at, int next, const ThroughRoadOptions& options) {
  Arm arm;
  const Vec2 origin = graph.nodes[at].placed;
  arm.chain = followChain(graph, at, next);
  const std::vector<int>& chain = arm.chain;
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
  arm.origin = origin;
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

/// Two arms that continue each other, with the line fitted to both.
struct ArmPair {
  double cosine;
  std::size_t a, b;
  Vec2 centre, direction;
};

/// Pairs of fitted arms close to opposite, straightest first; each arm in one pair at most, and the
/// pair only when the placements of both arms are consistent with one straight line. `paired` gets
/// one flag per arm.
std::vector<ArmPair> pairArms(const RoadGraph& graph, const std::vector<Arm>& arms,
                              const ThroughRoadOptions& options, bool shortArms, std::vector<char>& paired) {
  const double pairCos = -std::cos(options.pairAngle * M_PI / 180.0);
  std::vector<ArmPair> candidates;
  for (std::size_t a = 0; a < arms.size(); ++a)
    for (std::size_t b = a + 1; b < arms.size(); ++b) {
      if (!arms[a].fitted || !arms[b].fitted) continue;
      const double c = dot(arms[a].direction, arms[b].direction);
      if (c > pairCos) continue;
      candidates.push_back({c, a, b, {}, {}});
    }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const ArmPair& x, const ArmPair& y) { return x.cosine < y.cosine; });
  paired.assign(arms.size(), 0);
  std::vector<ArmPair> pairs;
  std::vector<Vec2> placements;
  for (ArmPair p : candidates) {
    if (paired[p.a] || paired[p.b]) continue;
    placements = arms[p.a].fitPlacements;
    placements.insert(placements.end(), arms[p.b].fitPlacements.begin(), arms[p.b].fitPlacements.end());
    fitLine(placements, p.centre, p.direction);
    if (!consistentWithLine(placements, p.centre, p.direction, options.slack)) continue;
    paired[p.a] = paired[p.b] = 1;
    pairs.push_back(p);
  }
  if (!shortArms) return pairs;
  // An arm too short to fit (a dead end a cell or two long, a road ending at the grid's edge) continues
  // an unpaired fitted arm when it leaves on the other side and all its cells lie in that arm's line's
  // band (the straightness rule).
  for (std::size_t u = 0; u < arms.size(); ++u) {
    if (paired[u] || arms[u].fitted || arms[u].nodes.empty()) continue;
    std::vector<Vec2> own;
    for (int k : arms[u].nodes) own.push_back(graph.nodes[k].placed);
    const Vec2 away = own.back() - arms[u].origin;
    if (length(away) == 0) continue;
    // Its direction, a cell or two long, is that of the grid's axes: only its side counts.
    double bestCos = 0.0;
    std::size_t best = SIZE_MAX;
    for (std::size_t f = 0; f < arms.size(); ++f) {
      if (paired[f] || !arms[f].fitted) continue;
      const double c = dot(arms[f].direction, away / length(away));
      if (c < bestCos && consistentWithLine(own, arms[f].centre, arms[f].direction, options.slack)) {
        bestCos = c;
        best = f;
      }
    }
    if (best == SIZE_MAX) continue;
    paired[u] = paired[best] = 1;
    pairs.push_back({bestCos, best, u, arms[best].centre, arms[best].direction});
  }
  return pairs;
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

/// Whether some straight line holds every placement within its band (digitalLineBand + slack; the
/// placements' strip strictly narrower than the band, so that a line exactly between two rows, on whose
/// band edges both rows lie, does not count) and the ends a and b within endOffset of that band of it: the
/// digital straight line test itself, where the total least-squares fit can leave a placement at a
/// staircase's step just outside the band of the fitted line although a line holding them all exists. Every
/// such line passes within the band of the first and last placements, so its direction is within asin(2 x
/// 0.71 / L) of the chord between them (L its length); the directions are tried a hundredth of a pw apart at
/// that length.
bool onADigitalLine(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b,
                    const ThroughRoadOptions& options) {
  const Vec2 chord = placements.back() - placements.front();
  const double span = length(chord);
  if (span <= 2.0 * (std::sqrt(0.5) + options.slack)) return false;  // no direction to speak of
  const double base = std::atan2(chord.y, chord.x);
  const double range = std::asin(std::min(1.0, 2.0 * (std::sqrt(0.5) + options.slack) / span));
  const double step = 0.01 / span;
  for (double turn = -range; turn <= range; turn += step) {
    const Vec2 d(std::cos(base + turn), std::sin(base + turn));
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const Vec2& p : placements) {
      const double off = cross(d, p - placements.front());
      lo = std::min(lo, off);
      hi = std::max(hi, off);
    }
    if (hi - lo >= 2.0 * (digitalLineBand(d) + options.slack) - kPlacementRounding) continue;
    const double mid = 0.5 * (lo + hi), ends = options.endOffset * digitalLineBand(d) + options.slack;
    if (std::fabs(cross(d, a - placements.front()) - mid) <= ends &&
        std::fabs(cross(d, b - placements.front()) - mid) <= ends)
      return true;
  }
  return false;
}

/// straightChain on the placements of a road between the nodes e0 and e1 (drawn from a to b), or on
/// those farther than innerRadius from the placement of an end that is an intersection: a crossing's
/// cells bulge around its node, as the arms' fits leave them out. `scratch` is working space.
bool straightBetween(const RoadGraph& graph, const std::vector<Vec2>& placements, int e0, int e1,
                     const Vec2& a, const Vec2& b, const ThroughRoadOptions& options,
                     std::vector<Vec2>& scratch, bool anyLine = false) {
  if (straightChain(placements, a, b, options, anyLine)) return true;
  scratch.clear();
  for (const Vec2& p : placements) {
    bool crossing = false;
    for (int e : {e0, e1})
      crossing = crossing || (graph.nodes[e].links.size() >= 3 &&
                              distance(p, graph.nodes[e].placed) <= options.innerRadius + kPlacementRounding);
    if (!crossing) scratch.push_back(p);
  }
  return scratch.size() >= 2 && scratch.size() < placements.size() &&
         straightChain(scratch, a, b, options, anyLine);
}

void placeIntersection(RoadGraph& graph, int at, const ThroughRoadOptions& options,
                       const Surroundings& around, ThroughRoadStats& stats) {
  if (around.footprint) around.footprint->nodes.push_back(at);
  RoadNode& node = graph.nodes[at];
  const std::vector<std::int32_t> links = node.links;
  std::vector<Arm> arms;
  for (int next : links) arms.push_back(buildArm(graph, at, next, options));
  std::vector<char> paired;
  const std::vector<ArmPair> pairs = pairArms(graph, arms, options, false, paired);
  stats.pairs += pairs.size();
  if (pairs.empty()) return;

  // The node: the crossing of the pair lines; with one pair, the point of its line nearest (least
  // squares) to the other arms' lines, so the through road stays straight and the stems meet it.
  Vec2 target = node.p;
  if (pairs.size() >= 2) {
    std::vector<std::pair<Vec2, Vec2>> lines;
    for (const ArmPair& p : pairs) lines.push_back({p.centre, p.direction});
    if (!leastSquaresCrossing(lines, target)) return;
  } else {
    const ArmPair& p = pairs[0];
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
    const std::vector<int>& chain = arm.chain;  // the links have not changed since buildArm
    for (std::size_t count = arm.movable; count >= 1; --count) {
      const int anchor = chain[std::min(count, chain.size() - 1)];
      if (anchor == at) break;
      const Vec2 ab = graph.nodes[anchor].p - target;
      const double len2 = dot(ab, ab);
      if (len2 == 0) break;
      onLine.clear();
      double along = 0.0;
      bool inReach = true;
      const bool pieceOnCells = pieceOnRoadCells(target, graph.nodes[anchor].p, options);
      for (std::size_t m = 0; m < count && inReach; ++m) {
        const RoadNode& n = graph.nodes[arm.nodes[m]];
        along = std::clamp(dot(n.p - target, ab) / len2, along, 1.0);
        onLine.push_back(target + ab * along);
        inReach = approachInReach(n, onLine.back(), pieceOnCells, options);
      }
      if (!inReach) continue;
      if (options.straightApproachesOnly) {
        // Only an approach whose cells are straight is drawn straight (the straight-road rule, from the
        // crossing to the anchor): a road curving into a crossing keeps its curve. The placements of
        // nodes that leave their reach (a skeleton's hook through another road's band, approachInReach)
        // are left out.
        cells.assign(1, node.placed);
        for (std::size_t m = 0; m < count; ++m) {
          const RoadNode& n = graph.nodes[arm.nodes[m]];
          if (distance(onLine[m], n.placed) <= placementReach(n.type, options.reach))
            cells.push_back(n.placed);
        }
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

/// Width of a road in cells by its node type (CONVENTIONS.md: a primary is 2 cells wide, a secondary 1).
double roadWidth(NodeType type) {
  return type == NodeType::Primary ? 2.0 : 1.0;
}

/// Lines meeting at less than asin(0.2) = 11.5 degrees do not cross within a cluster's reach.
constexpr double kShallowestMeet = 0.2;

/// A line of a junction cluster: the fitted line of a pair of arms that continue each other (a
/// through road), or of a single fitted arm (a stem).
struct ClusterLine {
  Vec2 centre, direction;
  bool through = true;
  bool dropped = false;                 ///< a stem that meets no through road near the cluster
  NodeType type = NodeType::Secondary;  ///< a stem's road (how far its line may lie from its cells)
};

/// A junction the cluster's lines imply: where two through roads cross, or a stem meets a through road.
struct ClusterPoint {
  Vec2 p;
  std::vector<std::size_t> lines;
};

/// A node a cluster's rebuild placed that may be nudged toward an uncovered cell: where the rebuild
/// put it, and the lines it must stay on with how far off each it may lie.
struct Nudgeable {
  int node = -1;
  Vec2 rebuilt;
  std::vector<std::pair<std::size_t, double>> lines;  ///< line, tolerance
};

/// Moves the nudgeable nodes toward the uncovered cells (`missing`), each cell in turn by the smallest
/// move of one node that brings one of its links within coverRadius of it, the node staying within
/// `reach` of where the rebuild put it, near a road cell, and within every one of its lines' band.
/// Returns false (positions partly moved; the caller undoes the rebuild) when a cell cannot be covered.
bool nudgeToCover(RoadGraph& graph, const std::vector<Nudgeable>& nodes,
                  const std::vector<ClusterLine>& lines, const std::vector<Vec2>& missing,
                  const ThroughRoadOptions& options) {
  auto linkDistance = [&](int n, const Vec2& p, const Vec2& c) {
    double best = std::numeric_limits<double>::max();
    for (int q : graph.nodes[n].links)
      if (graph.nodes[q].type != NodeType::Perimeter)
        best = std::min(best, distanceToSegment(c, p, graph.nodes[q].p));
    return best;
  };
  auto allowed = [&](const Nudgeable& n, const Vec2& p) {
    if (distance(p, n.rebuilt) > options.reach + kPlacementRounding) return false;
    for (const auto& [l, tolerance] : n.lines)
      if (std::fabs(cross(lines[l].direction, p - lines[l].centre)) > tolerance + kPlacementRounding)
        return false;
    return !options.cells || nearRoadCell(*options.cells, p, options.reach);
  };
  for (const Vec2& c : missing) {
    bool covered = false;
    for (const Nudgeable& n : nodes)
      covered = covered || linkDistance(n.node, graph.nodes[n.node].p, c) <= options.coverRadius;
    if (covered) continue;  // an earlier nudge covered it
    double bestMove = std::numeric_limits<double>::max();
    const Nudgeable* pick = nullptr;
    Vec2 bestAt;
    for (const Nudgeable& n : nodes) {
      const Vec2 from = graph.nodes[n.node].p;
      const double toCell = distance(from, c);
      if (toCell <= 0 || !allowed(n, from)) continue;
      const Vec2 step = (c - from) * (1.0 / toCell);
      auto at = [&](double t) { return from + step * t; };
      // The farthest allowed move toward the cell (the allowed region is convex but for the cells).
      double lo = 0.0, hi = std::min(toCell, 2.0 * options.reach);
      if (!allowed(n, at(hi))) {
        for (int i = 0; i < 30; ++i) {
          const double mid = 0.5 * (lo + hi);
          (allowed(n, at(mid)) ? lo : hi) = mid;
        }
        hi = lo;
      }
      if (!allowed(n, at(hi)) || linkDistance(n.node, at(hi), c) > options.coverRadius) continue;
      // The smallest move that covers it.
      lo = 0.0;
      for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (linkDistance(n.node, at(mid), c) <= options.coverRadius ? hi : lo) = mid;
      }
      if (hi < bestMove) {
        bestMove = hi;
        pick = &n;
        bestAt = at(hi);
      }
    }
    if (!pick) return false;
    graph.nodes[pick->node].p = bestAt;
  }
  return true;
}

/// One cluster of junctions (sorted ids) joined by short chains (ThroughRoadOptions::junctionSpan; the
/// chains' inner nodes sorted in `inner`, their first links from either end sorted in `innerStarts`),
/// replaced by the junctions its arms' fitted lines imply: the crossings of its through roads and
/// where its stems meet them, each within `clusterReach` of a junction of the cluster. Returns true
/// when the cluster was rebuilt.
/// Whether stem s's line goes on from where it meets one through road (a) to where it meets the next
/// (b): every point between them (sampled every quarter cell) lies on its road's cells (within
/// -smooth-reach of a road cell's centre, a primary's 0.71 pw more, as a node may lie), and a road cell
/// that near the stretch lies farther than coverRadius from every other line of the cluster (a cell only
/// the stem explains).
bool stemGoesOn(const Grid<std::uint8_t>& cells, const std::vector<ClusterLine>& lines, std::size_t s,
                const Vec2& a, const Vec2& b, const ThroughRoadOptions& options) {
  const double onCells = placementReach(lines[s].type, options.reach) + kPlacementRounding;
  if (!segmentOnCells(cells, a, b, onCells)) return false;
  bool own = false;
  forEachCellNearSegment(cells, a, b, onCells, [&](int col, int row, double) {
    if (own || !isRoadCode(cells.at(col, row))) return;
    const Vec2 c = patchCentre(cells, col, row);
    bool explained = false;
    for (std::size_t l = 0; l < lines.size() && !explained; ++l)
      explained = l != s && !lines[l].dropped &&
                  std::fabs(cross(lines[l].direction, c - lines[l].centre)) <= options.coverRadius;
    own = !explained;
  });
  return own;
}

/// Per arm: a dead end within the window (the arm's last node ends its chain with one link) whose stem
/// line is fitted and whose every node's placement lies within the band of one of the cluster's through
/// roads (ThroughRoadOptions::spursInBands): a street's staircase beside another road's band, split off
/// by the skeleton. None when an arm that goes on has no line (it would be joined with a bend).
std::vector<char> spursInBands(const RoadGraph& graph, const std::vector<Arm>& arms,
                               const std::vector<ClusterLine>& lines, const std::vector<std::size_t>& lineOf,
                               const ThroughRoadOptions& options) {
  std::vector<char> spur(arms.size(), 0);
  auto deadEnd = [&](const Arm& arm) {
    return !arm.nodes.empty() && graph.nodes[arm.nodes.back()].links.size() == 1;
  };
  for (std::size_t a = 0; a < arms.size(); ++a)
    if (!deadEnd(arms[a]) && lineOf[a] == SIZE_MAX) return spur;
  for (std::size_t a = 0; a < arms.size(); ++a) {
    if (!deadEnd(arms[a]) || lineOf[a] == SIZE_MAX || lines[lineOf[a]].through) continue;
    for (std::size_t l = 0; l < lines.size() && !spur[a]; ++l) {
      if (!lines[l].through) continue;
      const double band = digitalLineBand(lines[l].direction) + options.slack + kPlacementRounding;
      bool inBand = true;
      for (int k : arms[a].nodes)
        inBand =
            inBand && std::fabs(cross(lines[l].direction, graph.nodes[k].placed - lines[l].centre)) <= band;
      spur[a] = inBand ? 1 : 0;
    }
  }
  return spur;
}

bool consolidateCluster(RoadGraph& graph, const std::vector<int>& junctions, const std::vector<int>& inner,
                        const std::vector<std::pair<int, int>>& innerStarts, double clusterReach,
                        const ThroughRoadOptions& options, Surroundings& around, ThroughRoadStats& stats) {
  auto inCluster = [&](int k) {
    return std::binary_search(junctions.begin(), junctions.end(), k) ||
           std::binary_search(inner.begin(), inner.end(), k);
  };
  // The arms: every road leaving a junction of the cluster other than by its inner chains.
  std::vector<Arm> arms;
  std::vector<int> attach, first;  // per arm: its junction, and its first node outside the cluster
  std::vector<int> perimeter;      // perimeter nodes linked to the cluster's junctions
  for (int j : junctions)
    for (int next : graph.nodes[j].links) {
      if (!isRoad(graph.nodes[next])) {
        perimeter.push_back(next);  // a perimeter line: relinked to the nearest junction implied
        continue;
      }
      if (std::binary_search(innerStarts.begin(), innerStarts.end(),
                             std::make_pair(j, static_cast<int>(next))))
        continue;
      // A long road between two of its junctions (or back to one): left as it is, since both ends'
      // arms would claim its nodes.
      if (inCluster(next)) return false;
      Arm arm = buildArm(graph, j, next, options);
      if (inCluster(arm.chain.back())) return false;
      arms.push_back(std::move(arm));
      attach.push_back(j);
      first.push_back(next);
    }
  if (arms.size() < 3) return false;
  std::vector<char> paired;
  const std::vector<ArmPair> pairs = pairArms(graph, arms, options, true, paired);
  if (pairs.empty()) return false;
  std::vector<ClusterLine> lines;
  std::vector<std::size_t> lineOf(arms.size(), SIZE_MAX);
  for (const ArmPair& p : pairs) {
    lineOf[p.a] = lineOf[p.b] = lines.size();
    lines.push_back({p.centre, p.direction, true});
  }
  for (std::size_t a = 0; a < arms.size(); ++a)
    if (!paired[a] && arms[a].fitted) {
      lineOf[a] = lines.size();
      lines.push_back({arms[a].centre, arms[a].direction, false, false, graph.nodes[first[a]].type});
    }
  // A spur whose nodes all lie in a through road's band is that road's cells (spursInBands): no stem.
  const std::vector<char> spur = options.spursInBands ? spursInBands(graph, arms, lines, lineOf, options)
                                                      : std::vector<char>(arms.size(), 0);
  for (std::size_t a = 0; a < arms.size(); ++a)
    if (spur[a]) lines[lineOf[a]].dropped = true;
  // Where the lines meet near the cluster: through roads crossing each other, and each stem where it
  // first meets a through road coming in from its own cells.
  auto nearCluster = [&](const Vec2& p) {
    for (int j : junctions)
      if (distance(p, graph.nodes[j].placed) <= clusterReach) return true;
    return false;
  };
  std::vector<ClusterPoint> points;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t k = i + 1; k < lines.size() && lines[i].through; ++k) {
      if (!lines[k].through) continue;
      Vec2 x;
      if (leastSquaresCrossing({{lines[i].centre, lines[i].direction}, {lines[k].centre, lines[k].direction}},
                               x) &&
          nearCluster(x))
        points.push_back({x, {i, k}});
    }
  std::vector<double> stemEnd(lines.size(), 0.0);  // per stem: how far back along it its last junction lies
  for (std::size_t s = 0; s < lines.size(); ++s) {
    if (lines[s].through) continue;
    // The through roads the stem's line meets, nearest its own cells first (those meeting it at a shallow
    // angle too: beyond the first meet they only extend the stem, and nearCluster bounds how far).
    std::vector<std::pair<double, ClusterPoint>> meets;
    double firstT = std::numeric_limits<double>::max();  // the nearest meet leastSquaresCrossing finds
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (!lines[i].through) continue;
      Vec2 x;
      const bool crossing = leastSquaresCrossing(
          {{lines[s].centre, lines[s].direction}, {lines[i].centre, lines[i].direction}}, x);
      const double sine = cross(lines[s].direction, lines[i].direction);
      if (!crossing) {
        if (std::fabs(sine) < kShallowestMeet) continue;
        x = lines[s].centre +
            lines[s].direction * (cross(lines[i].centre - lines[s].centre, lines[i].direction) / sine);
      }
      const double t = dot(lines[s].centre - x, lines[s].direction);  // from the crossing out along the stem
      if (t <= 0) continue;
      meets.push_back({t, {x, {s, i}}});
      if (crossing) firstT = std::min(firstT, t);
    }
    std::stable_sort(meets.begin(), meets.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    // The stem ends at the first through road it crosses steeply enough for leastSquaresCrossing.
    while (!meets.empty() && meets.front().first < firstT) meets.erase(meets.begin());
    if (meets.empty() || !nearCluster(meets[0].second.p)) {
      lines[s].dropped = true;  // meets no through road here: its arm is attached as one without a line
      continue;
    }
    // A stem goes on through the through road it meets to the next one while its cells do
    // (stemsThrough): the stretch between the two lies on road cells, and a road cell along it no other
    // line of the cluster explains (farther than coverRadius from each). Its other side's cells ran into
    // another road's band, so the cluster showed it as a stem; ended at the first, it would leave those
    // cells uncovered.
    std::size_t last = 0;
    while (options.stemsThrough && options.cells && last + 1 < meets.size() &&
           nearCluster(meets[last + 1].second.p) &&
           stemGoesOn(*options.cells, lines, s, meets[last].second.p, meets[last + 1].second.p, options))
      ++last;
    for (std::size_t k = 0; k <= last; ++k) points.push_back(meets[k].second);
    stemEnd[s] = meets[last].first;
  }
  // Two stems that cross each other on their way to the through roads they meet cross there too.
  for (std::size_t s = 0; s < lines.size() && options.stemsCross; ++s)
    for (std::size_t r = s + 1; r < lines.size(); ++r) {
      if (lines[s].through || lines[r].through || lines[s].dropped || lines[r].dropped) continue;
      Vec2 x;
      if (!leastSquaresCrossing(
              {{lines[s].centre, lines[s].direction}, {lines[r].centre, lines[r].direction}}, x))
        continue;
      const double ts = dot(lines[s].centre - x, lines[s].direction),
                   tr = dot(lines[r].centre - x, lines[r].direction);
      if (ts > 0 && ts < stemEnd[s] && tr > 0 && tr < stemEnd[r] && nearCluster(x))
        points.push_back({x, {s, r}});
    }
  // Two crossings are one junction, at the least-squares crossing of all their lines, when that point
  // lies within every one of those lines' band (the straightness rule): no road bends at it. Where two
  // or more through roads meet, the junction is their crossing (where B7's placement puts it too), and a
  // stem joins it when that crossing lies within the stem's band or within -smooth-reach of its line (as
  // far as a node may move off its cells); a stem farther off keeps its own junction where it meets a
  // through road, instead of bending into a point between its line and the through roads' crossing.
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < points.size() && !merged; ++i)
      for (std::size_t k = i + 1; k < points.size() && !merged; ++k) {
        std::vector<std::size_t> both = points[i].lines;
        both.insert(both.end(), points[k].lines.begin(), points[k].lines.end());
        std::sort(both.begin(), both.end());
        both.erase(std::unique(both.begin(), both.end()), both.end());
        std::vector<std::pair<Vec2, Vec2>> fit, through;
        for (std::size_t l : both) {
          fit.push_back({lines[l].centre, lines[l].direction});
          if (lines[l].through) through.push_back(fit.back());
        }
        const bool atThrough = through.size() >= 2;
        Vec2 x = (points[i].p + points[k].p) * 0.5;
        if (!leastSquaresCrossing(atThrough ? through : fit, x) && atThrough) continue;
        bool onAll = true;
        for (std::size_t l : both) {
          double tolerance = digitalLineBand(lines[l].direction) + options.slack;
          if (atThrough && !lines[l].through) tolerance = std::max(tolerance, options.reach);
          onAll = onAll &&
                  std::fabs(cross(lines[l].direction, x - lines[l].centre)) <= tolerance + kPlacementRounding;
        }
        if (!onAll) continue;
        points[i] = {x, both};
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(k));
        merged = true;
      }
  }
  if (points.empty()) return false;
  // Every through road and stem must meet the others here, and every junction lie on the cells.
  for (std::size_t a = 0; a < arms.size(); ++a)
    if (lineOf[a] != SIZE_MAX && lines[lineOf[a]].dropped) lineOf[a] = SIZE_MAX;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (lines[l].dropped) continue;
    bool on = false;
    for (const ClusterPoint& q : points)
      on = on || std::find(q.lines.begin(), q.lines.end(), l) != q.lines.end();
    if (!on) return false;
  }
  for (const ClusterPoint& q : points) {
    const bool onCells = options.cells ? nearRoadCell(*options.cells, q.p, options.reach) : nearCluster(q.p);
    if (!onCells) return false;
  }
  // The new links: consecutive junctions along each through road, and each arm to the junction of its
  // line at its own side (the nearest junction for an arm without a line).
  std::vector<std::pair<std::size_t, std::size_t>> between;
  std::vector<double> betweenReach;  // per link: how far from road cells it may run (pw)
  std::vector<std::size_t> armPoint(arms.size(), SIZE_MAX);
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::vector<std::pair<double, std::size_t>> along;
    for (std::size_t q = 0; q < points.size(); ++q)
      if (std::find(points[q].lines.begin(), points[q].lines.end(), l) != points[q].lines.end())
        along.push_back({dot(points[q].p - lines[l].centre, lines[l].direction), q});
    std::sort(along.begin(), along.end());
    for (std::size_t k = 1; k < along.size(); ++k) {
      between.push_back({along[k - 1].second, along[k].second});
      // A stem going on through a through road (stemsThrough) lies on its own road's cells, a primary's
      // band 0.71 pw wider, as stemGoesOn tested.
      betweenReach.push_back(lines[l].through ? options.reach : placementReach(lines[l].type, options.reach));
    }
    for (std::size_t a = 0; a < arms.size(); ++a)
      if (lineOf[a] == l)
        armPoint[a] =
            dot(arms[a].direction, lines[l].direction) > 0 ? along.back().second : along.front().second;
  }
  for (std::size_t a = 0; a < arms.size(); ++a) {
    if (armPoint[a] != SIZE_MAX) continue;
    double best = std::numeric_limits<double>::max();
    for (std::size_t q = 0; q < points.size(); ++q)
      if (distance(points[q].p, graph.nodes[first[a]].p) < best) {
        best = distance(points[q].p, graph.nodes[first[a]].p);
        armPoint[a] = q;
      }
  }
  // The first node of each arm left in place: past its window, or its next end.
  std::vector<int> anchors(arms.size(), -1);
  for (std::size_t a = 0; a < arms.size(); ++a)
    if (arms[a].movable > 0) {
      const std::vector<int>& chain = arms[a].chain;  // from attach[a] through first[a]; not rebuilt yet
      if (arms[a].movable < chain.size() && chain[arms[a].movable] != attach[a])
        anchors[a] = chain[arms[a].movable];
    }
  // Rebuild, keeping a copy of every node whose links change to undo it.
  std::vector<int> touched = junctions;
  touched.insert(touched.end(), inner.begin(), inner.end());
  touched.insert(touched.end(), first.begin(), first.end());
  touched.insert(touched.end(), perimeter.begin(), perimeter.end());
  for (const Arm& arm : arms) touched.insert(touched.end(), arm.nodes.begin(), arm.nodes.end());
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<RoadNode> saved;
  for (int k : touched) saved.push_back(graph.nodes[k]);
  const std::vector<std::int64_t> covered =
      options.cells ? cellsNearLinks(graph, *options.cells, touched, options.coverRadius)
                    : std::vector<std::int64_t>();
  for (int k : inner) graph.removeNode(k);
  for (int j : junctions) {
    const std::vector<std::int32_t> links = graph.nodes[j].links;
    for (int l : links) graph.unlink(j, l);
  }
  // Each junction implied takes the id of the nearest junction of the cluster not yet taken; when the
  // lines imply more junctions than the cluster had, the others are new nodes.
  std::vector<int> ids(points.size(), -1);
  std::vector<char> taken(junctions.size(), 0);
  std::vector<int> added;
  for (std::size_t q = 0; q < points.size(); ++q) {
    double best = std::numeric_limits<double>::max();
    std::size_t pick = SIZE_MAX;
    for (std::size_t k = 0; k < junctions.size(); ++k)
      if (!taken[k] && distance(graph.nodes[junctions[k]].p, points[q].p) < best) {
        best = distance(graph.nodes[junctions[k]].p, points[q].p);
        pick = k;
      }
    if (pick != SIZE_MAX) {
      taken[pick] = 1;
      ids[q] = junctions[pick];
    } else {
      ids[q] = graph.addNode(points[q].p, NodeType::Secondary);
      added.push_back(ids[q]);
    }
    RoadNode& node = graph.nodes[ids[q]];
    node.p = node.placed = points[q].p;
    node.intersection = true;
  }
  for (std::size_t k = 0; k < junctions.size(); ++k)
    if (!taken[k]) graph.removeNode(junctions[k]);
  for (const auto& [q, r] : between) graph.link(ids[q], ids[r]);
  // Each arm with a line joins its junction straight: its approach nodes within the window go onto the
  // segment from the junction to the arm's first node beyond them (as B7's approaches, rule 5) while
  // they stay within reach of their cells, and those behind the junction (the cluster's junction moved
  // past them) go.
  std::vector<int> moved = ids;
  std::vector<Vec2> cells;
  auto lineTolerance = [&](std::size_t l) { return digitalLineBand(lines[l].direction) + options.slack; };
  for (std::size_t a = 0; a < arms.size(); ++a) {
    const Arm& arm = arms[a];
    if (spur[a]) {  // the through road's line covers its cells
      for (int k : arm.nodes) graph.removeNode(k);
      continue;
    }
    const int at = ids[armPoint[a]];
    std::size_t k = 0;
    if (lineOf[a] != SIZE_MAX && arm.movable > 0 && arm.nodes[0] == first[a] && anchors[a] >= 0) {
      const Vec2 x = points[armPoint[a]].p;
      const Vec2 ab = graph.nodes[anchors[a]].p - x;
      const double len2 = dot(ab, ab);
      if (len2 > 0) {
        while (k < arm.movable && dot(graph.nodes[arm.nodes[k]].p - x, ab) <= 0) ++k;
        if (k == arm.movable && arm.nodes.size() == arm.movable) k = 0;  // nothing left to link to
        for (std::size_t j = 0; j < k; ++j) graph.removeNode(arm.nodes[j]);
        // Only an approach whose cells are straight is drawn straight (B7's rule 5 with
        // straightApproachesOnly): the cells its line was fitted on and its anchor's (unless the anchor is
        // another junction, whose cells bulge) pass the straight-road rule between the junction and the
        // anchor, so a road curving away beyond the window keeps its curve.
        cells = arm.fitPlacements;
        if (graph.nodes[anchors[a]].links.size() == 2) cells.push_back(graph.nodes[anchors[a]].placed);
        const bool straight =
            !options.straightApproachesOnly || straightChain(cells, x, graph.nodes[anchors[a]].p, options);
        double along = 0.0;
        const bool pieceOnCells = pieceOnRoadCells(x, graph.nodes[anchors[a]].p, options);
        for (std::size_t j = k; j < arm.movable && straight; ++j) {
          RoadNode& node = graph.nodes[arm.nodes[j]];
          along = std::clamp(dot(node.p - x, ab) / len2, along, 1.0);
          const Vec2 onLine = x + ab * along;
          if (!approachInReach(node, onLine, pieceOnCells, options)) break;
          node.p = onLine;
        }
        for (std::size_t j = k; j < arm.nodes.size(); ++j) moved.push_back(arm.nodes[j]);
      }
    }
    graph.link(at, k == 0 ? first[a] : arm.nodes[k]);
  }
  for (int e : perimeter) {
    std::size_t nearest = 0;
    for (std::size_t q = 1; q < points.size(); ++q)
      if (distance(points[q].p, graph.nodes[e].p) < distance(points[nearest].p, graph.nodes[e].p))
        nearest = q;
    graph.link(ids[nearest], e);
  }
  for (std::size_t q = 0; q < points.size(); ++q) {
    bool primary = false;
    for (int l : graph.nodes[ids[q]].links) primary = primary || (graph.nodes[l].type == NodeType::Primary);
    graph.nodes[ids[q]].type = primary ? NodeType::Primary : NodeType::Secondary;
  }
  // The links between the junctions run on road cells, and nothing crosses or is uncovered.
  auto betweenOffCells = [&] {
    for (std::size_t b = 0; b < between.size(); ++b)
      if (!segmentOnCells(*options.cells, graph.nodes[ids[between[b].first]].p,
                          graph.nodes[ids[between[b].second]].p, betweenReach[b] + kPlacementRounding))
        return true;
    return false;
  };
  const bool offCells = options.cells && betweenOffCells();
  // The checks look around where the nodes are now, as far as the longest link (the rebuilt ones
  // included).
  LiveIndex& live = *around.live;
  Surroundings now = around;
  auto followMoves = [&](const std::vector<int>& nodes) {
    for (int k : nodes) {
      live.update(k);
      for (int l : graph.nodes[k].links)
        now.longestLink = std::max(now.longestLink, distance(graph.nodes[k].p, graph.nodes[l].p));
    }
    now.coverQuery = now.longestLink + options.coverRadius;
  };
  followMoves(touched);
  followMoves(added);
  // Every link of the rebuilt nodes leads to a live node (a backstop: an arm's nodes removed by another
  // arm would leave a dangling link).
  bool dangling = false;
  for (const std::vector<int>* nodes : {&touched, &added})
    for (int k : *nodes)
      if (graph.nodes[k].alive)
        for (int l : graph.nodes[k].links) dangling = dangling || !graph.nodes[l].alive;
  bool reject = offCells || dangling;
  if (!reject && movedLinksCross(graph, now, moved)) {
    ++stats.crossingsAvoided;
    reject = true;
  }
  if (!reject && options.cells) {
    // Only the nudge reads which cells are uncovered; otherwise the first one decides.
    const std::vector<Vec2> missing = uncoveredCells(graph, *options.cells, now, covered, options.coverRadius,
                                                     options.nudgeToCover ? SIZE_MAX : 1);
    if (!missing.empty()) {
      reject = true;
      // Retry once with the junctions on one through road nudged toward the uncovered cells (issue 20).
      // Where two through roads cross, the junction stays at their crossing (moved, both roads bend at
      // it), and approach nodes stay on their lines (moved sideways, they draw hooks).
      std::vector<Nudgeable> nudgeable;
      for (std::size_t q = 0; q < points.size(); ++q) {
        std::size_t through = 0;
        for (std::size_t l : points[q].lines) through += lines[l].through ? 1 : 0;
        if (through >= 2) continue;
        Nudgeable n{ids[q], points[q].p, {}};
        for (std::size_t l : points[q].lines) n.lines.push_back({l, lineTolerance(l)});
        nudgeable.push_back(n);
      }
      if (options.nudgeToCover && nudgeToCover(graph, nudgeable, lines, missing, options)) {
        std::vector<int> nudged;
        for (const Nudgeable& n : nudgeable) nudged.push_back(n.node);
        followMoves(nudged);
        if (betweenOffCells())
          ++stats.uncoveringAvoided;
        else if (!rejectMoves(graph, options, now, moved, covered, stats)) {  // counts what it rejects
          reject = false;
          ++stats.clustersNudged;
        }
      } else {
        ++stats.uncoveringAvoided;
      }
    }
  }
  if (reject) {
    for (std::size_t k = 0; k < touched.size(); ++k) graph.nodes[touched[k]] = saved[k];
    for (int k : added) {
      graph.nodes[k].links.clear();
      graph.nodes[k].alive = false;
    }
    for (const std::vector<int>* nodes : {&touched, &added})
      for (int k : *nodes) live.update(k);
    return false;
  }
  around.longestLink = now.longestLink;  // later clusters look as far as the links rebuilt here
  ++stats.clustersConsolidated;
  stats.junctionsRemoved +=
      junctions.size() - std::min(junctions.size(), points.size());  // (net, per cluster)
  return true;
}

/// Finds the clusters of junctions (road nodes of three or more links) joined by short chains
/// (ThroughRoadOptions::junctionSpan) and consolidates each (consolidateCluster), in node order.
void consolidateJunctions(RoadGraph& graph, const ThroughRoadOptions& options, ThroughRoadStats& stats) {
  const std::size_t n = graph.nodes.size();
  LiveIndex live(graph, 4.0);
  Surroundings around;  // its longestLink grows with the links rebuilt clusters make
  around.live = &live;
  around.longestLink = longestLink(graph);
  auto junction = [&](int k) { return isRoad(graph.nodes[k]) && graph.nodes[k].links.size() >= 3; };
  std::vector<int> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<int>(i);
  auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  std::vector<std::pair<int, int>> innerOf;  // (node, a junction of its chain)
  std::vector<std::pair<int, int>> starts;   // the first links of the inner chains, from both ends
  std::vector<char> joined(n, 0);            // junctions with an inner chain
  std::vector<double> extent(n, 0.0);        // the longest inner chain at each junction
  struct ShortChain {
    double length;
    int from, to, next;
    std::vector<int> chain;
  };
  std::vector<ShortChain> candidates;
  for (std::size_t i = 0; i < n; ++i) {
    if (!junction(static_cast<int>(i))) continue;
    for (int next : graph.nodes[i].links) {
      const std::vector<int> chain = followChain(graph, static_cast<int>(i), next, true);
      const int end = chain.back();
      if (!junction(end) || end < static_cast<int>(i)) continue;  // each chain once (loops from i)
      bool road = true;
      double length = 0.0;
      int prev = static_cast<int>(i);
      for (int k : chain) {
        road = road && isRoad(graph.nodes[k]);
        length += distance(graph.nodes[prev].p, graph.nodes[k].p);
        prev = k;
      }
      // Short: no longer than the stretch its road and the widest other road at its ends share when
      // they cross at the through-angle.
      const int last = chain.size() > 1 ? chain[chain.size() - 2] : static_cast<int>(i);
      const double own = roadWidth(graph.nodes[chain.size() > 1 ? chain[0] : static_cast<int>(i)].type);
      double other = 0.0;
      for (int l : graph.nodes[i].links)
        if (l != next && !(end == static_cast<int>(i) && l == last))
          other = std::max(other, roadWidth(graph.nodes[l].type));
      for (int l : graph.nodes[end].links)
        if (l != last && !(end == static_cast<int>(i) && l == next))
          other = std::max(other, roadWidth(graph.nodes[l].type));
      if (!road || length > options.junctionSpan * (own + other)) continue;
      candidates.push_back({length, static_cast<int>(i), end, next, chain});
    }
  }
  // Shortest chains first; two clusters join only while every two of their junctions stay within the
  // longest stretch two roads can share (two primaries), so ordinary junctions one short street apart
  // do not grow into one cluster.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const ShortChain& x, const ShortChain& y) { return x.length < y.length; });
  std::vector<std::vector<int>> group(n);
  const double diameter = options.junctionSpan * 2.0 * roadWidth(NodeType::Primary);
  for (const ShortChain& c : candidates) {
    const int ra = root(c.from), rb = root(c.to);
    if (group[ra].empty()) group[ra].push_back(c.from);
    if (group[rb].empty()) group[rb].push_back(c.to);
    if (ra != rb) {
      bool compact = true;
      for (int a : group[ra])
        for (int b : group[rb])
          compact = compact && distance(graph.nodes[a].placed, graph.nodes[b].placed) <= diameter;
      if (!compact) continue;
      parent[ra] = rb;
      group[rb].insert(group[rb].end(), group[ra].begin(), group[ra].end());
      group[ra].clear();
    }
    const int i = c.from, end = c.to;
    const std::vector<int>& chain = c.chain;
    extent[i] = std::max(extent[i], c.length);
    extent[end] = std::max(extent[end], c.length);
    joined[i] = joined[end] = 1;
    starts.push_back({i, c.next});
    starts.push_back({end, chain.size() > 1 ? chain[chain.size() - 2] : i});
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) innerOf.push_back({chain[k], end});
  }
  // Members of every cluster, by root.
  std::vector<std::vector<int>> members(n), inners(n);
  std::vector<std::vector<std::pair<int, int>>> innerStarts(n);
  for (const auto& s : starts) innerStarts[root(s.first)].push_back(s);
  std::vector<double> reach(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (joined[i]) {
      const int r = root(static_cast<int>(i));
      members[r].push_back(static_cast<int>(i));
      reach[r] = std::max(reach[r], extent[i]);
    }
  for (const auto& [k, j] : innerOf) inners[root(j)].push_back(k);
  for (std::size_t r = 0; r < n; ++r) {
    if (members[r].empty()) continue;
    std::vector<int>& inner = inners[r];
    std::sort(inner.begin(), inner.end());
    inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
    ++stats.clusters;
    std::sort(innerStarts[r].begin(), innerStarts[r].end());
    // The lines meet within the cluster's longest inner chain, or B1's window, of its junctions.
    consolidateCluster(graph, members[r], inner, innerStarts[r], std::max(reach[r], options.window), options,
                       around, stats);
  }
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
    if (!straightBetween(graph, placements, static_cast<int>(i), end, a, b, options, outer,
                         options.digitalStraightRoads))
      continue;
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
  to.clustersNudged += s.clustersNudged;
}

}  // namespace

bool consistentWithSegment(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b, double slack) {
  const Vec2 ab = b - a;
  const double len = length(ab);
  if (len == 0) return false;
  return consistentWithLine(placements, a, ab / len, slack);
}

bool straightChain(const std::vector<Vec2>& placements, const Vec2& a, const Vec2& b,
                   const ThroughRoadOptions& options, bool anyLine) {
  if (consistentWithSegment(placements, a, b, options.slack)) return true;
  if (!(options.endOffset > 0.0) || placements.size() < 2) return false;
  // The placements form a digital straight line of their own fitted line, and the ends the road is
  // drawn between lie near it: within endOffset of the band.
  Vec2 centre, direction;
  fitLine(placements, centre, direction);
  const double ends = options.endOffset * digitalLineBand(direction) + options.slack;
  if (consistentWithLine(placements, centre, direction, options.slack) &&
      std::fabs(cross(direction, a - centre)) <= ends && std::fabs(cross(direction, b - centre)) <= ends)
    return true;
  return anyLine && onADigitalLine(placements, a, b, options);
}

ThroughRoadStats straightenThroughRoads(RoadGraph& graph, const ThroughRoadOptions& options,
                                        const Progress& progress) {
  ThroughRoadStats stats;
  if (!options.enabled) {
    reportProgress(progress, 1.0, "through roads");
    return stats;
  }
  updateIntersectionFlags(graph);
  if (options.junctionSpan > 0) {
    // Junction clusters first: the rest of the stage sees the junctions they leave. The links a rebuild
    // draws across a cluster are cut into pieces no longer than the graph's longest link before, so the
    // rest of the stage looks no farther around a node than without clusters.
    const double longest = longestLink(graph);
    consolidateJunctions(graph, options, stats);
    if (longest > 0) subdivideLongLinks(graph, std::nextafter(longest, std::numeric_limits<double>::max()));
    graph.compact();
    updateIntersectionFlags(graph);
    graph.sortLinksClockwise();
  }
  const std::size_t n = graph.nodes.size();
  // Intersections are placed one after another in node order, then the straight roads drawn, each move
  // checked against the positions the earlier ones left: on several threads, speculatively with the same
  // result (SpeculativeMoves).
  SpeculativeMoves moves(graph, workerCount(options.threads), 4.0);
  double linkReach = longestLink(graph);
  // Moves only shorten or keep links near the window's size; a link within coverRadius of a cell has
  // an end within coverRadius + its length of it.
  const double coverQuery = linkReach + 2.0 * options.window + options.coverRadius;
  // Nodes move by a few pw at most; the neighbourhood queries look that much farther.
  linkReach += 2.0 * (options.reach + options.window);
  auto surroundings = [&](const NodeIndex& index, ReadFootprint* footprint) {
    return Surroundings{&index, linkReach, coverQuery, footprint};
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
