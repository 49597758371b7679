// Spec §3 D6 (thesis §3.4.2, paper §3.3.2) and its [INFERENCE] resolutions (Q15): which blocks get a
// spine, and steps 3-8 on the raw medial graph.
#include "urbanvec/vectorize/parcels/spines.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "urbanvec/vectorize/parcels/spine_skeleton.hpp"
#include "urbanvec/vectorize/parcels/spine_zhang_suen.hpp"

namespace urbanvec::vectorize::parcels {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Mutable adjacency form of a spine graph; removed vertices keep their slot until compaction.
struct Work {
  std::vector<Vec2> p;
  std::vector<std::set<int>> adj;
  std::vector<char> alive;

  explicit Work(const SpineGraph& g) : p(g.nodes), adj(g.nodes.size()), alive(g.nodes.size(), 1) {
    for (const auto& e : g.edges)
      if (e[0] != e[1]) {
        adj[e[0]].insert(e[1]);
        adj[e[1]].insert(e[0]);
      }
  }
  int degree(int v) const { return static_cast<int>(adj[v].size()); }
  void removeVertex(int v) {
    for (int n : adj[v]) adj[n].erase(v);
    adj[v].clear();
    alive[v] = 0;
  }
  int addVertex(const Vec2& q) {
    p.push_back(q);
    adj.emplace_back();
    alive.push_back(1);
    return static_cast<int>(p.size()) - 1;
  }
  void link(int a, int b) {
    adj[a].insert(b);
    adj[b].insert(a);
  }
  void unlink(int a, int b) {
    adj[a].erase(b);
    adj[b].erase(a);
  }

  /// Paths between vertices of degree != 2, each once, in a fixed order.
  std::vector<std::vector<int>> branches() const {
    std::vector<std::vector<int>> out;
    std::set<std::pair<int, int>> usedEdges;
    for (size_t s = 0; s < p.size(); ++s) {
      if (!alive[s] || degree(static_cast<int>(s)) == 2 || degree(static_cast<int>(s)) == 0) continue;
      for (int first : adj[s]) {
        if (usedEdges.count({static_cast<int>(s), first})) continue;
        std::vector<int> path{static_cast<int>(s), first};
        int prev = static_cast<int>(s), cur = first;
        while (degree(cur) == 2) {
          const int next = *adj[cur].begin() == prev ? *adj[cur].rbegin() : *adj[cur].begin();
          prev = cur;
          cur = next;
          path.push_back(cur);
        }
        for (size_t k = 0; k + 1 < path.size(); ++k) {
          usedEdges.insert({path[k], path[k + 1]});
          usedEdges.insert({path[k + 1], path[k]});
        }
        out.push_back(std::move(path));
      }
    }
    return out;
  }

  /// Farthest vertex (path length) from `from` and the predecessor tree.
  int farthest(int from, std::vector<int>& pred) const {
    std::vector<double> dist(p.size(), -1.0);
    pred.assign(p.size(), -1);
    std::vector<int> stack{from};
    dist[from] = 0.0;
    int best = from;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      if (dist[v] > dist[best]) best = v;
      for (int n : adj[v])
        if (dist[n] < 0.0) {
          dist[n] = dist[v] + distance(p[v], p[n]);
          pred[n] = v;
          stack.push_back(n);
        }
    }
    return best;
  }

  /// Vertices of the longest path of the tree (the primary spine).
  std::vector<char> primaryPath() const {
    std::vector<char> on(p.size(), 0);
    int start = -1;
    for (size_t v = 0; v < p.size() && start < 0; ++v)
      if (alive[v]) start = static_cast<int>(v);
    if (start < 0) return on;
    std::vector<int> pred;
    const int a = farthest(start, pred);
    const int b = farthest(a, pred);
    for (int v = b; v >= 0; v = pred[v]) on[v] = 1;
    return on;
  }

  SpineGraph compact() const {
    SpineGraph g;
    std::vector<int> index(p.size(), -1);
    for (size_t v = 0; v < p.size(); ++v)
      if (alive[v] && !adj[v].empty()) {
        index[v] = static_cast<int>(g.nodes.size());
        g.nodes.push_back(p[v]);
      }
    for (size_t v = 0; v < p.size(); ++v)
      if (index[v] >= 0)
        for (int n : adj[v])
          if (static_cast<int>(v) < n) g.edges.push_back({index[v], index[n]});
    return g;
  }
};

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

/// Kruskal with the shortest edges first: 4-connected pixel edges win over diagonals (spec Q15), then
/// only the component with the largest total length is kept.
SpineGraph spanningTree(const SpineGraph& raw) {
  std::vector<size_t> order(raw.edges.size());
  std::iota(order.begin(), order.end(), 0);
  auto len = [&](size_t e) { return distance(raw.nodes[raw.edges[e][0]], raw.nodes[raw.edges[e][1]]); };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return len(a) < len(b); });
  std::vector<int> parent(raw.nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  SpineGraph tree;
  tree.nodes = raw.nodes;
  for (size_t e : order) {
    const int a = findRoot(parent, raw.edges[e][0]), b = findRoot(parent, raw.edges[e][1]);
    if (a == b) continue;
    parent[a] = b;
    tree.edges.push_back(raw.edges[e]);
  }
  std::vector<double> componentLength(raw.nodes.size(), 0.0);
  for (const auto& e : tree.edges)
    componentLength[findRoot(parent, e[0])] += distance(tree.nodes[e[0]], tree.nodes[e[1]]);
  if (tree.edges.empty()) return {};
  const int best = static_cast<int>(std::max_element(componentLength.begin(), componentLength.end()) -
                                    componentLength.begin());
  SpineGraph kept;
  kept.nodes = tree.nodes;
  for (const auto& e : tree.edges)
    if (findRoot(parent, e[0]) == best) kept.edges.push_back(e);
  return kept;
}

void smooth(Work& w, int passes) {
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Vec2> next = w.p;
    for (size_t v = 0; v < w.p.size(); ++v) {
      if (!w.alive[v] || w.degree(static_cast<int>(v)) != 2) continue;  // ends and junctions stay
      Vec2 sum = w.p[v];
      for (int n : w.adj[v]) sum += w.p[n];
      next[v] = sum / 3.0;
    }
    w.p.swap(next);
  }
}

void prune(Work& w, int minEdges) {
  const std::vector<char> primary = w.primaryPath();
  bool changed = true;
  while (changed) {
    changed = false;
    for (const auto& path : w.branches()) {
      const int a = path.front(), b = path.back();
      const bool aLeaf = w.degree(a) == 1, bLeaf = w.degree(b) == 1;
      if (aLeaf == bLeaf) continue;  // not a side branch (isolated path or junction-junction)
      const int leaf = aLeaf ? a : b;
      if (primary[leaf] || static_cast<int>(path.size()) - 1 >= minEdges) continue;
      for (int v : path)
        if (w.degree(v) <= 2 && v != (aLeaf ? b : a)) w.removeVertex(v);
      changed = true;
      break;
    }
  }
}

void trim(Work& w, const Polygon& block, double within) {
  std::vector<int> queue;
  for (size_t v = 0; v < w.p.size(); ++v)
    if (w.alive[v] && w.degree(static_cast<int>(v)) <= 1) queue.push_back(static_cast<int>(v));
  while (!queue.empty()) {
    const int v = queue.back();
    queue.pop_back();
    if (!w.alive[v] || w.degree(v) > 1) continue;
    if (distanceToBoundary(block, w.p[v]) >= within) continue;
    const std::set<int> neighbours = w.adj[v];
    w.removeVertex(v);
    for (int n : neighbours)
      if (w.degree(n) <= 1) queue.push_back(n);
  }
  for (size_t v = 0; v < w.p.size(); ++v)
    if (w.alive[v] && w.degree(static_cast<int>(v)) == 0) w.alive[v] = 0;
}

double turning(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - b;
  return std::atan2(cross(u, v), dot(u, v)) * 180.0 / kPi;
}

void simplify(Work& w, double threshold, bool signedSum) {
  for (const auto& path : w.branches()) {
    if (path.size() <= 2) continue;
    std::vector<int> kept{path.front()};
    double sum = 0.0;
    for (size_t k = 1; k + 1 < path.size(); ++k) {
      const double t = turning(w.p[path[k - 1]], w.p[path[k]], w.p[path[k + 1]]);
      sum += signedSum ? t : std::fabs(t);
      if (std::fabs(sum) > threshold) {
        kept.push_back(path[k]);
        sum = 0.0;
      }
    }
    kept.push_back(path.back());
    for (size_t k = 0; k + 1 < path.size(); ++k) w.unlink(path[k], path[k + 1]);
    std::set<int> keep(kept.begin(), kept.end());
    for (size_t k = 1; k + 1 < path.size(); ++k)
      if (!keep.count(path[k])) w.alive[path[k]] = 0;
    for (size_t k = 0; k + 1 < kept.size(); ++k) w.link(kept[k], kept[k + 1]);
  }
}

void separateJunctions(Work& w) {
  std::vector<std::pair<int, int>> pairs;
  for (size_t v = 0; v < w.p.size(); ++v)
    if (w.alive[v] && w.degree(static_cast<int>(v)) > 2)
      for (int n : w.adj[v])
        if (static_cast<int>(v) < n && w.degree(n) > 2) pairs.emplace_back(static_cast<int>(v), n);
  for (const auto& [a, b] : pairs) {
    const int mid = w.addVertex((w.p[a] + w.p[b]) * 0.5);
    w.unlink(a, b);
    w.link(a, mid);
    w.link(mid, b);
  }
}

}  // namespace

double distanceToBoundary(const Polygon& polygon, const Vec2& p) {
  double best = 1e300;
  auto ring = [&](const Ring& r) {
    for (size_t i = 0; i + 1 < r.size(); ++i) best = std::min(best, distanceToSegment(p, r[i], r[i + 1]));
  };
  ring(polygon.outer);
  for (const Ring& h : polygon.holes) ring(h);
  return best;
}

std::string_view spineMethodName(SpineMethod method) {
  return method == SpineMethod::Skeleton ? "skeleton" : "zhang-suen";
}

std::optional<SpineMethod> parseSpineMethod(std::string_view name) {
  if (name == "skeleton") return SpineMethod::Skeleton;
  if (name == "zhang-suen") return SpineMethod::ZhangSuen;
  return std::nullopt;
}

bool needsSpine(const ParcelBlock& block, const SpineOptions& options) {
  if (block.external) return false;
  if (block.hasCulDeSac) return true;
  const double aspect = block.obbAspect >= 0.0 ? block.obbAspect : orientedBox(block.polygon).aspect();
  return aspect < options.oblongAspect;
}

Polygon skeletonInput(const Polygon& block, const SpineOptions& options, const geos::Context& geos) {
  if (options.skeletonSimplifyTolerance <= 0.0) return block;
  geos::GeomPtr g = geos.polygon(block);
  geos::GeomPtr s = geos.own(
      GEOSTopologyPreserveSimplify_r(geos.handle(), g.get(), options.skeletonSimplifyTolerance), "simplify");
  MultiPolygon parts = geos.toPolygons(s.get());
  return parts.size() == 1 ? parts.front() : block;
}

SpineGraph rawSpineGraph(const Polygon& block, const SpineOptions& options, const geos::Context& geos) {
  if (options.method == SpineMethod::Skeleton) {
    SpineGraph graph = straightSkeletonGraph(skeletonInput(block, options, geos));
    if (!graph.edges.empty()) return graph;
    // No inner bisector: either a near-square block (no spine is right) or a CGAL failure; the
    // pixel method decides both consistently.
  }
  return zhangSuenSpineGraph(block, options.pixelsPerCell);
}

SpineGraph cleanSpine(const SpineGraph& raw, const Polygon& block, const SpineOptions& options) {
  const SpineGraph tree = spanningTree(raw);
  if (tree.edges.empty()) return {};
  Work w(tree);
  for (size_t v = 0; v < w.p.size(); ++v)
    if (w.adj[v].empty()) w.alive[v] = 0;
  smooth(w, options.smoothingPasses);
  prune(w, options.minBranchEdges);
  trim(w, block, options.trimDistance);
  simplify(w, options.turningThreshold, options.signedTurning);
  separateJunctions(w);
  return w.compact();
}

SpineGraph buildSpine(const Polygon& block, const SpineOptions& options, const geos::Context& geos) {
  return cleanSpine(rawSpineGraph(block, options, geos), block, options);
}

std::vector<int> spineDegrees(const SpineGraph& spine) {
  std::vector<int> degree(spine.nodes.size(), 0);
  for (const auto& e : spine.edges) {
    ++degree[e[0]];
    ++degree[e[1]];
  }
  return degree;
}

MultiLineString spineBranches(const SpineGraph& spine) {
  Work w(spine);
  MultiLineString out;
  for (const auto& path : w.branches()) {
    LineString line;
    for (int v : path) line.push_back(w.p[v]);
    out.push_back(std::move(line));
  }
  return out;
}

std::vector<Vec2> spineEnds(const SpineGraph& spine) {
  std::vector<Vec2> ends;
  const std::vector<int> degree = spineDegrees(spine);
  for (size_t v = 0; v < spine.nodes.size(); ++v)
    if (degree[v] == 1) ends.push_back(spine.nodes[v]);
  return ends;
}

}  // namespace urbanvec::vectorize::parcels
