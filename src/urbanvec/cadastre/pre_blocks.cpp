// Pre-block graphs (spec pueyo-urban-data.md §A.6.1). See pre_blocks.hpp.
#include "urbanvec/cadastre/pre_blocks.hpp"

#include <algorithm>
#include <limits>
#include <unordered_map>

#include "urbanvec/core/union_find.hpp"

namespace urbanvec::cadastre {
namespace {

void edgeBox(const LineString& l, double& x0, double& y0, double& x1, double& y1) {
  x0 = y0 = std::numeric_limits<double>::infinity();
  x1 = y1 = -x0;
  for (const Vec2& p : l)
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
}

/// Parameter t >= 0 where the ray o + t d (|d| = 1) meets segment a-b, or infinity.
double rayHit(const Vec2& o, const Vec2& d, const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  const double den = cross(d, e);
  if (std::abs(den) < 1e-12) return std::numeric_limits<double>::infinity();
  const Vec2 w = a - o;
  const double t = cross(w, e) / den;
  const double u = cross(w, d) / den;
  if (t < 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (rayHit(a, (b - a) / std::max(length(b - a), 1e-300), c, d) <= length(b - a)) return 0.0;
  return std::min(std::min(distanceToSegment(a, c, d), distanceToSegment(b, c, d)),
                  std::min(distanceToSegment(c, a, b), distanceToSegment(d, a, b)));
}

/// A planar graph of straight segments, noded by a grid sweep (cells of about the median segment
/// length; each pair of segments sharing a cell is tested once per cell, O(n) for drawings of short
/// segments): segments are split where they cross or where an end touches another's inside; nodes by
/// exact coordinate, repeated pieces once. Nodes are numbered by (x, y) and edges by their end nodes,
/// so the result does not depend on the input order.
PlanarGraph nodedGraph(const std::vector<LineString>& lines) {
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (const LineString& l : lines)
    for (size_t i = 1; i < l.size(); ++i)
      if (l[i] != l[i - 1]) segs.emplace_back(l[i - 1], l[i]);
  PlanarGraph graph;
  if (segs.empty()) return graph;
  std::vector<double> lengths;
  for (const auto& [a, b] : segs) lengths.push_back(distance(a, b));
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                   lengths.end());
  CellGrid grid(std::max(lengths[lengths.size() / 2], 1e-6) * 2.0);
  for (size_t i = 0; i < segs.size(); ++i) {
    const auto& [a, b] = segs[i];
    grid.insertBox(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y),
                   static_cast<int>(i));
  }
  std::vector<std::vector<std::pair<double, Vec2>>> cuts(segs.size());
  const double eps = 1e-9;
  auto onInside = [&](const Vec2& p, const Vec2& a, const Vec2& b, double& t) {
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    t = dot(p - a, ab) / len2;
    if (t <= eps || t >= 1.0 - eps) return false;
    return distance(p, a + ab * t) <= eps * std::max(1.0, std::sqrt(len2));
  };
  grid.forEachCell([&](const std::vector<int>& ids) {
    for (size_t x = 0; x < ids.size(); ++x)
      for (size_t y = x + 1; y < ids.size(); ++y) {
        const int i = std::min(ids[x], ids[y]), j = std::max(ids[x], ids[y]);
        if (i == j) continue;
        const auto& [a, b] = segs[static_cast<size_t>(i)];
        const auto& [c, d] = segs[static_cast<size_t>(j)];
        if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
            std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
          continue;
        double t;
        // Ends touching the other's inside (T-vertices, collinear overlaps).
        if (onInside(c, a, b, t)) cuts[static_cast<size_t>(i)].emplace_back(t, c);
        if (onInside(d, a, b, t)) cuts[static_cast<size_t>(i)].emplace_back(t, d);
        if (onInside(a, c, d, t)) cuts[static_cast<size_t>(j)].emplace_back(t, a);
        if (onInside(b, c, d, t)) cuts[static_cast<size_t>(j)].emplace_back(t, b);
        // A proper crossing.
        const Vec2 r = b - a, q = d - c;
        const double den = cross(r, q);
        if (std::abs(den) <= 1e-15 * dot(r, r) * dot(q, q)) continue;
        const double tu = cross(c - a, q) / den, uu = cross(c - a, r) / den;
        if (tu <= eps || tu >= 1.0 - eps || uu <= eps || uu >= 1.0 - eps) continue;
        const Vec2 pnt = a + r * tu;
        cuts[static_cast<size_t>(i)].emplace_back(tu, pnt);
        cuts[static_cast<size_t>(j)].emplace_back(uu, pnt);
      }
  });
  std::vector<std::pair<Vec2, Vec2>> pieces;
  pieces.reserve(segs.size());
  for (size_t i = 0; i < segs.size(); ++i) {
    auto& cs = cuts[i];
    std::sort(cs.begin(), cs.end(), [](const auto& u, const auto& v) {
      return u.first != v.first
                 ? u.first < v.first
                 : (u.second.x != v.second.x ? u.second.x < v.second.x : u.second.y < v.second.y);
    });
    Vec2 prev = segs[i].first;
    for (const auto& [t, p] : cs) {
      if (p != prev) pieces.emplace_back(prev, p);
      prev = p;
    }
    if (segs[i].second != prev) pieces.emplace_back(prev, segs[i].second);
  }
  auto less = [](const Vec2& a, const Vec2& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::vector<Vec2> points;
  points.reserve(pieces.size() * 2);
  for (const auto& [a, b] : pieces) points.push_back(a), points.push_back(b);
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  for (const Vec2& p : points) graph.addNode(p);
  auto id = [&](const Vec2& p) {
    return static_cast<int>(std::lower_bound(points.begin(), points.end(), p, less) - points.begin());
  };
  std::vector<std::pair<int, int>> edges;
  edges.reserve(pieces.size());
  for (const auto& [a, b] : pieces) {
    const int i = id(a), j = id(b);
    if (i != j) edges.emplace_back(std::min(i, j), std::max(i, j));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [i, j] : edges) graph.addEdge(i, j);
  graph.sortRotations();
  return graph;
}

}  // namespace

PlanarGraph straightenChains(const PlanarGraph& g, double tolerance, GraphStats& stats) {
  std::vector<LineString> lines;
  for (const std::vector<int>& chain : g.chains()) {
    const std::vector<int> nodes = g.chainNodes(chain);
    std::vector<Vec2> pts;
    for (int n : nodes) pts.push_back(g.node(n).p);
    // Douglas-Peucker over the chain's nodes; a closed chain keeps its start and farthest node.
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    const bool closed = nodes.front() == nodes.back();
    std::vector<std::pair<size_t, size_t>> stack;
    if (closed) {
      size_t far = 0;
      for (size_t i = 1; i + 1 < pts.size(); ++i)
        if (distance(pts[i], pts[0]) > distance(pts[far], pts[0])) far = i;
      if (far == 0) {
        lines.push_back(pts);
        continue;
      }
      keep[far] = 1;
      stack = {{0, far}, {far, pts.size() - 1}};
    } else {
      stack = {{0, pts.size() - 1}};
    }
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      double worst = -1.0;
      size_t at = a;
      for (size_t i = a + 1; i < b; ++i) {
        const double d = distanceToSegment(pts[i], pts[a], pts[b]);
        if (d > worst) worst = d, at = i;
      }
      if (worst > tolerance) {
        keep[at] = 1;
        stack.push_back({a, at});
        stack.push_back({at, b});
      }
    }
    LineString kept;
    for (size_t i = 0; i < pts.size(); ++i) {
      if (keep[i])
        kept.push_back(pts[i]);
      else
        ++stats.verticesStraightened;
    }
    lines.push_back(std::move(kept));
  }
  // Straightened chains may now cross their neighbours: node them again.
  return nodedGraph(lines);
}

PlanarGraph structuredGraph(const Linework& lw, std::uint8_t layerMask, double gap, GraphStats& stats,
                            const Progress& progress, double simplifyTolerance) {
  std::vector<LineString> lines;
  for (const Segment& s : lw.segments)
    if (s.layers & layerMask)
      lines.push_back({lw.vertices[static_cast<size_t>(s.a)], lw.vertices[static_cast<size_t>(s.b)]});
  reportProgress(progress, 0.0, "noding");
  const PlanarGraph noded = nodedGraph(lines);
  reportProgress(progress, 0.4, "joining dangling ends");

  // Dangling ends: continue along their direction onto a segment, or join the nearest vertex.
  CellGrid edgeGrid(std::max(gap, 2.0));
  for (size_t e = 0; e < noded.edgeCount(); ++e) {
    double x0, y0, x1, y1;
    edgeBox(noded.edge(static_cast<int>(e)).line, x0, y0, x1, y1);
    edgeGrid.insertBox(x0, y0, x1, y1, static_cast<int>(e));
  }
  CellGrid nodeGrid(std::max(gap, 1e-9));
  for (size_t n = 0; n < noded.nodeCount(); ++n)
    nodeGrid.insert(noded.node(static_cast<int>(n)).p, static_cast<int>(n));
  // Dangling ends (degree 1): their position and direction (pointing out of the line).
  struct End {
    int node;
    int edge;
    Vec2 p;
    Vec2 d;
    int hook = -1;  ///< the folded-back edge beyond the end, if any (ignored when joining it)
  };
  std::vector<End> ends;
  std::vector<int> endOf(noded.nodeCount(), -1);
  // Short spurs (a free end within the gap) at each node.
  std::vector<int> shortSpurs(noded.nodeCount(), 0);
  for (size_t ni = 0; ni < noded.nodeCount(); ++ni) {
    const int n = static_cast<int>(ni);
    if (noded.degree(n) != 1) continue;
    const int e = noded.node(n).edges[0];
    if (noded.edgeLength(e) <= gap) ++shortSpurs[static_cast<size_t>(noded.otherEnd(e, n))];
  }
  // Whether the lines at a junction, its short spurs aside, cross there: two of them leave it in
  // directions apart by more than kCrossingAngle. A spur from a junction where only one doubled line
  // arrives (two copies of one line meeting) is that line going on, not an overshoot.
  auto crossedAt = [&](int m) {
    constexpr double kCrossingAngle = 0.35;  // radians, about 20 degrees
    std::vector<Vec2> dirs;
    for (int f : noded.node(m).edges) {
      const int o = noded.otherEnd(f, m);
      if (noded.degree(o) == 1 && noded.edgeLength(f) <= gap) continue;
      const LineString& l = noded.edge(f).line;
      const Vec2 q = noded.edge(f).a == m ? l[1] : l[l.size() - 2];
      const double len = distance(q, noded.node(m).p);
      if (len > 0) dirs.push_back((q - noded.node(m).p) / len);
    }
    for (size_t i = 0; i < dirs.size(); ++i)
      for (size_t j = i + 1; j < dirs.size(); ++j)
        if (std::acos(std::clamp(dot(dirs[i], dirs[j]), -1.0, 1.0)) > kCrossingAngle) return true;
    return false;
  };
  for (size_t ni = 0; ni < noded.nodeCount(); ++ni) {
    const int n = static_cast<int>(ni);
    if (noded.degree(n) != 1) continue;
    const int e = noded.node(n).edges[0];
    const int m = noded.otherEnd(e, n);
    const LineString& line = noded.edge(e).line;
    const Vec2 p = noded.node(n).p;
    const Vec2 prev = noded.edge(e).a == n ? line[1] : line[line.size() - 2];
    if (noded.degree(m) >= 3 && noded.edgeLength(e) <= gap &&
        noded.degree(m) - shortSpurs[static_cast<size_t>(m)] >= 2 && crossedAt(m)) {
      // A short spur from a junction is an end that ran past it (an overshoot): fringe removal cuts it.
      // Not when cutting every short spur there would leave the junction an end itself: then the
      // spurs are a fork of jittered copies, one of them the line going on, and are joined below.
      ++stats.overshootsCut;
      continue;
    }
    if (noded.degree(m) == 2 && noded.edgeLength(e) <= gap) {
      // A short last edge folding back on its line (a hook: a copy's end merged with the wrong
      // vertex) hides where the line was going: the line ends at the fold, in its own direction.
      const int e2 = noded.node(m).edges[0] == e ? noded.node(m).edges[1] : noded.node(m).edges[0];
      const LineString& l2 = noded.edge(e2).line;
      const Vec2 mp = noded.node(m).p;
      const Vec2 before = noded.edge(e2).a == m ? l2[1] : l2[l2.size() - 2];
      const double fl = distance(mp, before);
      if (e2 != e && fl > 0 && dot(p - mp, mp - before) < 0.0) {
        ++stats.hooksCut;
        endOf[static_cast<size_t>(m)] = static_cast<int>(ends.size());
        ends.push_back({m, e2, mp, (mp - before) / fl, e});
        continue;
      }
    }
    const double len = distance(p, prev);
    if (len <= 0) continue;
    endOf[ni] = static_cast<int>(ends.size());
    ends.push_back({n, e, p, (p - prev) / len});
  }
  // 1. Two dangling ends near each other meet where their lines cross (the corner both missed: an
  //    undershoot is extended, an overshoot trimmed), or are joined straight when they are parallel.
  //    Pairs are taken cheapest first, each end once.
  struct Pair {
    double cost;
    int i, j;
    Vec2 corner;
    bool parallel;
  };
  std::vector<Pair> pairs;
  CellGrid endGrid(std::max(gap, 2.0));
  for (size_t i = 0; i < ends.size(); ++i) endGrid.insert(ends[i].p, static_cast<int>(i));
  for (size_t i = 0; i < ends.size(); ++i) {
    const End& a = ends[i];
    endGrid.query(a.p.x - gap, a.p.y - gap, a.p.x + gap, a.p.y + gap, [&](int jj) {
      const size_t j = static_cast<size_t>(jj);
      if (j <= i) return;
      const End& b = ends[j];
      if (a.edge == b.edge || distance(a.p, b.p) > gap) return;
      // Two spurs from one node (a fork of jittered copies): their lines cross at that node, so
      // "closing the corner" would shrink both to a point and cut the line they continue.
      if (noded.otherEnd(a.edge, a.node) == noded.otherEnd(b.edge, b.node)) return;
      const double den = cross(a.d, b.d);
      if (std::abs(den) < 0.17) {                                // within ~10 degrees: parallel or opposite
        if (dot(a.d, b.d) < 0.0 && dot(b.p - a.p, a.d) > -1e-9)  // facing each other: a gap in one line
          pairs.push_back({distance(a.p, b.p), static_cast<int>(i), static_cast<int>(j), {}, true});
        return;
      }
      const double t = cross(b.p - a.p, b.d) / den;  // a.p + t a.d on b's line
      const Vec2 c = a.p + a.d * t;
      const double u = dot(c - b.p, b.d);
      if (std::abs(t) > gap || std::abs(u) > gap) return;
      pairs.push_back({std::abs(t) + std::abs(u), static_cast<int>(i), static_cast<int>(j), c, false});
    });
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    return x.cost != y.cost ? x.cost < y.cost : (x.i != y.i ? x.i < y.i : x.j < y.j);
  });
  std::vector<char> done(ends.size(), 0);
  std::vector<Vec2> moved(noded.nodeCount());
  std::vector<char> isMoved(noded.nodeCount(), 0);
  std::vector<LineString> bridges;
  for (const Pair& pr : pairs) {
    if (done[static_cast<size_t>(pr.i)] || done[static_cast<size_t>(pr.j)]) continue;
    done[static_cast<size_t>(pr.i)] = done[static_cast<size_t>(pr.j)] = 1;
    const End& a = ends[static_cast<size_t>(pr.i)];
    const End& b = ends[static_cast<size_t>(pr.j)];
    if (pr.parallel) {
      bridges.push_back({a.p, b.p});
    } else {
      moved[static_cast<size_t>(a.node)] = moved[static_cast<size_t>(b.node)] = pr.corner;
      isMoved[static_cast<size_t>(a.node)] = isMoved[static_cast<size_t>(b.node)] = 1;
    }
    ++stats.cornersClosed;
  }
  // 2. A lone dangling end is continued along its direction onto the first segment within the gap (an
  //    undershoot, also onto a segment's middle), or else joined to the nearest vertex.
  for (size_t i = 0; i < ends.size(); ++i) {
    if (done[i]) continue;
    const End& a = ends[i];
    const Vec2 p = a.p;
    double best = std::numeric_limits<double>::infinity();
    edgeGrid.query(p.x - gap, p.y - gap, p.x + gap, p.y + gap, [&](int f) {
      if (f == a.edge || f == a.hook) return;
      const LineString& l = noded.edge(f).line;
      for (size_t k = 1; k < l.size(); ++k) best = std::min(best, rayHit(p, a.d, l[k - 1], l[k]));
    });
    if (best > 1e-12 && best <= gap) {
      bridges.push_back({p, p + a.d * best});
      ++stats.undershootsToSegment;
      continue;
    }
    const int m = noded.otherEnd(a.edge, a.node);
    int nearest = -1;
    double nd = gap;
    nodeGrid.query(p.x - gap, p.y - gap, p.x + gap, p.y + gap, [&](int w) {
      if (w == a.node || w == m || (a.hook >= 0 && w == noded.otherEnd(a.hook, a.node))) return;
      const double dd = distance(p, noded.node(w).p);
      if (dd < nd || (dd == nd && nearest >= 0 && w < nearest)) nd = dd, nearest = w;
    });
    if (nearest >= 0) {
      bridges.push_back({p, noded.node(nearest).p});
      ++stats.undershootsToVertex;
    }
  }
  PlanarGraph joined = noded;
  if (!bridges.empty() || std::find(isMoved.begin(), isMoved.end(), 1) != isMoved.end()) {
    std::vector<LineString> all;
    all.reserve(noded.edgeCount() + bridges.size());
    for (size_t e = 0; e < noded.edgeCount(); ++e) {
      const auto& edge = noded.edge(static_cast<int>(e));
      LineString l = edge.line;
      if (isMoved[static_cast<size_t>(edge.a)]) l.front() = moved[static_cast<size_t>(edge.a)];
      if (isMoved[static_cast<size_t>(edge.b)]) l.back() = moved[static_cast<size_t>(edge.b)];
      all.push_back(std::move(l));
    }
    for (LineString& b : bridges) all.push_back(std::move(b));
    joined = nodedGraph(all);
  }
  reportProgress(progress, 0.8, "removing fringe paths");

  // Fringe removal: peel degree-1 nodes until none is left.
  std::vector<int> degree(joined.nodeCount());
  std::vector<char> removed(joined.edgeCount(), 0);
  std::vector<int> stack;
  for (size_t n = 0; n < joined.nodeCount(); ++n) {
    degree[n] = joined.degree(static_cast<int>(n));
    if (degree[n] == 1) stack.push_back(static_cast<int>(n));
  }
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (degree[static_cast<size_t>(n)] != 1) continue;
    for (int e : joined.node(n).edges) {
      if (removed[static_cast<size_t>(e)]) continue;
      removed[static_cast<size_t>(e)] = 1;
      ++stats.fringeEdgesRemoved;
      const int m = joined.otherEnd(e, n);
      degree[static_cast<size_t>(n)] = 0;
      if (--degree[static_cast<size_t>(m)] == 1) stack.push_back(m);
      break;
    }
  }
  PlanarGraph out;
  std::vector<int> newId(joined.nodeCount(), -1);
  for (size_t e = 0; e < joined.edgeCount(); ++e) {
    if (removed[e]) continue;
    const auto& edge = joined.edge(static_cast<int>(e));
    for (int n : {edge.a, edge.b})
      if (newId[static_cast<size_t>(n)] < 0) newId[static_cast<size_t>(n)] = 0;
  }
  for (size_t n = 0; n < joined.nodeCount(); ++n)
    if (newId[n] == 0) newId[n] = out.addNode(joined.node(static_cast<int>(n)).p);
  for (size_t e = 0; e < joined.edgeCount(); ++e) {
    if (removed[e]) continue;
    const auto& edge = joined.edge(static_cast<int>(e));
    out.addEdge(newId[static_cast<size_t>(edge.a)], newId[static_cast<size_t>(edge.b)], edge.line);
  }
  out.sortRotations();
  reportProgress(progress, 1.0, "removing fringe paths");
  return simplifyTolerance > 0.0 ? straightenChains(out, simplifyTolerance, stats) : out;
}

std::vector<int> preBlocks(const PlanarGraph& g, double threshold, int* count) {
  UnionFind uf(g.nodeCount());
  for (size_t e = 0; e < g.edgeCount(); ++e)
    uf.unite(g.edge(static_cast<int>(e)).a, g.edge(static_cast<int>(e)).b);
  CellGrid grid(std::max(threshold, 2.0));
  for (size_t e = 0; e < g.edgeCount(); ++e) {
    double x0, y0, x1, y1;
    edgeBox(g.edge(static_cast<int>(e)).line, x0, y0, x1, y1);
    grid.insertBox(x0, y0, x1, y1, static_cast<int>(e));
  }
  for (size_t ei = 0; ei < g.edgeCount(); ++ei) {
    const auto& e = g.edge(static_cast<int>(ei));
    double x0, y0, x1, y1;
    edgeBox(e.line, x0, y0, x1, y1);
    grid.query(x0 - threshold, y0 - threshold, x1 + threshold, y1 + threshold, [&](int fi) {
      const auto& f = g.edge(fi);
      if (uf.find(e.a) == uf.find(f.a)) return;
      for (size_t i = 1; i < e.line.size(); ++i)
        for (size_t j = 1; j < f.line.size(); ++j)
          if (segmentDistance(e.line[i - 1], e.line[i], f.line[j - 1], f.line[j]) < threshold) {
            uf.unite(e.a, f.a);
            return;
          }
    });
  }
  std::vector<int> id(g.nodeCount(), -1), label(g.nodeCount(), -1);
  int next = 0;
  for (size_t n = 0; n < g.nodeCount(); ++n) {
    const int r = uf.find(static_cast<int>(n));
    if (label[static_cast<size_t>(r)] < 0) label[static_cast<size_t>(r)] = next++;
    id[n] = label[static_cast<size_t>(r)];
  }
  if (count) *count = next;
  return id;
}

}  // namespace urbanvec::cadastre
