// Stage B1 (spec §3 B1) with the [INFERENCE] resolutions of Q9: arms follow degree-2 chains, "within
// 5 pw" is Euclidean distance to the intersection, the intersection node joins the fit, the fit is
// orthogonal (TLS, so north-south roads work), pairs go in ascending residual order and every arm is
// snapped at most once.
#include "urbanvec/vectorize/roads/straightening.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec::vectorize {

double fitLine(const std::vector<Vec2>& points, Vec2& centre, Vec2& direction) {
  centre = Vec2();
  for (const Vec2& p : points) centre += p;
  centre = centre / static_cast<double>(points.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const Vec2& p : points) {
    const Vec2 d = p - centre;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  // Principal axis of the 2x2 scatter matrix, closed form.
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  direction = Vec2(std::cos(angle), std::sin(angle));
  double sum = 0;
  for (const Vec2& p : points) {
    const double perp = cross(direction, p - centre);
    sum += perp * perp;
  }
  return std::sqrt(sum);
}

namespace {

Vec2 project(const Vec2& p, const Vec2& centre, const Vec2& direction) {
  return centre + direction * dot(p - centre, direction);
}

bool isRoadNode(const RoadNode& n) {
  return n.alive && n.type != NodeType::Perimeter;
}

}  // namespace

StraighteningStats straightenIntersections(RoadGraph& graph, const StraighteningOptions& options,
                                           const Progress& progress) {
  StraighteningStats stats;
  updateIntersectionFlags(graph);
  struct Pair {
    double residual;
    int a, b;
    Vec2 centre, direction;
  };
  std::vector<std::vector<int>> arms;
  std::vector<Pair> pairs;
  std::vector<Vec2> pts;
  ProgressTicker ticker(progress, "intersection straightening", graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i, ticker.tick()) {
    if (!isRoadNode(graph.nodes[i]) || !graph.nodes[i].intersection) continue;
    ++stats.intersections;
    const Vec2 centre = graph.nodes[i].p;
    arms.clear();
    for (int next : graph.nodes[i].links) {
      std::vector<int> arm;
      for (int k : followChain(graph, static_cast<int>(i), next)) {
        const RoadNode& n = graph.nodes[k];
        if (k == static_cast<int>(i) || n.intersection || n.type == NodeType::Perimeter ||
            distance(n.p, centre) > options.window)
          break;
        arm.push_back(k);
      }
      arms.push_back(std::move(arm));
    }
    pairs.clear();
    for (size_t a = 0; a < arms.size(); ++a)
      for (size_t b = a + 1; b < arms.size(); ++b) {
        if (arms[a].empty() || arms[b].empty()) continue;
        pts.assign(1, centre);
        for (int k : arms[a]) pts.push_back(graph.nodes[k].p);
        for (int k : arms[b]) pts.push_back(graph.nodes[k].p);
        Pair p{0, static_cast<int>(a), static_cast<int>(b), {}, {}};
        p.residual = fitLine(pts, p.centre, p.direction);
        pairs.push_back(p);
      }
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const Pair& x, const Pair& y) { return x.residual < y.residual; });
    std::vector<char> snapped(arms.size(), 0);
    std::vector<const Pair*> used;
    for (const Pair& p : pairs) {
      if (p.residual > options.maxResidual) break;
      if (snapped[p.a] || snapped[p.b]) continue;
      for (int side : {p.a, p.b})
        for (int k : arms[side]) graph.nodes[k].p = project(graph.nodes[k].p, p.centre, p.direction);
      if (used.empty()) graph.nodes[i].p = project(graph.nodes[i].p, p.centre, p.direction);
      snapped[p.a] = snapped[p.b] = 1;
      used.push_back(&p);
      ++stats.pairsSnapped;
    }
    if (used.size() >= 2 && options.crossingSnapDistance > 0) {
      const Pair& p = *used[0];
      const Pair& q = *used[1];
      const double denom = cross(p.direction, q.direction);
      if (std::fabs(denom) > 0.2) {  // lines cross at more than ~11.5 degrees
        const double t = cross(q.centre - p.centre, q.direction) / denom;
        const Vec2 crossing = p.centre + p.direction * t;
        if (distance(crossing, graph.nodes[i].p) <= options.crossingSnapDistance) graph.nodes[i].p = crossing;
      }
    }
  }
  ticker.finish();
  graph.sortLinksClockwise();
  return stats;
}

std::size_t straightenNearStraightPairs(RoadGraph& graph, double minAngleDegrees) {
  // An angle above the threshold has a cosine below the threshold's cosine.
  const double thresholdCos = std::cos(minAngleDegrees * M_PI / 180.0);
  std::size_t moved = 0;
  for (RoadNode& n : graph.nodes) {
    if (!isRoadNode(n) || !n.intersection) continue;
    double bestCos = thresholdCos;
    int bestA = -1, bestB = -1;
    for (size_t a = 0; a < n.links.size(); ++a)
      for (size_t b = a + 1; b < n.links.size(); ++b) {
        const RoadNode& na = graph.nodes[n.links[a]];
        const RoadNode& nb = graph.nodes[n.links[b]];
        if (na.type == NodeType::Perimeter || nb.type == NodeType::Perimeter) continue;
        const Vec2 ua = na.p - n.p, ub = nb.p - n.p;
        const double la = length(ua), lb = length(ub);
        if (la == 0 || lb == 0) continue;
        const double c = dot(ua, ub) / (la * lb);
        if (c < bestCos) {
          bestCos = c;
          bestA = n.links[a];
          bestB = n.links[b];
        }
      }
    if (bestA < 0) continue;
    const Vec2 a = graph.nodes[bestA].p, b = graph.nodes[bestB].p;
    const Vec2 ab = b - a;
    const double t = std::clamp(dot(n.p - a, ab) / dot(ab, ab), 0.0, 1.0);
    n.p = a + ab * t;
    ++moved;
  }
  return moved;
}

}  // namespace urbanvec::vectorize
