// Merging split vertices (issue 17). See vertex_merging.hpp.
#include "urbanvec/cadastre/vertex_merging.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/cadastre/segment_cleaning.hpp"
#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/core/union_find.hpp"

namespace urbanvec::cadastre {
void mergeSplitVertices(Linework& lw, double dist, double sliverWidth, MergeStats& stats) {
  stats = {};
  const std::size_t n = lw.vertices.size();
  if (!(dist > 0.0) || n == 0) return;
  // Clusters by union-find; the root is the lowest id, and holds the cluster's position and lists.
  UnionFind clusters(n);
  auto find = [&](int x) { return clusters.find(x); };
  std::vector<Vec2> pos = lw.vertices;
  std::vector<double> weight(n, 0.0);
  std::vector<std::vector<int>> drawn(n);  // ids observed by a drawn segment from the cluster
  for (const EndCopy& c : lw.copies)
    if (c.vertex >= 0 && c.other >= 0 && c.vertex != c.other) {
      weight[static_cast<std::size_t>(c.vertex)] += 1.0;
      drawn[static_cast<std::size_t>(c.vertex)].push_back(c.other);
    }
  std::vector<std::vector<int>> incident(n);  // segments at the cluster
  for (std::size_t s = 0; s < lw.segments.size(); ++s) {
    incident[static_cast<std::size_t>(lw.segments[s].a)].push_back(static_cast<int>(s));
    incident[static_cast<std::size_t>(lw.segments[s].b)].push_back(static_cast<int>(s));
  }
  // Segments in a grid by their box at the current positions; a moved segment is inserted again
  // (stale entries only add candidates, every query checks the current geometry).
  std::vector<double> lengths;
  for (const Segment& s : lw.segments)
    lengths.push_back(distance(pos[static_cast<std::size_t>(s.a)], pos[static_cast<std::size_t>(s.b)]));
  double cell = 2.0 * dist;
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                     lengths.end());
    cell = std::max(cell, lengths[lengths.size() / 2]);
  }
  CellGrid segGrid(cell);
  auto ends = [&](int s, Vec2& a, Vec2& b) {
    const Segment& sg = lw.segments[static_cast<std::size_t>(s)];
    a = pos[static_cast<std::size_t>(find(sg.a))], b = pos[static_cast<std::size_t>(find(sg.b))];
  };
  auto insertSegment = [&](int s) {
    Vec2 a, b;
    ends(s, a, b);
    segGrid.insertBox(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y), s);
  };
  for (std::size_t s = 0; s < lw.segments.size(); ++s) insertSegment(static_cast<int>(s));

  // Candidate pairs, closest first.
  struct Pair {
    double d;
    int i, j;
  };
  std::vector<Pair> pairs;
  {
    CellGrid grid(dist);
    for (std::size_t i = 0; i < n; ++i)
      if (!incident[i].empty()) grid.insert(pos[i], static_cast<int>(i));
    for (std::size_t i = 0; i < n; ++i) {
      if (incident[i].empty()) continue;
      const Vec2 p = pos[i];
      grid.query(p.x - dist, p.y - dist, p.x + dist, p.y + dist, [&](int j) {
        if (j <= static_cast<int>(i)) return;
        const double d = distance(p, pos[static_cast<std::size_t>(j)]);
        if (d < dist) pairs.push_back({d, static_cast<int>(i), j});
      });
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& u, const Pair& v) {
    return u.d != v.d ? u.d < v.d : (u.i != v.i ? u.i < v.i : u.j < v.j);
  });
  // A query may visit a cell twice (hashed cells): each pair once.
  pairs.erase(std::unique(pairs.begin(), pairs.end(),
                          [](const Pair& u, const Pair& v) { return u.i == v.i && u.j == v.j; }),
              pairs.end());
  stats.candidates = pairs.size();

  std::vector<int> before, after, seen, nx;
  // Segments (other than those at x or y) crossed by a segment at x or y, with x and y at px and py.
  auto crossed = [&](int x, int y, const Vec2& px, const Vec2& py, std::vector<int>& out) {
    out.clear();
    auto at = [&](int r) { return r == x ? px : (r == y ? py : pos[static_cast<std::size_t>(r)]); };
    for (int r : {x, y})
      for (int s : incident[static_cast<std::size_t>(r)]) {
        const Segment& sg = lw.segments[static_cast<std::size_t>(s)];
        const int ra = find(sg.a), rb = find(sg.b);
        if (ra == rb || ((ra == x || ra == y) && (rb == x || rb == y))) continue;
        const Vec2 a = at(ra), b = at(rb);
        seen.clear();
        segGrid.query(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y),
                      [&](int t) { seen.push_back(t); });
        std::sort(seen.begin(), seen.end());
        seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
        for (int t : seen) {
          const Segment& tg = lw.segments[static_cast<std::size_t>(t)];
          const int ta = find(tg.a), tb = find(tg.b);
          if (ta == x || ta == y || tb == x || tb == y || ta == ra || ta == rb || tb == ra || tb == rb)
            continue;
          if (segmentsCross(a, b, pos[static_cast<std::size_t>(ta)], pos[static_cast<std::size_t>(tb)]))
            out.push_back(t);
        }
      }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  auto neighbours = [&](int r, std::vector<int>& out) {
    out.clear();
    for (int s : incident[static_cast<std::size_t>(r)]) {
      const Segment& sg = lw.segments[static_cast<std::size_t>(s)];
      const int ra = find(sg.a), rb = find(sg.b);
      if (ra != rb) out.push_back(ra == r ? rb : ra);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  std::vector<int> ny;
  for (const Pair& q : pairs) {
    int x = find(q.i), y = find(q.j);
    if (x == y) continue;
    if (x > y) std::swap(x, y);
    const Vec2 px = pos[static_cast<std::size_t>(x)], py = pos[static_cast<std::size_t>(y)];
    if (!(distance(px, py) < dist)) continue;
    // A drawn segment between the two clusters: a true (short) edge.
    bool isDrawn = false;
    for (int r : {x, y}) {
      const int other = r == x ? y : x;
      for (int o : drawn[static_cast<std::size_t>(r)])
        if (find(o) == other) isDrawn = true;
    }
    if (isDrawn) {
      ++stats.refusedDrawn;
      continue;
    }
    const double wx = std::max(weight[static_cast<std::size_t>(x)], 1.0),
                 wy = std::max(weight[static_cast<std::size_t>(y)], 1.0);
    const Vec2 m = (px * wx + py * wy) / (wx + wy);
    // Faces: a triangle closed with a common neighbour collapses; only slivers may.
    neighbours(x, nx);
    neighbours(y, ny);
    bool face = false;
    for (int w : nx) {
      if (w == y || !std::binary_search(ny.begin(), ny.end(), w)) continue;
      const Vec2 pw = pos[static_cast<std::size_t>(w)];
      const double area2 = std::abs(cross(py - px, pw - px));
      const double longest = std::max({distance(px, py), distance(px, pw), distance(py, pw)});
      if (longest > 0 && area2 / longest >= sliverWidth) face = true;
    }
    if (face) {
      ++stats.refusedFace;
      continue;
    }
    crossed(x, y, px, py, before);
    crossed(x, y, m, m, after);
    if (!std::includes(before.begin(), before.end(), after.begin(), after.end())) {
      ++stats.refusedCrossing;
      continue;
    }
    clusters.unite(x, y);  // x < y: x stays the root
    pos[static_cast<std::size_t>(x)] = m;
    weight[static_cast<std::size_t>(x)] =
        weight[static_cast<std::size_t>(x)] + weight[static_cast<std::size_t>(y)];
    auto& dx = drawn[static_cast<std::size_t>(x)];
    auto& dy = drawn[static_cast<std::size_t>(y)];
    dx.insert(dx.end(), dy.begin(), dy.end());
    dy.clear();
    auto& ix = incident[static_cast<std::size_t>(x)];
    auto& iy = incident[static_cast<std::size_t>(y)];
    ix.insert(ix.end(), iy.begin(), iy.end());
    iy.clear();
    for (int s : ix) insertSegment(s);
    ++stats.merged;
  }
  if (stats.merged == 0) return;
  // Renumber: clusters in order of their root (lowest old id).
  std::vector<int> newId(n, -1);
  std::vector<Vec2> vertices;
  std::vector<char> sound;
  for (std::size_t i = 0; i < n; ++i) {
    const int r = find(static_cast<int>(i));
    if (r != static_cast<int>(i)) continue;
    newId[i] = static_cast<int>(vertices.size());
    vertices.push_back(pos[i]);
    if (!lw.sound.empty()) sound.push_back(lw.sound[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const int r = find(static_cast<int>(i));
    newId[i] = newId[static_cast<std::size_t>(r)];
    if (!lw.sound.empty() && !lw.sound[i]) sound[static_cast<std::size_t>(newId[i])] = 0;
  }
  std::vector<Segment> segments;
  segments.reserve(lw.segments.size());
  for (Segment s : lw.segments) {
    s.a = newId[static_cast<std::size_t>(s.a)], s.b = newId[static_cast<std::size_t>(s.b)];
    if (s.a != s.b) segments.push_back(s);
  }
  dropDuplicateSegments(segments);
  for (EndCopy& c : lw.copies) {
    if (c.vertex >= 0) c.vertex = newId[static_cast<std::size_t>(c.vertex)];
    if (c.other >= 0) c.other = newId[static_cast<std::size_t>(c.other)];
  }
  lw.vertices = std::move(vertices);
  lw.segments = std::move(segments);
  lw.sound = std::move(sound);
}

}  // namespace urbanvec::cadastre
