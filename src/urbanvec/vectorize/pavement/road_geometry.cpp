// Stage C, "Road geometry creation" (shared/specs/sexton-vectorizer.md §3 C, §5.2, §6, §11.3).
#include "urbanvec/vectorize/pavement/road_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/parallel.hpp"
#include "urbanvec/vectorize/blocks/block_outline.hpp"

namespace urbanvec::vectorize {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Points closer than this (cells) are one point: duplicate nodes carry no direction.
constexpr double kSamePoint = 1e-9;

Vec2 unit(const Vec2& v) {
  const double len = length(v);
  return len > 0.0 ? v / len : Vec2{0.0, 0.0};
}
Vec2 leftNormal(const Vec2& d) {
  return {-d.y, d.x};
}
Vec2 rightNormal(const Vec2& d) {
  return {d.y, -d.x};
}

/// Azimuth clockwise from due north in [0, 2*pi) (spec §0).
double azimuthOf(const Vec2& d) {
  double a = std::atan2(d.x, d.y);
  if (a < 0.0) a += 2.0 * kPi;
  return a;
}

LineString withoutRepeats(const LineString& line) {
  LineString out;
  for (const Vec2& p : line)
    if (out.empty() || distance(out.back(), p) > kSamePoint) out.push_back(p);
  return out;
}

double halfWidthOf(RoadClass c, const RoadGeometryOptions& o) {
  return c == RoadClass::Primary ? o.primaryHalfWidth : o.secondaryHalfWidth;
}

geos::GeomPtr convexHullOf(const geos::Context& ctx, const std::vector<Vec2>& points) {
  std::vector<geos::GeomPtr> parts;
  for (const Vec2& p : points) parts.push_back(ctx.point(p));
  geos::GeomPtr multi = ctx.collection(GEOS_MULTIPOINT, std::move(parts));
  return ctx.own(GEOSConvexHull_r(ctx.handle(), multi.get()), "convex hull");
}

/// The offset of a polyline vertex on one side (`side` = +1 left, -1 right): the miter point of the
/// offset lines of the two incident links, clamped to `clamp` x w, or the plain normal offset at ends.
Vec2 curbVertex(const LineString& line, size_t i, double w, double side, double clamp) {
  const size_t n = line.size();
  if (i == 0) return line[0] + leftNormal(unit(line[1] - line[0])) * (side * w);
  if (i + 1 == n) return line[i] + leftNormal(unit(line[i] - line[i - 1])) * (side * w);
  const Vec2 n0 = leftNormal(unit(line[i] - line[i - 1]));
  const Vec2 n1 = leftNormal(unit(line[i + 1] - line[i]));
  const Vec2 sum = n0 + n1;
  const double sumLength = length(sum);
  // Nearly reversing links have no finite miter: offset along the incoming normal instead.
  if (sumLength < 1e-9) return line[i] + n0 * (side * w);
  const double miter = std::min(2.0 * w / sumLength, clamp * w);
  return line[i] + sum / sumLength * (side * miter);
}

/// The pavement of one segment: the area between its two curbs, i.e. the triangle strip of the curb
/// vertices (miter points at the nodes, flat ends at the segment's end nodes). GEOS's flat-capped
/// mitre buffer of the centreline is exactly that strip where it is simple, and stays a valid polygon
/// where a raw strip would fold over itself (sharp turns, links shorter than the width); the mitre
/// limit is the miter clamp.
geos::GeomPtr segmentPavement(const geos::Context& ctx, const LineString& line, double w, double clamp) {
  geos::GeomPtr centreline = ctx.lineString(line);
  return ctx.own(GEOSBufferWithStyle_r(ctx.handle(), centreline.get(), w, 8, GEOSBUF_CAP_FLAT,
                                       GEOSBUF_JOIN_MITRE, clamp),
                 "segment buffer");
}

/// Octagon centred on `centre` with circumradius r and one edge perpendicular to `towardEnd`
/// (the direction of the incoming link), counter-clockwise.
Polygon octagon(const Vec2& centre, const Vec2& towardEnd, double r) {
  const double base = std::atan2(towardEnd.y, towardEnd.x);
  Polygon p;
  for (int k = 0; k < 8; ++k) {
    const double a = base + kPi / 8.0 + k * kPi / 4.0;
    p.outer.push_back(centre + Vec2{std::cos(a), std::sin(a)} * r);
  }
  p.outer.push_back(p.outer.front());
  return p;
}

/// One road leaving a node: the direction of the segment's first link seen from the node.
struct Arm {
  int segment = 0;
  int end = 0;  // 0 = the segment starts here, 1 = it ends here
  Vec2 dir;
  double halfWidth = 0.5;
  double azimuth = 0.0;
  RoadClass roadClass = RoadClass::Secondary;
  double firstLinkLength = 0.0;
};

/// The curb return in the block wedge at `corner` between the rays along dirA and dirB (wedge angle
/// `wedge` < pi): the region between the two curbs and the arc tangent to both, as a polygon; empty
/// when too small to matter. The tangent distance is capped at `maxTangent`.
Polygon curbReturn(const Vec2& corner, const Vec2& dirA, const Vec2& dirB, double wedge, double radius,
                   double maxTangent, int segments) {
  Polygon out;
  if (!(radius > 0.0) || !(wedge > 1e-3) || !(wedge < kPi - 1e-3) || segments < 1) return out;
  const double half = wedge / 2.0;
  double tangent = radius / std::tan(half);
  if (tangent > maxTangent) {
    tangent = maxTangent;
    radius = tangent * std::tan(half);
  }
  if (tangent < 1e-3) return out;
  const Vec2 bisector = unit(dirA + dirB);
  const Vec2 centre = corner + bisector * (radius / std::sin(half));
  const Vec2 ta = corner + dirA * tangent;
  const Vec2 fromCentre = ta - centre;
  const Vec2 tb = corner + dirB * tangent;
  const double sweep = (kPi - wedge) * (cross(fromCentre, tb - centre) >= 0.0 ? 1.0 : -1.0);
  out.outer.push_back(corner);
  for (int k = 0; k <= segments; ++k) {
    const double a = sweep * k / segments;
    const Vec2 r{fromCentre.x * std::cos(a) - fromCentre.y * std::sin(a),
                 fromCentre.x * std::sin(a) + fromCentre.y * std::cos(a)};
    out.outer.push_back(k == segments ? tb : centre + r);
  }
  out.outer.push_back(corner);
  return out;
}

struct RawPiece {
  geos::GeomPtr geom;
  PavementKind kind;
  RoadClass roadClass;
  int segment;
  int node;
};

/// Rounds every vertex to the precision grid; only a polygon that rounding made invalid pays for a
/// snap-rounding overlay.
geos::GeomPtr snapToGrid(const geos::Context& ctx, const GEOSGeometry* g, double grid) {
  MultiPolygon parts = ctx.toPolygons(g);
  auto round = [grid](Ring& ring) {
    for (Vec2& p : ring) p = {std::round(p.x / grid) * grid, std::round(p.y / grid) * grid};
  };
  for (Polygon& p : parts) {
    round(p.outer);
    for (Ring& h : p.holes) round(h);
  }
  geos::GeomPtr rounded = parts.size() == 1 ? ctx.polygon(parts.front()) : ctx.multiPolygon(parts);
  if (GEOSisValid_r(ctx.handle(), rounded.get()) == 1) return rounded;
  return ctx.own(GEOSGeom_setPrecision_r(ctx.handle(), g, grid, 0), "set precision");
}

bool isConvexPolygon(const std::vector<Vec2>& pts) {
  // Strict convexity of the closed sequence, ignoring repeated points; clockwise expected.
  std::vector<Vec2> p;
  for (const Vec2& v : pts)
    if (p.empty() || distance(p.back(), v) > kSamePoint) p.push_back(v);
  while (p.size() > 1 && distance(p.front(), p.back()) <= kSamePoint) p.pop_back();
  if (p.size() < 3) return true;
  int sign = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    const Vec2& c = p[(i + 2) % p.size()];
    const double t = cross(b - a, c - b);
    if (std::fabs(t) < 1e-12) continue;
    const int s = t > 0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign) return false;
  }
  return true;
}

/// Even-odd test of `p` against every ring of `polygons`.
bool insidePolygons(const MultiPolygon& polygons, const Vec2& p) {
  bool inside = false;
  for (const Polygon& poly : polygons) {
    inside ^= ringContains(poly.outer, p);
    for (const Ring& h : poly.holes) inside ^= ringContains(h, p);
  }
  return inside;
}

/// Overlap resolution as one arrangement (issue 21, round 6): the boundaries of the pieces are noded
/// together by snap rounding on the grid, the noded linework is cut into faces, and each face goes to
/// the first piece, in priority order, that holds its interior point. Neighbouring pieces are then made
/// of the same noded edges, so they meet on exactly shared vertices (a polygon coverage) and D1's union
/// of them is a walk of the unshared edges (coverageUnion), not an overlay.
///
/// The arrangement is built by region, in parallel, and gives the faces of the arrangement of all
/// pieces at once: snap rounding moves a segment only onto the hot pixels (vertices and crossings,
/// rounded to the grid) whose pixel it passes through, and splits it there. A face of piece A lies
/// inside A, so every edge around it runs inside A (or within a pixel of it) between hot pixels there:
/// the crossings with A's boundary, the vertices and crossings of the segments near A. Those segments
/// belong to A's neighbours (the pieces whose envelope comes within two grid steps of A's). So a region
/// (a square of `regionSize` cells anchored at the frame's origin, holding the pieces whose envelope
/// starts in it) nodes its own pieces with their neighbours and keeps the faces of its own pieces;
/// tiles, threads and the region size do not change them
/// (PavementCoverage.ResolvingByRegionGivesThePiecesOfOneRegion).
std::vector<PavementPiece> resolveOverlaps(const geos::Context& ctx, const GeosWorkers& workers,
                                           const std::vector<RawPiece>& raw, double grid, double regionSize,
                                           const Progress& progress) {
  const size_t n = raw.size();
  std::vector<std::array<double, 5>> env(n);
  for (size_t i = 0; i < n; ++i) env[i] = envelopeKey(ctx, raw[i].geom.get());
  // Neighbours: the pieces whose envelope comes within two grid steps of a piece's envelope (a hot
  // pixel is one grid step wide), itself included, in increasing order.
  std::vector<std::vector<int>> near(n);
  {
    std::vector<const GEOSGeometry*> rawGeoms;
    for (const RawPiece& piece : raw) rawGeoms.push_back(piece.geom.get());
    GeometryIndex index(ctx, rawGeoms);
    const double pad = 2.0 * grid;
    for (size_t i = 0; i < n; ++i) {
      const auto& e = env[i];
      geos::GeomPtr box = ctx.polygon(Polygon{{{e[0] - pad, e[1] - pad},
                                               {e[2] + pad, e[1] - pad},
                                               {e[2] + pad, e[3] + pad},
                                               {e[0] - pad, e[3] + pad},
                                               {e[0] - pad, e[1] - pad}},
                                              {}});
      near[i] = index.query(box.get());
    }
  }
  // Regions in frame order, each with its pieces in increasing order.
  std::vector<std::tuple<std::int64_t, std::int64_t, int>> keyed;
  for (size_t i = 0; i < n; ++i)
    keyed.emplace_back(static_cast<std::int64_t>(std::floor(env[i][0] / regionSize)),
                       static_cast<std::int64_t>(std::floor(env[i][1] / regionSize)), static_cast<int>(i));
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::vector<int>> regions;
  for (size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || std::get<0>(keyed[k]) != std::get<0>(keyed[k - 1]) ||
        std::get<1>(keyed[k]) != std::get<1>(keyed[k - 1]))
      regions.emplace_back();
    regions.back().push_back(std::get<2>(keyed[k]));
  }
  ProgressTicker ticker(progress, "road geometry overlaps", regions.size());
  std::vector<PavementPiece> resolved(n);
  std::vector<std::vector<int>> stamp(workers.size(), std::vector<int>(n, -1));
  workers.run(
      regions.size(),
      [&](size_t r, size_t worker, const geos::Context& c) {
        const GEOSContextHandle_t h = c.handle();
        std::vector<int>& mark = stamp[worker];  // mark[i] = 2r: own piece, 2r + 1: in the halo
        const int own = 2 * static_cast<int>(r), halo = own + 1;
        std::vector<int> members;
        for (int i : regions[r]) {
          mark[i] = own;
          members.push_back(i);
        }
        const size_t ownCount = members.size();
        for (size_t m = 0; m < ownCount; ++m)
          for (int j : near[members[m]])
            if (mark[j] != own && mark[j] != halo) {
              mark[j] = halo;
              members.push_back(j);
            }
        std::sort(members.begin(), members.end());
        std::vector<geos::GeomPtr> boundaries;
        std::vector<const GEOSGeometry*> memberGeoms;
        for (int i : members) {
          boundaries.push_back(c.own(GEOSBoundary_r(h, raw[i].geom.get()), "boundary"));
          memberGeoms.push_back(raw[i].geom.get());
        }
        geos::GeomPtr lines = c.collection(GEOS_GEOMETRYCOLLECTION, std::move(boundaries));
        geos::GeomPtr noded = c.own(GEOSUnaryUnionPrec_r(h, lines.get(), grid), "noding");
        const GEOSGeometry* nodedRaw = noded.get();
        geos::GeomPtr faces = c.own(GEOSPolygonize_r(h, &nodedRaw, 1), "polygonize");
        const int faceCount = GEOSGetNumGeometries_r(h, faces.get());
        GeometryIndex index(c, memberGeoms);
        std::vector<MultiPolygon> shapes(members.size());
        std::vector<std::vector<int>> facesOf(members.size());
        for (int k = 0; k < faceCount; ++k) {
          const GEOSGeometry* face = GEOSGetGeometryN_r(h, faces.get(), k);
          geos::GeomPtr pt = c.own(GEOSPointOnSurface_r(h, face), "point on surface");
          Vec2 probe;
          GEOSGeomGetX_r(h, pt.get(), &probe.x);
          GEOSGeomGetY_r(h, pt.get(), &probe.y);
          for (int m : index.query(pt.get())) {
            const int i = members[m];
            if (shapes[m].empty()) shapes[m] = c.toPolygons(raw[i].geom.get());
            if (!insidePolygons(shapes[m], probe)) continue;
            if (mark[i] == own) facesOf[m].push_back(k);
            break;
          }
        }
        for (size_t m = 0; m < members.size(); ++m) {
          const int i = members[m];
          if (mark[i] != own || facesOf[m].empty()) continue;
          // The piece's faces share their edges: their union is the walk of the edges they do not share.
          MultiPolygon shape;
          for (int k : facesOf[m]) {
            MultiPolygon face = c.toPolygons(GEOSGetGeometryN_r(h, faces.get(), k));
            shape.insert(shape.end(), face.begin(), face.end());
          }
          if (shape.size() > 1) {
            std::vector<const Polygon*> parts;
            for (const Polygon& p : shape) parts.push_back(&p);
            MultiPolygon merged;
            if (!coverageUnion(parts, merged)) {  // not met; an overlay union if it ever is
              std::vector<geos::GeomPtr> geoms;
              for (int k : facesOf[m])
                geoms.push_back(c.own(GEOSGeom_clone_r(h, GEOSGetGeometryN_r(h, faces.get(), k)), "clone"));
              merged = c.toPolygons(unionOnGrid(c, std::move(geoms), grid).get());
            }
            shape = std::move(merged);
          }
          PavementPiece& piece = resolved[i];
          piece = {{}, raw[i].kind, raw[i].roadClass, raw[i].segment, raw[i].node};
          for (Polygon& p : shape) {
            if (!(area(p) >= grid)) continue;  // precision crumbs
            orientClockwise(p);                // spec: clockwise polygons
            piece.shape.push_back(std::move(p));
          }
        }
        for (int i : members) mark[i] = -1;
      },
      [&](size_t done) { ticker.tick(done); });
  ticker.finish();
  return resolved;
}

}  // namespace

std::string_view pavementKindName(PavementKind kind) {
  switch (kind) {
    case PavementKind::Segment:
      return "segment";
    case PavementKind::Intersection:
      return "intersection";
    case PavementKind::CulDeSac:
      return "cul_de_sac";
  }
  return "segment";
}

std::string_view roadClassName(RoadClass roadClass) {
  switch (roadClass) {
    case RoadClass::Primary:
      return "primary";
    case RoadClass::Secondary:
      return "secondary";
    case RoadClass::Perimeter:
      return "perimeter";
  }
  return "secondary";
}

bool curbCorner(const Vec2& origin, const Vec2& dirA, double halfWidthA, const Vec2& dirB, double halfWidthB,
                double parallelSinEpsilon, Vec2& corner) {
  const double sine = cross(dirA, dirB);
  if (std::fabs(sine) < parallelSinEpsilon) return false;
  // origin + wA*rightA + t*dirA = origin + wB*leftB + s*dirB, solved for t.
  const Vec2 pa = rightNormal(dirA) * halfWidthA;
  const Vec2 pb = leftNormal(dirB) * halfWidthB;
  const double t = cross(pb - pa, dirB) / cross(dirA, dirB);
  corner = origin + pa + dirA * t;
  return true;
}

GeometryIndex::GeometryIndex(const geos::Context& context, const std::vector<const GEOSGeometry*>& geometries)
    : context_(context), ids_(geometries.size()) {
  tree_ = GEOSSTRtree_create_r(context_.handle(), 10);
  if (!tree_) throw internalError("GEOS failed to create an STRtree: " + context_.lastError());
  for (size_t i = 0; i < geometries.size(); ++i) {
    ids_[i] = static_cast<int>(i);
    if (geometries[i] && !GEOSisEmpty_r(context_.handle(), geometries[i]))
      GEOSSTRtree_insert_r(context_.handle(), tree_, geometries[i], &ids_[i]);
  }
}

GeometryIndex::~GeometryIndex() {
  if (tree_) GEOSSTRtree_destroy_r(context_.handle(), tree_);
}

std::vector<int> GeometryIndex::query(const GEOSGeometry* g) const {
  std::vector<int> hits;
  if (!g || GEOSisEmpty_r(context_.handle(), g)) return hits;
  GEOSSTRtree_query_r(
      context_.handle(), tree_, g,
      [](void* item, void* userdata) {
        static_cast<std::vector<int>*>(userdata)->push_back(*static_cast<const int*>(item));
      },
      &hits);
  std::sort(hits.begin(), hits.end());
  return hits;
}

GeosWorkers::GeosWorkers(int threads) {
  const size_t n = workerCount(threads);
  for (size_t i = 0; i < n; ++i) contexts_.push_back(std::make_unique<geos::Context>());
}

void GeosWorkers::run(size_t n, const std::function<void(size_t, size_t, const geos::Context&)>& body,
                      const std::function<void(size_t)>& tick) const {
  runParallel(
      contexts_.size(), n, [&](size_t i, size_t worker) { body(i, worker, *contexts_[worker]); }, tick);
}

geos::GeomPtr unionOnGrid(const geos::Context& context, std::vector<geos::GeomPtr> parts, double grid) {
  geos::GeomPtr all = context.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
  return context.own(GEOSUnaryUnionPrec_r(context.handle(), all.get(), grid), "unary union");
}

geos::GeomPtr floatingUnion(const geos::Context& context, std::vector<geos::GeomPtr> parts, double grid) {
  geos::GeomPtr all = context.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
  if (GEOSGeometry* g = GEOSUnaryUnion_r(context.handle(), all.get())) return context.own(g, "unary union");
  return context.own(GEOSUnaryUnionPrec_r(context.handle(), all.get(), grid), "unary union");
}

geos::GeomPtr floatingDifference(const geos::Context& context, const GEOSGeometry* a, const GEOSGeometry* b,
                                 double grid) {
  if (GEOSGeometry* g = GEOSDifference_r(context.handle(), a, b)) return context.own(g, "difference");
  return context.own(GEOSDifferencePrec_r(context.handle(), a, b, grid), "difference");
}

geos::GeomPtr frameAnchoredUnion(const geos::Context& context, const GeosWorkers& workers,
                                 std::vector<geos::GeomPtr> parts, double grid, double squareSize) {
  if (!(squareSize > 0.0))
    throw invalidOption("The union square must be positive, got " + std::to_string(squareSize) + " cells.");
  // Square keys are shifted to be non-negative, so halving them reaches one root square from anywhere.
  constexpr std::int64_t kKeyOffset = std::int64_t{1} << 40;
  struct Item {
    std::int64_t kx = 0, ky = 0;
    std::array<double, 5> envelope{};
    geos::GeomPtr geom;
  };
  std::vector<Item> items;
  const GEOSContextHandle_t h = context.handle();
  for (geos::GeomPtr& part : parts) {
    if (!part || GEOSisEmpty_r(h, part.get())) continue;
    Item item;
    item.envelope = envelopeKey(context, part.get());
    item.kx = static_cast<std::int64_t>(std::floor(item.envelope[0] / squareSize)) + kKeyOffset;
    item.ky = static_cast<std::int64_t>(std::floor(item.envelope[1] / squareSize)) + kKeyOffset;
    item.geom = std::move(part);
    items.push_back(std::move(item));
  }
  if (items.empty()) return context.collection(GEOS_GEOMETRYCOLLECTION, {});
  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return std::tie(a.kx, a.ky, a.envelope) < std::tie(b.kx, b.ky, b.envelope);
  });
  // OverlayNG keeps the lines of edges that snap rounding collapsed; the union of areas is the polygons.
  auto unite = [grid](const geos::Context& c, geos::GeomPtr& into, geos::GeomPtr add) {
    into = c.own(GEOSUnionPrec_r(c.handle(), into.get(), add.get(), grid), "union");
    if (GEOSGeomTypeId_r(c.handle(), into.get()) == GEOS_GEOMETRYCOLLECTION)
      into = c.multiPolygon(c.toPolygons(into.get()));
  };
  // Runs of equal key in `items` (sorted by key) are united in order into their first item.
  auto uniteRuns = [&] {
    std::vector<size_t> starts;
    for (size_t i = 0; i < items.size(); ++i)
      if (i == 0 || items[i].kx != items[i - 1].kx || items[i].ky != items[i - 1].ky) starts.push_back(i);
    starts.push_back(items.size());
    workers.run(starts.size() - 1, [&](size_t g, size_t, const geos::Context& c) {
      for (size_t i = starts[g] + 1; i < starts[g + 1]; ++i)
        unite(c, items[starts[g]].geom, std::move(items[i].geom));
    });
    std::vector<Item> next;
    for (size_t g = 0; g + 1 < starts.size(); ++g) next.push_back(std::move(items[starts[g]]));
    items = std::move(next);
  };
  uniteRuns();  // the squares
  for (bool byX = true; items.size() > 1; byX = !byX) {
    for (Item& item : items) (byX ? item.kx : item.ky) >>= 1;
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
      return std::tie(a.kx, a.ky) < std::tie(b.kx, b.ky);
    });
    uniteRuns();
  }
  return std::move(items.front().geom);
}

std::array<double, 5> envelopeKey(const geos::Context& context, const GEOSGeometry* g) {
  std::array<double, 5> key{};
  GEOSGeom_getXMin_r(context.handle(), g, &key[0]);
  GEOSGeom_getYMin_r(context.handle(), g, &key[1]);
  GEOSGeom_getXMax_r(context.handle(), g, &key[2]);
  GEOSGeom_getYMax_r(context.handle(), g, &key[3]);
  key[4] = geosArea(context, g);
  return key;
}

double geosArea(const geos::Context& context, const GEOSGeometry* g) {
  double a = 0.0;
  if (!g || GEOSisEmpty_r(context.handle(), g)) return 0.0;
  if (!GEOSArea_r(context.handle(), g, &a)) throw internalError("GEOS failed to compute an area");
  return a;
}

RoadGeometry buildRoadGeometry(const RoadNetwork& network, const RoadGeometryOptions& options,
                               const Progress& progress) {
  if (!(options.primaryHalfWidth > 0.0) || !(options.secondaryHalfWidth > 0.0))
    throw invalidOption("Road half-widths must be positive (primary " +
                        std::to_string(options.primaryHalfWidth) + ", secondary " +
                        std::to_string(options.secondaryHalfWidth) + " cells).");
  if (!(options.culDeSacCircumradius > 0.0))
    throw invalidOption("The cul-de-sac circumradius must be positive, got " +
                        std::to_string(options.culDeSacCircumradius) + " cells.");
  if (!(options.miterClamp >= 1.0))
    throw invalidOption("The miter clamp must be at least 1, got " + std::to_string(options.miterClamp) +
                        ".");
  if (!(options.precisionGrid > 0.0))
    throw invalidOption("The precision grid must be positive, got " + std::to_string(options.precisionGrid) +
                        ".");
  if (!(options.curbReturnRadius >= 0.0) || options.curbReturnSegments < 1)
    throw invalidOption("Curb returns need a radius of 0 or more and at least one chord, got " +
                        std::to_string(options.curbReturnRadius) + " cells and " +
                        std::to_string(options.curbReturnSegments) + " chords.");

  const int nodeCount = static_cast<int>(network.nodes.size());
  std::vector<LineString> lines(network.segments.size());
  for (size_t s = 0; s < network.segments.size(); ++s) {
    const NetworkSegment& seg = network.segments[s];
    if (seg.points.size() < 2)
      throw invalidInput("Road segment " + std::to_string(s) + " has fewer than two points.");
    if (seg.fromNode < 0 || seg.fromNode >= nodeCount || seg.toNode < 0 || seg.toNode >= nodeCount)
      throw invalidInput("Road segment " + std::to_string(s) + " references a node that does not exist (" +
                         std::to_string(seg.fromNode) + ", " + std::to_string(seg.toNode) + " of " +
                         std::to_string(nodeCount) + " nodes).");
    for (const Vec2& p : seg.points)
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw invalidInput("Road segment " + std::to_string(s) + " has a non-finite coordinate.");
    if (seg.roadClass != RoadClass::Perimeter) lines[s] = withoutRepeats(seg.points);
  }

  geos::Context ctx;
  const GeosWorkers workers(options.threads);  // outlives `raw`, which ends up holding their geometries
  const double grid = options.precisionGrid;
  RoadGeometry out;
  std::vector<RawPiece> raw;
  const Progress build = subProgress(progress, 0.0, 0.5);
  ProgressTicker ticker(build, "road geometry", network.segments.size() + 1);

  // Arms per node, from every road segment with a direction.
  std::vector<std::vector<Arm>> arms(network.nodes.size());
  for (size_t s = 0; s < network.segments.size(); ++s) {
    const LineString& line = lines[s];
    if (line.size() < 2) continue;
    const NetworkSegment& seg = network.segments[s];
    const double w = halfWidthOf(seg.roadClass, options);
    const Vec2 startDir = unit(line[1] - line[0]);
    const Vec2 endDir = unit(line[line.size() - 2] - line.back());
    arms[seg.fromNode].push_back({static_cast<int>(s), 0, startDir, w, azimuthOf(startDir), seg.roadClass,
                                  distance(line[0], line[1])});
    arms[seg.toNode].push_back({static_cast<int>(s), 1, endDir, w, azimuthOf(endDir), seg.roadClass,
                                distance(line.back(), line[line.size() - 2])});
  }

  // Junction and cul-de-sac pieces first: they win every overlap.
  for (size_t node = 0; node < arms.size(); ++node) {
    std::vector<Arm>& here = arms[node];
    if (here.empty()) continue;
    const Vec2 at = here[0].end == 0 ? lines[here[0].segment].front() : lines[here[0].segment].back();
    if (here.size() == 1) {
      if (here[0].roadClass != RoadClass::Secondary) continue;  // primary dead ends keep a flat cap
      Polygon oct = octagon(at, here[0].dir * -1.0, options.culDeSacCircumradius);
      raw.push_back(
          {ctx.polygon(oct), PavementKind::CulDeSac, RoadClass::Secondary, -1, static_cast<int>(node)});
      continue;
    }
    std::stable_sort(here.begin(), here.end(),
                     [](const Arm& a, const Arm& b) { return a.azimuth < b.azimuth; });
    std::vector<Vec2> hullPoints{at};
    std::vector<Vec2> ordered;  // the documented polygon: corners and end vertices in clockwise order
    std::vector<Polygon> returns;
    RoadClass cls = RoadClass::Secondary;
    for (size_t i = 0; i < here.size(); ++i) {
      const Arm& a = here[i];
      const Arm& b = here[(i + 1) % here.size()];
      if (a.roadClass == RoadClass::Primary) cls = RoadClass::Primary;
      double gap = b.azimuth - a.azimuth;
      if (gap < 0.0) gap += 2.0 * kPi;
      const Vec2 endRightA = at + rightNormal(a.dir) * a.halfWidth;
      const Vec2 endLeftB = at + leftNormal(b.dir) * b.halfWidth;
      Vec2 corner;
      if (!curbCorner(at, a.dir, a.halfWidth, b.dir, b.halfWidth, options.parallelSinEpsilon, corner)) {
        // Parallel pair: an edge between the two curb end vertices instead of a corner.
        ordered.push_back(endRightA);
        ordered.push_back(endLeftB);
        hullPoints.push_back(endRightA);
        hullPoints.push_back(endLeftB);
        continue;
      }
      const double limit = options.miterClamp * std::max(a.halfWidth, b.halfWidth);
      if (distance(corner, at) > limit) {
        // A very sharp pair: cut the corner on both curbs at the clamp distance.
        const double ta = std::clamp(dot(corner - endRightA, a.dir), -limit, limit);
        const double tb = std::clamp(dot(corner - endLeftB, b.dir), -limit, limit);
        corner = endRightA + a.dir * ta;
        const Vec2 cornerB = endLeftB + b.dir * tb;
        ordered.push_back(corner);
        ordered.push_back(cornerB);
        hullPoints.push_back(corner);
        hullPoints.push_back(cornerB);
      } else {
        ordered.push_back(corner);
        hullPoints.push_back(corner);
        if (gap < kPi) {
          const double maxTangent = std::min({limit, a.firstLinkLength, b.firstLinkLength});
          Polygon r = curbReturn(corner, a.dir, b.dir, gap, options.curbReturnRadius, maxTangent,
                                 options.curbReturnSegments);
          if (!r.outer.empty()) returns.push_back(std::move(r));
        }
      }
      // A reflex gap puts the corner behind the node; the end vertices keep the hull over the
      // wedge between the two flat segment ends.
      if (gap > kPi) {
        hullPoints.push_back(endRightA);
        hullPoints.push_back(endLeftB);
      }
    }
    geos::GeomPtr hull = convexHullOf(ctx, hullPoints);
    if (GEOSGeomTypeId_r(ctx.handle(), hull.get()) != GEOS_POLYGON) continue;  // degenerate: width step only
    if (!isConvexPolygon(ordered)) ++out.convexHullFallbacks;
    raw.push_back({std::move(hull), PavementKind::Intersection, cls, -1, static_cast<int>(node)});
    for (const Polygon& r : returns)
      raw.push_back({ctx.polygon(r), PavementKind::Intersection, cls, -1, static_cast<int>(node)});
  }
  ticker.tick();

  // Segment strips, primary before secondary.
  std::vector<size_t> order;
  for (size_t s = 0; s < lines.size(); ++s)
    if (lines[s].size() >= 2) order.push_back(s);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return (network.segments[a].roadClass == RoadClass::Primary) >
           (network.segments[b].roadClass == RoadClass::Primary);
  });
  for (size_t s : order) {
    const NetworkSegment& seg = network.segments[s];
    const double w = halfWidthOf(seg.roadClass, options);
    const LineString& line = lines[s];
    raw.push_back({segmentPavement(ctx, line, w, options.miterClamp), PavementKind::Segment, seg.roadClass,
                   static_cast<int>(s), -1});
    for (double side : {1.0, -1.0}) {
      LineString curb;
      for (size_t i = 0; i < line.size(); ++i)
        curb.push_back(curbVertex(line, i, w, side, options.miterClamp));
      out.curbs.push_back(std::move(curb));
    }
    ticker.tick();
  }

  // Overlap resolution: every piece loses what higher-priority pieces already cover, on the faces of one
  // snap-rounded arrangement of all pieces (resolveOverlaps). Snap rounding keeps a tiled run's pieces
  // equal to the single run's, which floating overlays did not (issue 21, round 4).
  const Progress resolve = subProgress(progress, 0.5, 1.0);
  reportProgress(resolve, 0.0, "road geometry overlaps");
  {
    std::vector<geos::GeomPtr> snapped(raw.size());
    workers.run(raw.size(), [&](size_t i, size_t, const geos::Context& c) {
      snapped[i] = snapToGrid(c, raw[i].geom.get(), grid);
    });
    for (size_t i = 0; i < raw.size(); ++i) raw[i].geom = std::move(snapped[i]);
  }
  std::vector<PavementPiece> resolved =
      resolveOverlaps(ctx, workers, raw, grid, options.overlapRegion, resolve);
  for (PavementPiece& piece : resolved)
    if (!piece.shape.empty()) out.pieces.push_back(std::move(piece));
  return out;
}

}  // namespace urbanvec::vectorize
