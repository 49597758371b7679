// Stage C's pieces as a polygon coverage and D1's union of them by a boundary walk (issue 21, round 6).
#include <unordered_map>

#include "../network_fixtures.hpp"

namespace {

/// A lattice of secondary roads off the precision grid, two primary avenues, and one long slanted
/// primary road drawn as a single two-point segment that crosses the lattice without nodes: its strip's
/// long edges are snap-rounded through the hot pixels of every piece along them.
RoadNetwork latticeWithALongSlantedRoad() {
  NetworkBuilder b;
  const double step = 6.3, x0 = 0.137, y0 = -0.071;
  for (int i = 0; i <= 6; ++i) {
    std::vector<Vec2> row, column;
    for (int j = 0; j <= 6; ++j) {
      row.push_back({x0 + j * step, y0 + i * step});
      column.push_back({x0 + i * step, y0 + j * step});
    }
    b.chain(row, i == 3 ? RoadClass::Primary : RoadClass::Secondary);
    b.chain(column, i == 2 ? RoadClass::Primary : RoadClass::Secondary);
  }
  b.polyline({{-2.2, 1.7}, {40.9, 33.3}}, RoadClass::Primary);
  b.polyline({{x0 + 6 * step, y0}, {x0 + 7.5 * step, y0 - 2.0}, {x0 + 8 * step, y0 + 3.1}},
             RoadClass::Secondary);
  return b.finish();
}

struct Edge {
  Vec2 a, b;
};

std::vector<Edge> edgesOf(const std::vector<PavementPiece>& pieces) {
  std::vector<Edge> edges;
  for (const PavementPiece& piece : pieces)
    for (const Polygon& p : piece.shape) {
      std::vector<const Ring*> rings{&p.outer};
      for (const Ring& h : p.holes) rings.push_back(&h);
      for (const Ring* r : rings)
        for (size_t i = 0; i + 1 < r->size(); ++i) edges.push_back({(*r)[i], (*r)[i + 1]});
    }
  return edges;
}

/// Vertices of any piece lying inside an edge of another (not at its ends), within `tolerance`: where
/// two pieces meet without sharing that vertex.
int vertexOnEdgeCount(const std::vector<PavementPiece>& pieces, double tolerance) {
  std::unordered_map<long long, std::vector<Vec2>> bucket;
  auto key = [](long long x, long long y) { return x * 1000003LL + y; };
  for (const Edge& e : edgesOf(pieces))
    bucket[key(std::llround(std::floor(e.a.x)), std::llround(std::floor(e.a.y)))].push_back(e.a);
  int count = 0;
  for (const Edge& e : edgesOf(pieces)) {
    const long long xa = std::llround(std::floor(std::min(e.a.x, e.b.x))) - 1;
    const long long xb = std::llround(std::floor(std::max(e.a.x, e.b.x))) + 1;
    const long long ya = std::llround(std::floor(std::min(e.a.y, e.b.y))) - 1;
    const long long yb = std::llround(std::floor(std::max(e.a.y, e.b.y))) + 1;
    const Vec2 d = e.b - e.a;
    const double len2 = dot(d, d);
    for (long long x = xa; x <= xb; ++x)
      for (long long y = ya; y <= yb; ++y) {
        const auto it = bucket.find(key(x, y));
        if (it == bucket.end()) continue;
        for (const Vec2& v : it->second) {
          if (v == e.a || v == e.b) continue;
          const double t = dot(v - e.a, d) / len2;
          if (t <= 0.0 || t >= 1.0) continue;
          if (distance(e.a + d * t, v) < tolerance) ++count;
        }
      }
  }
  return count;
}

bool sameShapes(const std::vector<PavementPiece>& a, const std::vector<PavementPiece>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].kind != b[i].kind || a[i].segment != b[i].segment || a[i].node != b[i].node) return false;
    if (a[i].shape.size() != b[i].shape.size()) return false;
    for (size_t k = 0; k < a[i].shape.size(); ++k) {
      const Polygon &p = a[i].shape[k], &q = b[i].shape[k];
      if (p.outer != q.outer || p.holes != q.holes) return false;
    }
  }
  return true;
}

}  // namespace

TEST(PavementCoverage, PiecesMeetOnSharedVerticesAndTheirUnionIsTheWalkOfUnsharedEdges) {
  const RoadGeometry g = buildRoadGeometry(latticeWithALongSlantedRoad(), {});
  ASSERT_GT(g.pieces.size(), 100u);
  // Where two pieces meet, each has the other's vertices: no vertex lies inside another piece's edge.
  EXPECT_EQ(vertexOnEdgeCount(g.pieces, 1e-9), 0);
  MultiPolygon walked;
  ASSERT_TRUE(coverageUnion(g.pieces, walked));
  double sumOfAreas = 0.0;
  for (const PavementPiece& p : g.pieces) sumOfAreas += area(p.shape);
  EXPECT_NEAR(area(walked), sumOfAreas, 1e-9 * sumOfAreas);  // no overlaps
  geos::Context ctx;
  geos::GeomPtr mine = ctx.multiPolygon(walked);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), mine.get()), 1);
  std::vector<geos::GeomPtr> parts;
  for (const PavementPiece& p : g.pieces) parts.push_back(ctx.multiPolygon(p.shape));
  geos::GeomPtr overlay = unionOnGrid(ctx, std::move(parts), 1e-9);
  geos::GeomPtr diff = ctx.own(GEOSSymDifference_r(ctx.handle(), mine.get(), overlay.get()), "symdiff");
  EXPECT_LT(geosArea(ctx, diff.get()), 1e-9 * sumOfAreas);
  // The blocks: the lattice's 36 cells, less those the slanted road or the loop road cut or fill.
  size_t holes = 0;
  for (const Polygon& p : walked) holes += p.holes.size();
  EXPECT_GT(holes, 36u);
}

TEST(PavementCoverage, ResolvingByRegionGivesThePiecesOfOneRegion) {
  // Each region nodes its pieces with their neighbours and the neighbours' neighbours; with squares
  // smaller than one piece every piece's faces come from a different arrangement than in one square.
  const RoadNetwork net = latticeWithALongSlantedRoad();
  RoadGeometryOptions whole, small;
  whole.overlapRegion = 1e6;
  small.overlapRegion = 2.0;
  small.threads = 2;
  const RoadGeometry a = buildRoadGeometry(net, whole);
  const RoadGeometry b = buildRoadGeometry(net, small);
  EXPECT_TRUE(sameShapes(a.pieces, b.pieces));
}

TEST(PavementCoverage, WalkSplitsRingsWhereTheUnionTouchesItself) {
  // Unit squares of a 6 x 5 lattice, less four: two holes touching at a corner (a pinched block), a
  // hole touching the outer ring at a corner, plus a square touching the lattice at one corner only.
  std::vector<PavementPiece> pieces;
  auto add = [&](int x, int y) {
    PavementPiece p;
    Polygon sq = box(x, y, x + 1, y + 1);
    orientClockwise(sq);
    p.shape.push_back(sq);
    pieces.push_back(p);
  };
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 5; ++y)
      if (!((x == 1 && y == 1) || (x == 2 && y == 2) || (x == 4 && y == 3) || (x == 5 && y == 4))) add(x, y);
  add(6, -1);
  MultiPolygon walked;
  ASSERT_TRUE(coverageUnion(pieces, walked));
  geos::Context ctx;
  geos::GeomPtr mine = ctx.multiPolygon(walked);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), mine.get()), 1);
  EXPECT_NEAR(area(walked), 27.0, 1e-12);
  ASSERT_EQ(walked.size(), 2u);
  size_t holes = 0;
  for (const Polygon& p : walked) {
    EXPECT_LT(signedArea(p.outer), 0.0);
    for (const Ring& h : p.holes) {
      EXPECT_GT(signedArea(h), 0.0);
      EXPECT_NEAR(std::fabs(signedArea(h)), 1.0, 1e-12);
      ++holes;
    }
  }
  EXPECT_EQ(holes, 3u);
  // Overlapping pieces are not a coverage.
  pieces.push_back(pieces.front());
  EXPECT_FALSE(coverageUnion(pieces, walked));
}

TEST(PavementCoverage, WalkGivesAHoleToTheSmallestShellAroundIt) {
  // A frame of unit squares (0..7 around a 5 x 5 hole) and inside its hole a smaller frame (2..5 around
  // a one-cell hole): the inner hole belongs to the inner frame, not to the outer one around it.
  std::vector<PavementPiece> pieces;
  auto frame = [&](int lo, int hi) {
    for (int x = lo; x < hi; ++x)
      for (int y = lo; y < hi; ++y) {
        if (x > lo && x < hi - 1 && y > lo && y < hi - 1) continue;
        PavementPiece p;
        Polygon sq = box(x, y, x + 1, y + 1);
        orientClockwise(sq);
        p.shape.push_back(sq);
        pieces.push_back(p);
      }
  };
  frame(2, 5);  // the inner frame first, so its ring is not simply the last shell
  frame(0, 7);
  MultiPolygon walked;
  ASSERT_TRUE(coverageUnion(pieces, walked));
  ASSERT_EQ(walked.size(), 2u);
  for (const Polygon& p : walked) {
    ASSERT_EQ(p.holes.size(), 1u);
    const double shell = -signedArea(p.outer), hole = signedArea(p.holes[0]);
    EXPECT_NEAR(hole, shell > 20.0 ? 25.0 : 1.0, 1e-12);
  }
  geos::Context ctx;
  geos::GeomPtr mine = ctx.multiPolygon(walked);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), mine.get()), 1);
  EXPECT_NEAR(area(walked), 24.0 + 8.0, 1e-12);
}

TEST(PavementCoverage, WalkOrientsRingsAFewGridStepsWideFarFromTheOrigin) {
  // Faces of one grid step, 4000 cells out (a 4096² grid's far corner): the shoelace sum of absolute
  // coordinates rounds away their area, so the walk takes each ring's orientation about its first vertex.
  const double g = 1e-6;
  std::vector<Polygon> faces;
  const double y = 3999.654321, top = y + g;
  for (int k = 0; k < 8; ++k) {
    const double x = 4000.123456 + k * g, right = 4000.123456 + (k + 1) * g;
    faces.push_back(Polygon{{{x, y}, {right, y}, {right, top}, {x, y}}, {}});  // counter-clockwise
    faces.push_back(Polygon{{{x, y}, {x, top}, {right, top}, {x, y}}, {}});    // clockwise
  }
  std::vector<const Polygon*> parts;
  for (const Polygon& f : faces) parts.push_back(&f);
  MultiPolygon walked;
  ASSERT_TRUE(coverageUnion(parts, walked));
  ASSERT_EQ(walked.size(), 1u);
  EXPECT_TRUE(walked[0].holes.empty());
  EXPECT_EQ(walked[0].outer.size(), 19u);  // 8 steps along each long side, one along each short side, closed
}
