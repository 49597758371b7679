// Stage C (pavement) on hand-made networks with exact answers (the vectorizer spec §11.3).
#include "../network_fixtures.hpp"

// ---- Stage C ----

TEST(RoadGeometry, TwoCrossingSecondaryRoadsGiveTheUnitSquare) {
  NetworkBuilder b;
  for (Vec2 end : {Vec2{4, 0}, Vec2{-4, 0}, Vec2{0, 4}, Vec2{0, -4}})
    b.chain({{0, 0}, end}, RoadClass::Secondary);
  const RoadGeometry g = buildRoadGeometry(b.finish(), {});
  const PavementPiece* p = pieceAtNode(g, 0, PavementKind::Intersection);
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->shape.size(), 1u);
  EXPECT_NEAR(area(p->shape[0]), 1.0, 1e-9);
  EXPECT_LT(signedArea(p->shape[0].outer), 0.0);  // clockwise (spec §11.3 check 21)
  EXPECT_EQ(cornerSet(p->shape[0].outer),
            (std::set<std::pair<long, long>>{{-500, -500}, {-500, 500}, {500, -500}, {500, 500}}));
  EXPECT_EQ(p->roadClass, RoadClass::Secondary);
}

TEST(RoadGeometry, PrimaryCrossingSecondaryGivesHalfByOneCorners) {
  NetworkBuilder b;
  b.chain({{0, 0}, {5, 0}}, RoadClass::Primary);
  b.chain({{0, 0}, {-5, 0}}, RoadClass::Primary);
  b.chain({{0, 0}, {0, 5}}, RoadClass::Secondary);
  b.chain({{0, 0}, {0, -5}}, RoadClass::Secondary);
  const RoadGeometry g = buildRoadGeometry(b.finish(), {});
  const PavementPiece* p = pieceAtNode(g, 0, PavementKind::Intersection);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(cornerSet(p->shape[0].outer),
            (std::set<std::pair<long, long>>{{-500, -1000}, {-500, 1000}, {500, -1000}, {500, 1000}}));
  EXPECT_EQ(p->roadClass, RoadClass::Primary);
  // Curbs: 1 cell off the primary centreline, 0.5 cell off the secondary one (pavement 2 and 1 wide).
  const Polygon eastWindow = box(2, -3, 4, 3), northWindow = box(-3, 2, 3, 4);
  EXPECT_NEAR(unionArea(g.pieces, &eastWindow), 2.0 * 2.0, 1e-9);
  EXPECT_NEAR(unionArea(g.pieces, &northWindow), 2.0 * 1.0, 1e-9);
}

TEST(RoadGeometry, CurbCornerIsRightOfAThenLeftOfBAndParallelPairsHaveNone) {
  Vec2 corner;
  ASSERT_TRUE(curbCorner({0, 0}, {0, 1}, 0.5, {1, 0}, 1.0, 0.05, corner));
  EXPECT_NEAR(corner.x, 0.5, 1e-12);
  EXPECT_NEAR(corner.y, 1.0, 1e-12);
  EXPECT_FALSE(curbCorner({0, 0}, {1, 0}, 1.0, {-1, 0.01}, 1.0, 0.05, corner));
}

TEST(RoadGeometry, TJunctionPavementIsTheUnionOfTheTwoCorridors) {
  NetworkBuilder b;
  b.chain({{0, 0}, {8, 0}}, RoadClass::Primary);
  b.chain({{0, 0}, {-8, 0}}, RoadClass::Primary);
  b.chain({{0, 0}, {0, 8}}, RoadClass::Secondary);
  RoadGeometryOptions sharp;  // the documents' sharp curb corners
  sharp.curbReturnRadius = 0.0;
  const RoadGeometry g = buildRoadGeometry(b.finish(), sharp);
  const PavementPiece* p = pieceAtNode(g, 0, PavementKind::Intersection);
  ASSERT_NE(p, nullptr);
  // North corners (±0.5, 1); the parallel E/W pair joins its south curb ends, both (0, -1).
  EXPECT_EQ(cornerSet(p->shape[0].outer),
            (std::set<std::pair<long, long>>{{-500, 1000}, {500, 1000}, {0, -1000}}));
  geos::Context ctx;
  std::vector<geos::GeomPtr> parts;
  double sumOfAreas = 0.0;
  for (const PavementPiece& piece : g.pieces) {
    parts.push_back(ctx.multiPolygon(piece.shape));
    sumOfAreas += area(piece.shape);
  }
  geos::GeomPtr pave = unionOnGrid(ctx, std::move(parts), 1e-9);
  EXPECT_NEAR(sumOfAreas, geosArea(ctx, pave.get()), 1e-9);  // pieces do not overlap
  std::vector<geos::GeomPtr> corridors;
  corridors.push_back(ctx.polygon(box(-3, -1, 3, 1)));
  corridors.push_back(ctx.polygon(box(-0.5, 0, 0.5, 3)));
  geos::GeomPtr expected = unionOnGrid(ctx, std::move(corridors), 1e-9);
  geos::GeomPtr window = ctx.polygon(box(-3, -3, 3, 3));
  geos::GeomPtr clipped = ctx.own(GEOSIntersection_r(ctx.handle(), pave.get(), window.get()), "clip");
  geos::GeomPtr diff = ctx.own(GEOSSymDifference_r(ctx.handle(), clipped.get(), expected.get()), "symdiff");
  EXPECT_LT(geosArea(ctx, diff.get()), 1e-9);
}

TEST(RoadGeometry, SecondaryDeadEndGetsAConvexOctagonCentredOnIt) {
  NetworkBuilder b;
  b.chain({{0, 0}, {3, 1}}, RoadClass::Secondary);  // a slanted dead-end road
  b.chain({{0, 0}, {-6, 0}}, RoadClass::Primary);   // primary dead end: flat cap, no octagon
  b.chain({{0, 0}, {0, 6}}, RoadClass::Secondary);
  const RoadNetwork net = b.finish();
  const RoadGeometry g = buildRoadGeometry(net, {});
  int octagons = 0;
  for (const PavementPiece& p : g.pieces) octagons += p.kind == PavementKind::CulDeSac ? 1 : 0;
  EXPECT_EQ(octagons, 2);  // the two secondary dead ends
  EXPECT_EQ(pieceAtNode(g, b.node({-6, 0}), PavementKind::CulDeSac), nullptr);
  const PavementPiece* p = pieceAtNode(g, b.node({3, 1}), PavementKind::CulDeSac);
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->shape.size(), 1u);
  const Ring ring = withoutStraightVertices(p->shape[0].outer);
  ASSERT_EQ(ring.size(), 9u);
  const Vec2 centre{3, 1};
  Vec2 sum;
  for (size_t i = 0; i + 1 < ring.size(); ++i) {
    EXPECT_NEAR(distance(ring[i], centre), 1.0, 1e-5);
    sum += ring[i];
    const double turn = cross(ring[i + 1] - ring[i], ring[(i + 2) % 8] - ring[i + 1]);
    EXPECT_GT(turn * signedArea(ring), 0.0) << "not convex at vertex " << i;
  }
  EXPECT_NEAR(distance(sum / 8.0, centre), 0.0, 1e-5);
  // One edge is perpendicular to the incoming link (direction (3, 1)).
  const Vec2 dir = Vec2{3, 1} / std::sqrt(10.0);
  bool perpendicularEdge = false;
  for (size_t i = 0; i + 1 < ring.size(); ++i)
    if (std::fabs(dot(ring[i + 1] - ring[i], dir)) < 1e-5) perpendicularEdge = true;
  EXPECT_TRUE(perpendicularEdge);
}

TEST(RoadGeometry, MalformedSegmentsAreInputErrors) {
  RoadNetwork net;
  net.nodes.push_back({{0, 0}, NetworkNodeKind::DeadEnd, 1});
  net.segments.push_back({{{0, 0}, {1, 0}}, RoadClass::Secondary, 0, 3});
  try {
    buildRoadGeometry(net, {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidInput);
    EXPECT_STREQ(e.what(), "Road segment 0 references a node that does not exist (0, 3 of 1 nodes).");
  }
  RoadGeometryOptions bad;
  bad.secondaryHalfWidth = 0.0;
  EXPECT_THROW(buildRoadGeometry(RoadNetwork{}, bad), Error);
}

TEST(RoadGeometry, SharpTurnsAndNearParallelPairsNeverOverlap) {
  NetworkBuilder b;
  // A degree-5 intersection with two arms 8 degrees apart, a hairpin and a tiny segment.
  const double deg = 3.14159265358979323846 / 180.0;
  for (double a : {0.0, 8.0, 100.0, 200.0, 290.0})
    b.chain({{0, 0}, {6 * std::sin(a * deg), 6 * std::cos(a * deg)}},
            a == 100.0 ? RoadClass::Primary : RoadClass::Secondary);
  b.polyline({{6 * std::sin(200 * deg), 6 * std::cos(200 * deg)}, {-4, -8}, {-1.5, -6.5}},
             RoadClass::Secondary);
  b.polyline({{-1.5, -6.5}, {-1.45, -6.48}}, RoadClass::Secondary);
  const RoadGeometry g = buildRoadGeometry(b.finish(), {});
  double sumOfAreas = 0.0;
  for (const PavementPiece& p : g.pieces) sumOfAreas += area(p.shape);
  EXPECT_NEAR(sumOfAreas, unionArea(g.pieces), 1e-6 * sumOfAreas);
  geos::Context ctx;
  for (const PavementPiece& p : g.pieces) {
    geos::GeomPtr geom = ctx.multiPolygon(p.shape);
    EXPECT_EQ(GEOSisValid_r(ctx.handle(), geom.get()), 1);
  }
}

TEST(RoadGeometry, FloatingOverlaysKeepCrossingsOffThePrecisionGrid) {
  // The water stages overlay in floating point: a crossing of two edges stays where it is, even
  // on a grid so coarse that snap rounding would move it to a whole number.
  geos::Context ctx;
  const geos::GeomPtr square = ctx.polygon(box(0, 0, 3, 3));
  const geos::GeomPtr wedge = ctx.polygon(Polygon{{{1, -1}, {2, 4}, {2, -1}}, {}});
  const double coarseGrid = 1.0;
  auto hasVertex = [](const MultiPolygon& shape, Vec2 v) {
    for (const Polygon& p : shape)
      for (const Vec2& q : p.outer)
        if (distance(q, v) < 1e-12) return true;
    return false;
  };
  const MultiPolygon cut =
      ctx.toPolygons(floatingDifference(ctx, square.get(), wedge.get(), coarseGrid).get());
  EXPECT_TRUE(hasVertex(cut, {1.2, 0.0}));
  EXPECT_TRUE(hasVertex(cut, {1.8, 3.0}));
  double cutArea = 0.0;
  for (const Polygon& p : cut) cutArea += area(p);
  EXPECT_NEAR(cutArea, 9.0 - 1.5, 1e-9);  // the wedge covers 0.8 to 0.2 of each row, 1.5 in all
  std::vector<geos::GeomPtr> parts;
  parts.push_back(ctx.polygon(box(0, 0, 3, 3)));
  parts.push_back(ctx.polygon(Polygon{{{1, -1}, {2, 4}, {2, -1}}, {}}));
  const MultiPolygon joined = ctx.toPolygons(floatingUnion(ctx, std::move(parts), coarseGrid).get());
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_TRUE(hasVertex(joined, {1.2, 0.0}));
  EXPECT_TRUE(hasVertex(joined, {1.8, 3.0}));
}
