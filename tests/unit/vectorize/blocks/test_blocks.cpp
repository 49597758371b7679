// Stages D1-D5 (blocks) on hand-made networks with exact answers (the vectorizer spec §11.3-11.4),
// and the invariant checker.
#include "../network_fixtures.hpp"

// ---- D1 ----

TEST(BlockOutline, OrientedBoxOfARotatedRectangle) {
  const double a = 0.5236;  // 30 degrees
  const Vec2 u{std::cos(a), std::sin(a)}, v{-std::sin(a), std::cos(a)};
  Polygon rect{{u * 0 + v * 0, u * 6, u * 6 + v * 2, v * 2, {0, 0}}, {}};
  const OrientedBox obb = orientedBoundingBox(rect);
  EXPECT_NEAR(obb.length, 6.0, 1e-9);
  EXPECT_NEAR(obb.width, 2.0, 1e-9);
  EXPECT_NEAR(obb.aspect, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(obb.diagonal, std::sqrt(40.0), 1e-9);
  EXPECT_NEAR(std::fabs(dot(obb.axis, u)), 1.0, 1e-9);
  const OrientedBox square = orientedBoundingBox(box(3, 3, 7, 7));
  EXPECT_NEAR(square.aspect, 1.0, 1e-9);
  EXPECT_NEAR(square.diagonal, std::sqrt(32.0), 1e-9);
  EXPECT_NEAR(orientedBoundingBox(box(0, 0, 1, 3)).aspect, 1.0 / 3.0, 1e-9);  // oblong for D6 (< 1:2)
}

// ---- Pipeline on small grids ----

namespace {

/// Four secondary streets in a # shape on a 16 x 16 grid: centrelines x = 2.5, 12.5 and
/// y = 3.5, 13.5 (cells col 2, 12 and row 12, 2); the one enclosed block is x in [3, 12], y in [4, 13].
RoadNetwork hashNetwork() {
  NetworkBuilder b;
  for (double y : {3.5, 13.5}) b.chain({{0.5, y}, {2.5, y}, {12.5, y}, {15.5, y}}, RoadClass::Secondary);
  for (double x : {2.5, 12.5}) b.chain({{x, 0.5}, {x, 3.5}, {x, 13.5}, {x, 15.5}}, RoadClass::Secondary);
  return b.finish();
}

LandUse hashLandUse(int c, int r) {
  if (c == 2 || c == 12 || r == 2 || r == 12) return LandUse::SecondaryRoad;
  if (c > 2 && c < 12 && r > 2 && r < 12) return LandUse::Residential;
  return LandUse::Unused;
}

/// Area a default curb return takes from a 90° block corner: the r x r square minus the polygonal
/// quarter disc of `curbReturnSegments` chords.
double curbReturnArea() {
  const RoadGeometryOptions o;
  const double r = o.curbReturnRadius;
  return r * r -
         o.curbReturnSegments * 0.5 * r * r * std::sin(3.14159265358979323846 / 2.0 / o.curbReturnSegments);
}

std::vector<const BlockInfo*> blocksOfKind(const BlocksResult& r, bool internal) {
  std::vector<const BlockInfo*> out;
  for (const BlockInfo& b : r.blockInfo)
    if (b.internal == internal) out.push_back(&b);
  return out;
}

BlocksCheckReport check(const BlocksResult& r, const TestCity& t) {
  BlocksCheckInput in;
  in.pavement = &r.pavement;
  in.blocks = &r.blocks;
  in.water = &r.water;
  in.perimeter = r.perimeter;
  in.cellSize = t.spec.transform.cellSize();
  in.failsafeUses = r.stats.failsafeUses;
  in.simulatedBlocks = r.stats.simulatedBlocks;
  return checkBlocks(in);
}

}  // namespace

TEST(BlocksPipeline, SquareBlockBetweenFourRoadsIsOneInternalBlock) {
  const TestCity t = makeCity(16, 16, hashLandUse);
  const BlocksResult r = vectorizeBlocks(hashNetwork(), t.city, t.spec);
  const auto internal = blocksOfKind(r, true);
  ASSERT_EQ(internal.size(), 1u);
  EXPECT_NEAR(internal[0]->areaCells, 81.0 - 4 * curbReturnArea(), 1e-6);
  EXPECT_NEAR(std::get<double>(r.blocks.features[0].values[3]), (81.0 - 4 * curbReturnArea()) * 144.0,
              1e-3);  // m^2
  EXPECT_NEAR(internal[0]->obb.aspect, 1.0, 1e-9);
  EXPECT_NEAR(internal[0]->obbDiagonal, 9.0 * std::sqrt(2.0) * 12.0, 1e-6);
  ASSERT_EQ(internal[0]->simBlockIds.size(), 1u);
  EXPECT_EQ(internal[0]->simBlockIds[0], t.city.blocks[0].id);
  EXPECT_EQ(r.matching.rule[0], MatchRule::Centre);
  EXPECT_EQ(r.stats.failsafeUses, 0);
  // World frame: the block spans columns 3..12 and rows 3..12 of the geotransform.
  const Polygon& world = std::get<Polygon>(r.blocks.features[0].geometry);
  double minX = 1e300, maxY = -1e300;
  for (const Vec2& p : world.outer) {
    minX = std::min(minX, p.x);
    maxY = std::max(maxY, p.y);
  }
  EXPECT_NEAR(minX, 500000.0 + 3 * 12.0, 1e-6);
  EXPECT_NEAR(maxY, 4000000.0 - 3 * 12.0, 1e-6);
  EXPECT_LT(signedArea(world.outer), 0.0);  // clockwise
  const BlocksCheckReport c = check(r, t);
  EXPECT_TRUE(qualityFailures(c).empty()) << qualityFailures(c).front();
  EXPECT_EQ(r.blocks.fieldIndex("has_spine"), 4);
  EXPECT_EQ(r.pavement.fields[1].name, "kind");
}

TEST(BlocksPipeline, ALakeAcrossABlockSplitsItAndAPondMakesAHole) {
  // Water row 7 across the whole block: two simulated blocks, two vector blocks of 4 x 9 cells.
  const TestCity t = makeCity(16, 16, [](int c, int r) {
    if (r == 7 && c > 2 && c < 12) return LandUse::Water;
    return hashLandUse(c, r);
  });
  ASSERT_EQ(t.city.blocks.size(), 2u);
  const BlocksResult r = vectorizeBlocks(hashNetwork(), t.city, t.spec);
  const auto internal = blocksOfKind(r, true);
  ASSERT_EQ(internal.size(), 2u);
  EXPECT_NEAR(internal[0]->areaCells, 36.0 - 2 * curbReturnArea(), 1e-6);
  EXPECT_NEAR(internal[1]->areaCells, 36.0 - 2 * curbReturnArea(), 1e-6);
  EXPECT_EQ(r.stats.waterSplitBlocks, 1);
  ASSERT_EQ(r.matching.rule.size(), 2u);
  EXPECT_EQ(r.matching.rule[0], MatchRule::WaterSplit);
  EXPECT_EQ(r.matching.rule[1], MatchRule::WaterSplit);
  EXPECT_NE(r.matching.vectorBlockOfSim[0], r.matching.vectorBlockOfSim[1]);
  ASSERT_EQ(r.water.features.size(), 1u);
  const BlocksCheckReport c = check(r, t);
  EXPECT_EQ(c.invalidPolygons, 0);
  EXPECT_LE(c.blockWaterOverlapArea + c.blockPavementOverlapArea, 1e-6 * c.blockArea);
  EXPECT_LE(c.tilingGapArea + c.tilingExcessArea, 1e-6 * c.perimeterArea);

  // A one-cell pond in the middle: the block keeps one piece with a smoothed hole.
  const TestCity pond = makeCity(16, 16, [](int c, int r) {
    if (r == 7 && c == 7) return LandUse::Water;
    return hashLandUse(c, r);
  });
  const BlocksResult rp = vectorizeBlocks(hashNetwork(), pond.city, pond.spec);
  const auto one = blocksOfKind(rp, true);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0]->shape.holes.size(), 1u);
  EXPECT_GT(one[0]->areaCells, 80.0);
  EXPECT_LT(one[0]->areaCells, 81.0 - 4 * curbReturnArea() - 0.25);
  const BlocksCheckReport cp = check(rp, pond);
  EXPECT_TRUE(qualityFailures(cp).empty()) << qualityFailures(cp).front();
}

TEST(BlocksPipeline, ExternalBlockFromBoundaryLineAndTrappedLineDeleted) {
  // A secondary loop around x, y in [2.5, 9.5] on a 20 x 12 grid, developed external land east of it
  // (x in [10, 15], y in [3, 9]) closed by a boundary line, and a boundary line trapped inside the loop.
  NetworkBuilder b;
  b.chain({{2.5, 2.5},
           {9.5, 2.5},
           {9.5, 3.5},
           {9.5, 8.5},
           {9.5, 9.5},
           {2.5, 9.5},
           {2.5, 6.5},
           {2.5, 5.5},
           {2.5, 2.5}},
          RoadClass::Secondary);
  b.polyline({{9.5, 3.5}, {10, 3}, {15, 3}, {15, 9}, {10, 9}, {9.5, 8.5}}, RoadClass::Perimeter);
  b.polyline({{2.5, 5.5}, {4, 5.5}, {4, 6.5}, {2.5, 6.5}}, RoadClass::Perimeter);
  const TestCity t = makeCity(20, 12, [](int c, int r) {
    const bool loop = (c == 2 || c == 9) && r >= 2 && r <= 9;
    const bool loopRow = (r == 2 || r == 9) && c >= 2 && c <= 9;
    if (loop || loopRow) return LandUse::SecondaryRoad;
    if (c > 2 && c < 9 && r > 2 && r < 9) return LandUse::Residential;
    if (c >= 10 && c <= 14 && r >= 3 && r <= 8) return LandUse::Commercial;
    return LandUse::Unused;
  });
  ASSERT_EQ(t.city.blocks.size(), 2u);
  ASSERT_FALSE(t.city.blocks[1].internal);
  BlocksOptions raw;  // unsmoothed boundary lines give the exact external block
  raw.external.boundarySmoothingPasses = 0;
  const RoadNetwork net = b.finish();
  const BlocksResult r = vectorizeBlocks(net, t.city, t.spec, raw);
  EXPECT_EQ(r.stats.boundaryLines, 2);
  EXPECT_EQ(r.stats.deletedBoundaryLines, 1);
  const auto internal = blocksOfKind(r, true);
  const auto external = blocksOfKind(r, false);
  ASSERT_EQ(internal.size(), 1u);
  ASSERT_EQ(external.size(), 1u);
  EXPECT_NEAR(internal[0]->areaCells, 36.0 - 4 * curbReturnArea(), 1e-6);
  EXPECT_NEAR(external[0]->areaCells, 30.0, 1e-6);
  ASSERT_EQ(external[0]->simBlockIds.size(), 1u);
  EXPECT_EQ(external[0]->simBlockIds[0], t.city.blocks[1].id);
  EXPECT_EQ(r.stats.failsafeUses, 0);
  BlocksCheckReport c = check(r, t);
  EXPECT_EQ(c.invalidPolygons, 0);
  EXPECT_LE(c.tilingGapArea, 1e-6 * c.perimeterArea);
  EXPECT_GT(c.squareTurnShare, 0.05);  // the raw staircase corners of the boundary line
  // Smoothed boundary lines (default) round the far corners of the external block.
  const BlocksResult smooth = vectorizeBlocks(net, t.city, t.spec);
  const auto smoothExternal = blocksOfKind(smooth, false);
  ASSERT_EQ(smoothExternal.size(), 1u);
  EXPECT_GT(smoothExternal[0]->areaCells, 29.0);
  EXPECT_LT(smoothExternal[0]->areaCells, 30.0 - 1e-3);
  c = check(smooth, t);
  EXPECT_TRUE(qualityFailures(c).empty()) << qualityFailures(c).front();
}

TEST(ExternalBlocks, StraightBoundaryLineBetweenTwoDeadEndsIsKeptAndAnIslandGetsItsBlock) {
  // A secondary loop (x, y in [2.5, 9.5]) with two dead ends running east along y = 2.5 and y = 9.5
  // to x = 15.5. Developed land between them (x in [10, 15], y in [3, 9]) is closed on the east by a
  // straight boundary line from one dead end to the other: two points, both in the pavement of the
  // culs-de-sac, the line between them in the open. A 2 x 2 commercial island stands in open land.
  NetworkBuilder b;
  b.chain({{2.5, 2.5}, {9.5, 2.5}, {9.5, 9.5}, {2.5, 9.5}, {2.5, 2.5}}, RoadClass::Secondary);
  b.chain({{9.5, 2.5}, {12.5, 2.5}, {15.5, 2.5}}, RoadClass::Secondary);
  b.chain({{9.5, 9.5}, {12.5, 9.5}, {15.5, 9.5}}, RoadClass::Secondary);
  b.polyline({{15.5, 2.5}, {15.5, 9.5}}, RoadClass::Perimeter);
  const TestCity t = makeCity(20, 12, [](int c, int r) {
    const bool loop = (c == 2 || c == 9) && r >= 2 && r <= 9;
    const bool rows = (r == 2 || r == 9) && c >= 2 && c <= 15;
    if (loop || rows) return LandUse::SecondaryRoad;
    if (c > 2 && c < 9 && r > 2 && r < 9) return LandUse::Residential;
    if (c >= 10 && c <= 14 && r >= 3 && r <= 8) return LandUse::Commercial;
    if (c >= 17 && c <= 18 && r >= 5 && r <= 6) return LandUse::Commercial;
    return LandUse::Unused;
  });
  ASSERT_EQ(t.city.blocks.size(), 3u);
  const RoadNetwork net = b.finish();
  const BlocksResult r = vectorizeBlocks(net, t.city, t.spec);
  EXPECT_EQ(r.stats.deletedBoundaryLines, 0);
  const auto external = blocksOfKind(r, false);
  ASSERT_EQ(external.size(), 2u);
  // The block between the dead ends: 5.5 x 6 cells less the dead ends' culs-de-sac.
  EXPECT_GT(external[0]->areaCells, 28.0);
  EXPECT_LT(external[0]->areaCells, 33.0);
  ASSERT_EQ(external[0]->simBlockIds.size(), 1u);
  EXPECT_EQ(external[0]->simBlockIds[0], t.city.blocks[1].id);
  // The island: its 2 x 2 cells with smoothed corners.
  EXPECT_GT(external[1]->areaCells, 3.0);
  EXPECT_LT(external[1]->areaCells, 4.0);
  ASSERT_EQ(external[1]->simBlockIds.size(), 1u);
  EXPECT_EQ(external[1]->simBlockIds[0], t.city.blocks[2].id);
  EXPECT_EQ(r.stats.failsafeUses, 0);
  const BlocksCheckReport c = check(r, t);
  EXPECT_EQ(c.invalidPolygons, 0);
  EXPECT_LE(c.blockPavementOverlapArea, 1e-6 * c.blockArea);
  // Without island blocks the island's parcel goes to the failsafe.
  BlocksOptions noIslands;
  noIslands.external.islandBlocks = false;
  const BlocksResult n = vectorizeBlocks(net, t.city, t.spec, noIslands);
  EXPECT_EQ(blocksOfKind(n, false).size(), 1u);
  EXPECT_EQ(n.stats.failsafeUses, 1);
}

TEST(ExternalBlocks, AGridWithoutRoadsIsOneIslandBlock) {
  // Issue 15: a grid of developed land without any road gives no pavement and no boundary line; its
  // one external simulated block is an island and still gets its block, the whole grid with
  // smoothed corners.
  const TestCity t = makeCity(6, 5, [](int, int) { return LandUse::Residential; });
  ASSERT_EQ(t.city.blocks.size(), 1u);
  const RoadNetwork none;
  const BlocksResult r = vectorizeBlocks(none, t.city, t.spec);
  ASSERT_EQ(r.blockInfo.size(), 1u);
  EXPECT_FALSE(r.blockInfo[0].internal);
  EXPECT_GT(r.blockInfo[0].areaCells, 28.0);
  EXPECT_LT(r.blockInfo[0].areaCells, 30.0);
  ASSERT_EQ(r.blockInfo[0].simBlockIds.size(), 1u);
  EXPECT_EQ(r.blockInfo[0].simBlockIds[0], t.city.blocks[0].id);
  EXPECT_EQ(r.stats.failsafeUses, 0);
  EXPECT_EQ(r.pavement.features.size(), 0u);
  // Open land only: no block, and nothing breaks.
  const TestCity open = makeCity(6, 5, [](int, int) { return LandUse::Unused; });
  EXPECT_EQ(vectorizeBlocks(none, open.city, open.spec).blockInfo.size(), 0u);
}

TEST(ExternalBlocks, TrappedLineRuleNeedsBothEndsAndMoreThanHalf) {
  EXPECT_TRUE(boundaryLineTrappedInside({true, false, true, true, true}, 0.5));
  EXPECT_FALSE(boundaryLineTrappedInside({true, false, false, true}, 0.5));  // exactly 50%
  EXPECT_FALSE(boundaryLineTrappedInside({false, true, true, true, true}, 0.5));
  EXPECT_FALSE(boundaryLineTrappedInside({}, 0.5));
}

namespace {

/// A 3 x 3 lattice on a 24 x 24 grid: secondary streets x = 4.5, 19.5 and y = 4.5, 12.5, 19.5, a
/// primary avenue on x = 12 (cells 11 and 12), and a dead-end stub from (8.5, 4.5) up to (8.5, 9.5).
RoadNetwork latticeNetwork() {
  NetworkBuilder b;
  b.chain({{0.5, 4.5}, {4.5, 4.5}, {8.5, 4.5}, {12, 4.5}, {19.5, 4.5}, {23.5, 4.5}}, RoadClass::Secondary);
  for (double y : {12.5, 19.5})
    b.chain({{0.5, y}, {4.5, y}, {12, y}, {19.5, y}, {23.5, y}}, RoadClass::Secondary);
  for (double x : {4.5, 19.5})
    b.chain({{x, 0.5}, {x, 4.5}, {x, 12.5}, {x, 19.5}, {x, 23.5}}, RoadClass::Secondary);
  b.chain({{12, 0.5}, {12, 4.5}, {12, 12.5}, {12, 19.5}, {12, 23.5}}, RoadClass::Primary);
  b.chain({{8.5, 4.5}, {8.5, 9.5}}, RoadClass::Secondary);
  return b.finish();
}

TestCity latticeCity() {
  return makeCity(24, 24, [](int c, int r) {
    if (c == 11 || c == 12) return LandUse::PrimaryRoad;
    if (c == 4 || c == 19 || r == 19 || r == 11 || r == 4) return LandUse::SecondaryRoad;
    if (c == 8 && r >= 14 && r <= 18) return LandUse::SecondaryRoad;
    if (c > 4 && c < 19 && r > 4 && r < 19) return LandUse::Residential;
    return LandUse::Unused;
  });
}

}  // namespace

TEST(BlocksChecker, LatticeWithAvenueAndDeadEndTilesWithoutOverlaps) {
  const TestCity t = latticeCity();
  ASSERT_EQ(t.city.blocks.size(), 4u);
  const BlocksResult r = vectorizeBlocks(latticeNetwork(), t.city, t.spec);
  const auto internal = blocksOfKind(r, true);
  ASSERT_EQ(internal.size(), 4u);
  int pierced = 0;
  for (const BlockInfo* b : internal) pierced += b->hasCulDeSac ? 1 : 0;
  EXPECT_EQ(pierced, 1);
  EXPECT_EQ(r.stats.matchedSimulatedBlocks, 4);
  EXPECT_EQ(r.stats.failsafeUses, 0);
  std::set<int> matched(r.matching.vectorBlockOfSim.begin(), r.matching.vectorBlockOfSim.end());
  EXPECT_EQ(matched.size(), 4u);  // one vector block per simulated block
  const BlocksCheckReport c = check(r, t);
  EXPECT_EQ(c.invalidPolygons, 0);
  EXPECT_LE(c.pavementOverlapArea, 1e-6 * c.pavementArea);
  EXPECT_LE(c.blockPavementOverlapArea, 1e-6 * c.blockArea);
  EXPECT_LE(c.tilingGapArea, 1e-6 * c.perimeterArea);
  EXPECT_GT(c.perimeterArea, 0.0);
  EXPECT_NEAR(c.pavementArea + c.blockArea, c.perimeterArea, 1e-6 * c.perimeterArea);
  EXPECT_TRUE(qualityFailures(c).empty()) << qualityFailures(c).front();

  // The same check without the saved perimeter derives it from pavement + internal blocks.
  BlocksCheckInput derived;
  derived.pavement = &r.pavement;
  derived.blocks = &r.blocks;
  EXPECT_NEAR(checkBlocks(derived).perimeterArea, c.perimeterArea, 1e-6 * c.perimeterArea);
}

TEST(BlocksChecker, DetectsOverlappingPavementAndMissingBlocks) {
  const TestCity t = latticeCity();
  BlocksResult r = vectorizeBlocks(latticeNetwork(), t.city, t.spec);
  BlocksResult overlapping = r;
  overlapping.pavement.features.push_back(overlapping.pavement.features.front());
  const BlocksCheckReport c1 = check(overlapping, t);
  EXPECT_NEAR(c1.pavementOverlapArea, area(std::get<Polygon>(r.pavement.features.front().geometry)), 1e-3);
  const auto failures = qualityFailures(c1);
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0].rfind("The pavement overlap share is", 0), 0u) << failures[0];

  BlocksResult missing = r;
  const double removed = std::get<double>(missing.blocks.features.front().values[3]);
  missing.blocks.features.erase(missing.blocks.features.begin());
  const BlocksCheckReport c2 = check(missing, t);
  EXPECT_NEAR(c2.tilingGapArea, removed, 1e-3);
  ASSERT_FALSE(qualityFailures(c2).empty());
  EXPECT_EQ(qualityFailures(c2)[0].rfind("The tiling gap share is", 0), 0u);

  // Truth blocks: the result's own blocks match themselves, a shifted copy does not.
  BlocksCheckInput in;
  in.pavement = &r.pavement;
  in.blocks = &r.blocks;
  in.cellSize = 12.0;
  in.truthBlocks = &r.blocks;
  EXPECT_DOUBLE_EQ(checkBlocks(in).truthMatchShare, 1.0);
  Layer shifted = r.blocks;
  for (Feature& f : shifted.features)
    for (Vec2& p : std::get<Polygon>(f.geometry).outer) p.x += 4 * 12.0;
  in.truthBlocks = &shifted;
  EXPECT_LT(checkBlocks(in).truthMatchShare, 0.9);
}

TEST(BlocksChecker, SquareTurnShareOfAGridStaircaseIsHigh) {
  Layer blocks;
  blocks.fields = {{"kind", FieldType::String}};
  Feature f;
  f.values = {std::string("internal")};
  f.geometry = Polygon{{{0, 0}, {0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}, {0, 0}}, {}};
  blocks.features.push_back(f);
  Layer pavement;
  BlocksCheckInput in;
  in.pavement = &pavement;
  in.blocks = &blocks;
  const BlocksCheckReport c = checkBlocks(in);
  EXPECT_EQ(c.outlineVertices, 6);
  EXPECT_DOUBLE_EQ(c.squareTurnShare, 1.0);
}

TEST(BlocksPipeline, DeterministicAndRejectsAMismatchedGrid) {
  const TestCity t = latticeCity();
  const BlocksResult a = vectorizeBlocks(latticeNetwork(), t.city, t.spec);
  const BlocksResult b = vectorizeBlocks(latticeNetwork(), t.city, t.spec);
  ASSERT_EQ(a.blocks.features.size(), b.blocks.features.size());
  ASSERT_EQ(a.pavement.features.size(), b.pavement.features.size());
  for (size_t i = 0; i < a.blocks.features.size(); ++i) {
    EXPECT_EQ(std::get<Polygon>(a.blocks.features[i].geometry).outer,
              std::get<Polygon>(b.blocks.features[i].geometry).outer);
    EXPECT_EQ(a.blocks.features[i].values, b.blocks.features[i].values);
  }
  for (size_t i = 0; i < a.pavement.features.size(); ++i)
    EXPECT_EQ(std::get<Polygon>(a.pavement.features[i].geometry).outer,
              std::get<Polygon>(b.pavement.features[i].geometry).outer);
  GridSpec wrong = t.spec;
  wrong.width = 10;
  try {
    vectorizeBlocks(latticeNetwork(), t.city, wrong);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "The land-use grid is 24 x 24 cells but the grid it belongs to is 10 x 24.");
  }
}

TEST(BlocksPipeline, ProgressIsMonotonicAndEndsAtOne) {
  const TestCity t = latticeCity();
  std::vector<double> seen;
  vectorizeBlocks(latticeNetwork(), t.city, t.spec, {}, [&](double f, std::string_view) {
    seen.push_back(f);
    return true;
  });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  EXPECT_THROW(
      vectorizeBlocks(latticeNetwork(), t.city, t.spec, {}, [](double, std::string_view) { return false; }),
      Cancelled);
}

namespace {

/// A messy network like part 1's output: an n x n lattice of streets `spacing` cells apart with nodes
/// every cell, smoothly jittered, every third street primary, diagonal roads making degree-6
/// intersections with 45° angles, dead ends leaving intersections 6° off a street (near-parallel
/// pairs), and tiny segments.
RoadNetwork messyNetwork(int n, double spacing, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0.0, 6.28);
  const double p1 = phase(rng), p2 = phase(rng), p3 = phase(rng);
  auto jitter = [&](Vec2 p) {
    return p + Vec2{0.7 * std::sin(p.y * 0.37 + p1) + 0.3 * std::sin(p.x * 0.9 + p3),
                    0.7 * std::sin(p.x * 0.41 + p2) + 0.3 * std::cos(p.y * 0.8 + p1)};
  };
  NetworkBuilder b;
  const double origin = 4.0;
  auto at = [&](int i, int j) { return jitter(Vec2{origin + i * spacing, origin + j * spacing}); };
  auto road = [&](Vec2 from, Vec2 to, Vec2 rawFrom, Vec2 rawTo, RoadClass cls) {
    LineString pts;
    const int steps = std::max(1, static_cast<int>(std::ceil(distance(rawFrom, rawTo))));
    for (int k = 0; k <= steps; ++k) pts.push_back(jitter(rawFrom + (rawTo - rawFrom) * (double(k) / steps)));
    pts.front() = from;
    pts.back() = to;
    b.polyline(pts, cls);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec2 raw{origin + i * spacing, origin + j * spacing};
      if (i + 1 < n)
        road(at(i, j), at(i + 1, j), raw, raw + Vec2{spacing, 0},
             j % 3 == 1 ? RoadClass::Primary : RoadClass::Secondary);
      if (j + 1 < n) road(at(i, j), at(i, j + 1), raw, raw + Vec2{0, spacing}, RoadClass::Secondary);
      if (i + 1 < n && j + 1 < n && (i * 7 + j * 3) % 5 == 0)
        road(at(i, j), at(i + 1, j + 1), raw, raw + Vec2{spacing, spacing}, RoadClass::Secondary);
      if (i + 1 < n && j + 1 < n && (i * 5 + j) % 7 == 3) {
        const Vec2 end = at(i, j) + Vec2{std::cos(0.105), std::sin(0.105)} * (spacing * 0.6);
        b.polyline({at(i, j), at(i, j) + Vec2{std::cos(0.105), std::sin(0.105)} * 1.5, end},
                   RoadClass::Secondary);
        b.polyline({end, end + Vec2{0.05, 0.08}}, RoadClass::Secondary);  // a tiny dead-end segment
      }
    }
  return b.finish();
}

}  // namespace

TEST(BlocksChecker, MessyNetworkKeepsEveryInvariant) {
  const int n = 12;
  const double spacing = 8.0;
  const int size = static_cast<int>(2 * 4 + (n - 1) * spacing + 2);
  const TestCity t = makeCity(size, size, [](int, int) { return LandUse::Unused; });
  for (std::uint64_t seed : {1u, 2u}) {
    const RoadNetwork net = messyNetwork(n, spacing, seed);
    const BlocksResult r = vectorizeBlocks(net, t.city, t.spec);
    const BlocksCheckReport c = check(r, t);
    EXPECT_EQ(c.invalidPolygons, 0);
    EXPECT_LE(c.pavementOverlapArea, 1e-6 * c.pavementArea);
    EXPECT_LE(c.blockPavementOverlapArea + c.blockBlockOverlapArea, 1e-6 * c.blockArea);
    EXPECT_LE(c.tilingGapArea + c.tilingExcessArea, 1e-6 * c.perimeterArea);
    EXPECT_LT(c.squareTurnShare, 0.05);
    // Every lattice cell not cut by a diagonal is one block; diagonals split theirs in two.
    EXPECT_GE(blocksOfKind(r, true).size(), size_t((n - 1) * (n - 1)));
  }
}

TEST(BlockOutline, FacesBelowTheMinimumAreaGoBackToThePavement) {
  NetworkBuilder b;
  for (double y : {3.5, 13.5}) b.chain({{0.5, y}, {2.5, y}, {12.5, y}, {15.5, y}}, RoadClass::Secondary);
  for (double x : {2.5, 12.5}) b.chain({{x, 0.5}, {x, 3.5}, {x, 13.5}, {x, 15.5}}, RoadClass::Secondary);
  RoadGeometry g = buildRoadGeometry(b.finish(), {});
  BlockOutlineOptions coarse;
  coarse.minBlockArea = 100.0;  // the 9 x 9 block counts as a sliver
  const BlockOutline outline = outlineBlocks(g.pieces, coarse);
  EXPECT_TRUE(outline.internalBlocks.empty());
  ASSERT_EQ(outline.slivers.size(), 1u);
  const double before = unionArea(g.pieces);
  EXPECT_EQ(absorbSlivers(g.pieces, outline.slivers, coarse.precisionGrid), 1);
  double sum = 0.0;
  for (const PavementPiece& p : g.pieces) sum += area(p.shape);
  EXPECT_NEAR(unionArea(g.pieces), before + area(outline.slivers), 1e-6);
  EXPECT_NEAR(sum, unionArea(g.pieces), 1e-6);  // still no overlap
  EXPECT_TRUE(outlineBlocks(g.pieces, coarse).slivers.empty());
}

TEST(BlockMatching, BlocksUnderPavementGoByCellOverlapOrStayUnmatchedWithoutParcels) {
  // Three one-cell simulated blocks on a 10 x 3 grid, none with its centre in a vector block: cell
  // (1, 1) overlaps the vector block [0, 1.3] x [0, 3] by 0.3 cell; cells (5, 1) and (8, 1) overlap
  // nothing, and only (8, 1) holds a parcel.
  SimulatedCity city;
  city.grid = Grid<LandUse>(10, 3, LandUse::Residential);
  Grid<int> blockOfCell(10, 3, -1);
  for (int col : {1, 5, 8}) {
    SimulatedBlock block;
    block.id = col;
    block.cells = {{col, 1}};
    block.centre = cellCentre({col, 1}, 3);
    blockOfCell.at(col, 1) = static_cast<int>(city.blocks.size());
    city.blocks.push_back(block);
  }
  city.blocks[2].parcelIds = {80};
  city.parcels.push_back({80, LandUse::Residential, {{8, 1}}, cellCentre({8, 1}, 3)});
  const std::vector<Polygon> vectorBlocks = {box(0, 0, 1.3, 3), box(6.2, 0, 6.8, 3)};
  const BlockMatching m = matchSimulatedBlocks(vectorBlocks, city, blockOfCell, {});
  EXPECT_EQ(m.vectorBlockOfSim[0], 0);
  EXPECT_EQ(m.rule[0], MatchRule::CellOverlap);
  EXPECT_EQ(m.vectorBlockOfSim[1], -1);
  EXPECT_EQ(m.rule[1], MatchRule::UnderPavement);
  EXPECT_EQ(m.vectorBlockOfSim[2], 1);  // nearest centroid
  EXPECT_EQ(m.rule[2], MatchRule::Failsafe);
  EXPECT_EQ(m.overlapUses, 1);
  EXPECT_EQ(m.underPavement, 1);
  EXPECT_EQ(m.failsafeUses, 1);
  // The documents' rules send all three to the failsafe.
  BlockMatchingOptions documentsOnly;
  documentsOnly.matchByCellOverlap = false;
  documentsOnly.leaveBlocksUnderPavement = false;
  EXPECT_EQ(matchSimulatedBlocks(vectorBlocks, city, blockOfCell, {}, {}, documentsOnly).failsafeUses, 3);
}

TEST(BlockMatching, CentreInASliverGivesWayToTheBlockHoldingMostCells) {
  // A simulated block: a 2-wide square ring (72 cells) and a 3x3 core (9 cells) in its middle. Its
  // centre lies in the core, which the roads cut off as a small vector block of its own.
  const int size = 13;
  SimulatedCity city;
  city.grid = Grid<LandUse>(size, size, LandUse::Residential);
  SimulatedBlock block;
  block.id = 1;
  Vec2 sum(0, 0);
  for (int r = 1; r <= 11; ++r)
    for (int c = 1; c <= 11; ++c) {
      const bool ring = c <= 2 || c >= 10 || r <= 2 || r >= 10;
      const bool core = c >= 5 && c <= 7 && r >= 5 && r <= 7;
      if (!ring && !core) continue;
      block.cells.push_back({c, r});
      sum += cellCentre({c, r}, size);
    }
  block.centre = sum * (1.0 / static_cast<double>(block.cells.size()));
  city.blocks.push_back(block);
  Grid<int> blockOfCell(size, size, -1);
  for (const GridCell& c : block.cells) blockOfCell.at(c.col, c.row) = 0;
  Polygon ring = box(0.5, 0.5, 12.5, 12.5);
  ring.holes.push_back(box(3.5, 3.5, 9.5, 9.5).outer);
  const std::vector<Polygon> vectorBlocks = {box(4, 4, 9, 9), ring};

  const BlockMatching m = matchSimulatedBlocks(vectorBlocks, city, blockOfCell, {});
  EXPECT_EQ(m.vectorBlockOfSim[0], 1);
  EXPECT_EQ(m.rule[0], MatchRule::Majority);
  EXPECT_EQ(m.majorityUses, 1);
  // The documents' centre rule alone keeps the sliver.
  BlockMatchingOptions documentsOnly;
  documentsOnly.minShareOfCells = 0.0;
  const BlockMatching d = matchSimulatedBlocks(vectorBlocks, city, blockOfCell, {}, {}, documentsOnly);
  EXPECT_EQ(d.vectorBlockOfSim[0], 0);
  EXPECT_EQ(d.rule[0], MatchRule::Centre);
}

TEST(WaterSplit, TallyCellsCountsTheCellCentresOfTheEvenOddInterior) {
  // Random rings (star-shaped outlines with many vertices, holes, long thin spikes) on a window of a
  // larger raster (frame offsets), against the even-odd crossing count of every cell centre.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int w = 40, h = 30;
  Grid<LandUse> landUse(w, h, LandUse::Residential);
  Grid<int> blockOfCell(w, h, -1);
  landUse.frameDx = blockOfCell.frameDx = 7;
  landUse.frameDy = blockOfCell.frameDy = 5;
  const LandUse uses[4] = {LandUse::Residential, LandUse::SecondaryRoad, LandUse::Water, LandUse::Unused};
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      landUse.at(c, r) = uses[rng() % 4];
      blockOfCell.at(c, r) = rng() % 3 == 0 ? -1 : static_cast<int>((c / 6) + 7 * (r / 5));
    }
  auto star = [&](Vec2 centre, double radius, int n) {
    Ring ring;
    for (int i = 0; i < n; ++i) {
      const double a = 6.283185307179586 * i / n;
      const double rr = radius * (i % 11 == 0 ? 1.0 : 0.3 + 0.7 * unit(rng));
      ring.push_back(centre + Vec2{std::cos(a), std::sin(a)} * rr);
    }
    ring.push_back(ring.front());
    return ring;
  };
  int nonEmpty = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec2 centre{7 + w * unit(rng), 5 + h * unit(rng)};
    Polygon p{star(centre, 4.0 + 25.0 * unit(rng), 5 + static_cast<int>(rng() % 300)), {}};
    for (int k = 0; k < trial % 3; ++k) p.holes.push_back(star(centre + Vec2{unit(rng), unit(rng)}, 3.0, 12));
    CellTally want;
    std::map<int, int> blocks;
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        const Vec2 centreOfCell{7 + c + 0.5, 5 + h - r - 0.5};
        bool inside = ringContains(p.outer, centreOfCell);
        for (const Ring& hole : p.holes) inside ^= ringContains(hole, centreOfCell);
        if (!inside) continue;
        ++want.cells;
        want.road += isRoad(landUse.at(c, r)) ? 1 : 0;
        want.water += landUse.at(c, r) == LandUse::Water ? 1 : 0;
        if (blockOfCell.at(c, r) >= 0) ++blocks[blockOfCell.at(c, r)];
      }
    const CellTally got = tallyCells(p, blockOfCell, landUse);
    EXPECT_EQ(got.cells, want.cells) << trial;
    EXPECT_EQ(got.road, want.road) << trial;
    EXPECT_EQ(got.water, want.water) << trial;
    const std::map<int, int> gotBlocks(got.blocks.begin(), got.blocks.end());
    EXPECT_EQ(gotBlocks, blocks) << trial;
    for (size_t k = 1; k < got.blocks.size(); ++k) EXPECT_GE(got.blocks[k - 1].second, got.blocks[k].second);
    nonEmpty += want.cells > 0 ? 1 : 0;
  }
  EXPECT_GT(nonEmpty, 20);
}
