// Stage D1, "Block outlining" (shared/specs/sexton-vectorizer.md §3 D1, §10, §11.4).
#include "urbanvec/vectorize/blocks/block_outline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"

namespace urbanvec::vectorize {

void orientClockwise(Polygon& polygon) {
  if (signedArea(polygon.outer) > 0.0) std::reverse(polygon.outer.begin(), polygon.outer.end());
  for (Ring& hole : polygon.holes)
    if (signedArea(hole) < 0.0) std::reverse(hole.begin(), hole.end());
}

OrientedBox orientedBoundingBox(const Polygon& polygon) {
  OrientedBox box;
  if (polygon.outer.size() < 4) return box;
  // Moments relative to the first vertex keep the sums well conditioned in large frames.
  const Vec2 ref = polygon.outer.front();
  double a = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  auto accumulate = [&](const Ring& ring, double sign) {
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2 p = ring[i] - ref;
      const Vec2 q = ring[i + 1] - ref;
      const double c = sign * cross(p, q);
      a += c / 2.0;
      sx += (p.x + q.x) * c / 6.0;
      sy += (p.y + q.y) * c / 6.0;
      sxx += (p.x * p.x + p.x * q.x + q.x * q.x) * c / 12.0;
      syy += (p.y * p.y + p.y * q.y + q.y * q.y) * c / 12.0;
      sxy += (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) * c / 24.0;
    }
  };
  accumulate(polygon.outer, signedArea(polygon.outer) >= 0.0 ? 1.0 : -1.0);
  for (const Ring& hole : polygon.holes) accumulate(hole, signedArea(hole) >= 0.0 ? -1.0 : 1.0);
  if (!(a > 0.0)) return box;
  const double cx = sx / a, cy = sy / a;
  const double cxx = sxx / a - cx * cx, cyy = syy / a - cy * cy, cxy = sxy / a - cx * cy;
  auto extents = [&](double theta, double& minU, double& maxU, double& minV, double& maxV) {
    const Vec2 u{std::cos(theta), std::sin(theta)};
    const Vec2 v{-u.y, u.x};
    minU = minV = 1e300;
    maxU = maxV = -1e300;
    for (const Vec2& p : polygon.outer) {
      const Vec2 d = p - ref;
      minU = std::min(minU, dot(d, u));
      maxU = std::max(maxU, dot(d, u));
      minV = std::min(minV, dot(d, v));
      maxV = std::max(maxV, dot(d, v));
    }
  };
  double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  // An isotropic shape (square, disc) has no principal axis: PCA's angle is then rounding noise, so
  // take the tightest box over the outline's edge directions instead.
  const double spread = std::hypot(cxx - cyy, 2.0 * cxy);
  if (spread <= 1e-3 * (cxx + cyy)) {
    double bestArea = 1e300;
    for (size_t i = 0; i + 1 < polygon.outer.size(); ++i) {
      const Vec2 e = polygon.outer[i + 1] - polygon.outer[i];
      if (length(e) <= 0.0) continue;
      const double candidate = std::atan2(e.y, e.x);
      double a0, a1, b0, b1;
      extents(candidate, a0, a1, b0, b1);
      if ((a1 - a0) * (b1 - b0) < bestArea * (1.0 - 1e-9)) {
        bestArea = (a1 - a0) * (b1 - b0);
        theta = candidate;
      }
    }
  }
  const Vec2 u{std::cos(theta), std::sin(theta)};
  const Vec2 v{-u.y, u.x};
  double minU, maxU, minV, maxV;
  extents(theta, minU, maxU, minV, maxV);
  const double extentU = maxU - minU, extentV = maxV - minV;
  box.centre = ref + Vec2{cx, cy};
  box.axis = extentU >= extentV ? u : v;
  box.length = std::max(extentU, extentV);
  box.width = std::min(extentU, extentV);
  box.aspect = box.length > 0.0 ? box.width / box.length : 0.0;
  box.diagonal = std::hypot(box.width, box.length);
  return box;
}

int absorbSlivers(std::vector<PavementPiece>& pavement, const MultiPolygon& slivers, double precisionGrid,
                  int threads) {
  if (slivers.empty()) return 0;
  geos::Context ctx;
  std::vector<geos::GeomPtr> pieces;
  std::vector<const GEOSGeometry*> raw;
  for (const PavementPiece& p : pavement) {
    pieces.push_back(ctx.multiPolygon(p.shape));
    raw.push_back(pieces.back().get());
  }
  GeometryIndex index(ctx, raw);
  std::vector<std::vector<geos::GeomPtr>> additions(pavement.size());
  int absorbed = 0;
  // The envelope of each piece: its place in the order that picks a sliver's piece.
  std::vector<std::array<double, 5>> key(pavement.size());
  for (size_t k = 0; k < pavement.size(); ++k) key[k] = envelopeKey(ctx, raw[k]);
  for (const Polygon& sliver : slivers) {
    geos::GeomPtr g = ctx.polygon(sliver);
    int best = -1;
    for (int k : index.query(g.get())) {
      double d = 1.0;
      GEOSDistance_r(ctx.handle(), raw[k], g.get(), &d);
      if (d > 10.0 * precisionGrid) continue;
      if (best < 0 || key[k] < key[best]) best = k;
    }
    if (best < 0) continue;
    additions[best].push_back(std::move(g));
    ++absorbed;
  }
  std::vector<size_t> grown;
  for (size_t k = 0; k < pavement.size(); ++k)
    if (!additions[k].empty()) grown.push_back(k);
  const GeosWorkers workers(threads);
  workers.run(grown.size(), [&](size_t i, size_t, const geos::Context& context) {
    const size_t k = grown[i];
    additions[k].push_back(std::move(pieces[k]));
    geos::GeomPtr merged = unionOnGrid(context, std::move(additions[k]), precisionGrid);
    MultiPolygon shape = context.toPolygons(merged.get());
    for (Polygon& p : shape) orientClockwise(p);
    pavement[k].shape = std::move(shape);
  });
  return absorbed;
}

namespace {

std::uint64_t bitsOf(double v) {
  std::uint64_t u = 0;
  v += 0.0;  // -0 and +0 are one point
  std::memcpy(&u, &v, sizeof u);
  return u;
}

struct PointKey {
  std::uint64_t x = 0, y = 0;
  bool operator==(const PointKey& o) const { return x == o.x && y == o.y; }
};
struct EdgeKey {
  PointKey a, b;
  bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b; }
};
struct EdgeKeyHash {
  size_t operator()(const EdgeKey& k) const {
    std::uint64_t h = k.a.x * 0x9E3779B97F4A7C15ull;
    for (std::uint64_t v : {k.a.y, k.b.x, k.b.y}) h = (h ^ (h >> 29) ^ v) * 0xBF58476D1CE4E5B9ull;
    return static_cast<size_t>(h ^ (h >> 32));
  }
};
PointKey keyOf(const Vec2& p) {
  return {bitsOf(p.x), bitsOf(p.y)};
}

/// Signed area of a closed ring about its first vertex: the orientation of rings a few grid steps wide
/// far from the origin, where the shoelace sum of absolute coordinates loses it to rounding.
double localSignedArea(const Ring& ring) {
  if (ring.size() < 4) return 0.0;
  double twice = 0.0;
  const Vec2 o = ring.front();
  for (size_t i = 1; i + 2 < ring.size(); ++i) twice += cross(ring[i] - o, ring[i + 1] - o);
  return 0.5 * twice;
}

/// Angle from `from` to `to`, counter-clockwise, in (0, 2 pi].
double ccwAngle(const Vec2& from, const Vec2& to) {
  double a = std::atan2(cross(from, to), dot(from, to));
  if (a <= 0.0) a += 2.0 * 3.14159265358979323846;
  return a;
}

}  // namespace

bool coverageUnion(const std::vector<PavementPiece>& pieces, MultiPolygon& out) {
  std::vector<const Polygon*> polygons;
  for (const PavementPiece& piece : pieces)
    for (const Polygon& p : piece.shape) polygons.push_back(&p);
  return coverageUnion(polygons, out);
}

bool coverageUnion(const std::vector<const Polygon*>& polygons, MultiPolygon& out) {
  out.clear();
  // Every ring edge, directed with the piece on its right (outer rings clockwise, holes
  // counter-clockwise); an edge met once in each direction lies between two pieces and cancels.
  std::vector<std::pair<Vec2, Vec2>> edges;
  std::vector<char> alive;
  std::unordered_map<EdgeKey, size_t, EdgeKeyHash> open;
  auto addRing = [&](const Ring& ring, bool outer) {
    const bool reverse = (localSignedArea(ring) > 0.0) == outer;
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      Vec2 a = ring[i], b = ring[i + 1];
      if (reverse) std::swap(a, b);
      if (a == b) continue;
      const auto back = open.find({keyOf(b), keyOf(a)});
      if (back != open.end()) {
        alive[back->second] = 0;
        open.erase(back);
        continue;
      }
      if (!open.emplace(EdgeKey{keyOf(a), keyOf(b)}, edges.size()).second) return false;  // overlap
      edges.emplace_back(a, b);
      alive.push_back(1);
    }
    return true;
  };
  for (const Polygon* p : polygons) {
    if (!addRing(p->outer, true)) return false;
    for (const Ring& h : p->holes)
      if (!addRing(h, false)) return false;
  }
  open = {};
  // The edges left over, by start point, for the walk.
  std::vector<size_t> left;
  for (size_t e = 0; e < edges.size(); ++e)
    if (alive[e]) left.push_back(e);
  auto lexLess = [](const Vec2& p, const Vec2& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); };
  std::vector<size_t> byStart = left;
  std::sort(byStart.begin(), byStart.end(), [&](size_t e, size_t f) {
    return lexLess(edges[e].first, edges[f].first) || (edges[e].first == edges[f].first && e < f);
  });
  // Each incoming edge continues with the first outgoing edge counter-clockwise from its reverse:
  // that keeps the pavement on the right and splits the boundary at points where it touches itself.
  auto next = [&](size_t in) -> size_t {
    const Vec2& v = edges[in].second;
    auto lo = std::lower_bound(byStart.begin(), byStart.end(), v,
                               [&](size_t e, const Vec2& p) { return lexLess(edges[e].first, p); });
    size_t best = SIZE_MAX;
    double bestAngle = 0.0;
    const Vec2 back = edges[in].first - v;
    for (auto it = lo; it != byStart.end() && edges[*it].first == v; ++it) {
      const double a = ccwAngle(back, edges[*it].second - v);
      if (best == SIZE_MAX || a < bestAngle) {
        best = *it;
        bestAngle = a;
      }
    }
    return best;
  };
  std::vector<char> used(edges.size(), 0);
  std::vector<Ring> shells, holes;
  for (size_t start : left) {
    if (used[start]) continue;
    Ring ring{edges[start].first};
    for (size_t e = start;;) {
      used[e] = 1;
      ring.push_back(edges[e].second);
      e = next(e);
      if (e == SIZE_MAX || (used[e] && e != start)) return false;  // not closed: not a coverage
      if (e == start) break;
    }
    // A ring through one point twice (the union touching itself there) is split into simple rings
    // at that point; clockwise ones bound pavement (shells), counter-clockwise ones holes.
    std::vector<Vec2> stack;
    std::unordered_map<EdgeKey, size_t, EdgeKeyHash> seen;  // point (as a degenerate edge) -> depth
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2& p = ring[i];
      const PointKey k = keyOf(p);
      const auto at = seen.find({k, k});
      if (at == seen.end()) {
        seen.emplace(EdgeKey{k, k}, stack.size());
        stack.push_back(p);
        continue;
      }
      Ring loop(stack.begin() + static_cast<std::ptrdiff_t>(at->second), stack.end());
      loop.push_back(p);
      for (size_t j = at->second + 1; j < stack.size(); ++j)
        seen.erase(EdgeKey{keyOf(stack[j]), keyOf(stack[j])});
      stack.resize(at->second + 1);
      (localSignedArea(loop) < 0.0 ? shells : holes).push_back(std::move(loop));
    }
    stack.push_back(stack.front());
    (localSignedArea(stack) < 0.0 ? shells : holes).push_back(std::move(stack));
  }
  // Each hole goes to the smallest shell around one of its edge midpoints (shells tested smallest
  // first). A shell's crossing test visits only the edges of the horizontal strip that holds the point:
  // the whole network's outline, around every block, has most of the vertices.
  struct Strips {
    double y0 = 0.0, height = 1.0;
    std::vector<std::vector<std::uint32_t>> edges;  // per strip, the edges whose y range meets it
  };
  std::vector<std::array<double, 4>> box(shells.size());
  std::vector<double> shellArea(shells.size());
  std::vector<Strips> strips(shells.size());
  for (size_t s = 0; s < shells.size(); ++s) {
    box[s] = {1e300, 1e300, -1e300, -1e300};
    for (const Vec2& p : shells[s]) {
      box[s][0] = std::min(box[s][0], p.x);
      box[s][1] = std::min(box[s][1], p.y);
      box[s][2] = std::max(box[s][2], p.x);
      box[s][3] = std::max(box[s][3], p.y);
    }
    shellArea[s] = -localSignedArea(shells[s]);
    const Ring& r = shells[s];
    const size_t count = std::max<size_t>(1, static_cast<size_t>(std::sqrt(static_cast<double>(r.size()))));
    Strips& st = strips[s];
    st.y0 = box[s][1];
    st.height = std::max((box[s][3] - box[s][1]) / static_cast<double>(count), 1e-300);
    st.edges.resize(count);
    auto stripOf = [&](double y) {
      return std::min(count - 1, static_cast<size_t>(std::max(0.0, (y - st.y0) / st.height)));
    };
    for (size_t e = 0; e + 1 < r.size(); ++e) {
      const size_t lo = stripOf(std::min(r[e].y, r[e + 1].y)), hi = stripOf(std::max(r[e].y, r[e + 1].y));
      for (size_t k = lo; k <= hi; ++k) st.edges[k].push_back(static_cast<std::uint32_t>(e));
    }
  }
  auto shellContains = [&](size_t s, const Vec2& p) {
    const Strips& st = strips[s];
    const Ring& r = shells[s];
    const size_t k =
        std::min(st.edges.size() - 1, static_cast<size_t>(std::max(0.0, (p.y - st.y0) / st.height)));
    bool inside = false;
    for (std::uint32_t e : st.edges[k])
      if (edgeCrossesRayRight(r[e], r[e + 1], p)) inside = !inside;
    return inside;
  };
  std::vector<size_t> byX(shells.size());
  for (size_t s = 0; s < shells.size(); ++s) byX[s] = s;
  std::sort(byX.begin(), byX.end(),
            [&](size_t a, size_t b) { return box[a][0] < box[b][0] || (box[a][0] == box[b][0] && a < b); });
  for (size_t s = 0; s < shells.size(); ++s) out.push_back(Polygon{shells[s], {}});
  std::vector<size_t> candidates;
  for (Ring& h : holes) {
    const Vec2 probe = (h[0] + h[1]) * 0.5;
    candidates.clear();
    for (size_t s : byX) {
      if (box[s][0] > probe.x) break;
      if (probe.x <= box[s][2] && probe.y >= box[s][1] && probe.y <= box[s][3]) candidates.push_back(s);
    }
    std::sort(candidates.begin(), candidates.end(), [&](size_t a, size_t b) {
      return shellArea[a] < shellArea[b] || (shellArea[a] == shellArea[b] && a < b);
    });
    size_t best = SIZE_MAX;
    for (size_t s : candidates)
      if (shellContains(s, probe)) {
        best = s;
        break;
      }
    if (best == SIZE_MAX) return false;
    out[best].holes.push_back(std::move(h));
  }
  return true;
}

BlockOutline outlineBlocks(const std::vector<PavementPiece>& pavement, const BlockOutlineOptions& options,
                           const Progress& progress) {
  if (!(options.precisionGrid > 0.0))
    throw invalidOption("The precision grid must be positive, got " + std::to_string(options.precisionGrid) +
                        ".");
  reportProgress(progress, 0.0, "block outlining");
  geos::Context ctx;
  const double grid = options.precisionGrid;
  BlockOutline out;
  // Stage C's pieces form a coverage: their union is the walk of the edges that are not shared. The
  // frame-anchored overlay union stays for pavement that is not one (pieces made elsewhere).
  MultiPolygon pavementUnion;  // on the precision grid; freed when D1 returns
  if (!coverageUnion(pavement, pavementUnion)) {
    std::vector<geos::GeomPtr> parts;
    for (const PavementPiece& piece : pavement) parts.push_back(ctx.multiPolygon(piece.shape));
    const GeosWorkers workers(options.threads);
    geos::GeomPtr all = frameAnchoredUnion(ctx, workers, std::move(parts), grid, options.unionSquare);
    pavementUnion = ctx.toPolygons(all.get());
  }
  reportProgress(progress, 0.5, "block outlining");

  const MultiPolygon& components = pavementUnion;
  std::vector<geos::GeomPtr> filled;
  std::vector<geos::GeomPtr> probes;  // one point inside each component's pavement
  std::vector<const GEOSGeometry*> filledRaw;
  for (const Polygon& c : components) {
    filled.push_back(ctx.polygon(Polygon{c.outer, {}}));
    geos::GeomPtr solid = ctx.polygon(c);
    probes.push_back(ctx.own(GEOSPointOnSurface_r(ctx.handle(), solid.get()), "point on surface"));
    filledRaw.push_back(filled.back().get());
  }
  GeometryIndex index(ctx, filledRaw);
  std::vector<bool> nested(components.size(), false);
  const Progress holes = subProgress(progress, 0.5, 1.0);
  ProgressTicker ticker(holes, "block outlining", components.size());
  for (size_t k = 0; k < components.size(); ++k) {
    for (const Ring& holeRing : components[k].holes) {
      geos::GeomPtr hole = ctx.polygon(Polygon{holeRing, {}});
      std::vector<geos::GeomPtr> inside;
      for (int j : index.query(hole.get())) {
        if (static_cast<size_t>(j) == k) continue;
        if (GEOSContains_r(ctx.handle(), hole.get(), probes[j].get()) == 1) {
          nested[j] = true;
          inside.push_back(ctx.own(GEOSGeom_clone_r(ctx.handle(), filled[j].get()), "clone"));
        }
      }
      MultiPolygon faces;
      if (inside.empty()) {
        faces.push_back(Polygon{holeRing, {}});
      } else {
        geos::GeomPtr cut = unionOnGrid(ctx, std::move(inside), grid);
        geos::GeomPtr face =
            ctx.own(GEOSDifferencePrec_r(ctx.handle(), hole.get(), cut.get(), grid), "difference");
        faces = ctx.toPolygons(face.get());
      }
      for (Polygon& f : faces) {
        if (!(area(f) > 0.0)) continue;
        orientClockwise(f);
        (area(f) < options.minBlockArea ? out.slivers : out.internalBlocks).push_back(std::move(f));
      }
    }
    ticker.tick();
  }
  for (size_t k = 0; k < components.size(); ++k) {
    if (nested[k]) continue;
    Polygon p{components[k].outer, {}};
    orientClockwise(p);
    out.perimeter.push_back(std::move(p));
  }
  ticker.finish();
  return out;
}

}  // namespace urbanvec::vectorize
