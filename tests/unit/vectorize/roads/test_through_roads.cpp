// Stage B7 (through roads and straight roads, issue 20) on hand-made graphs with known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "urbanvec/core/landuse.hpp"
#include "urbanvec/vectorize/roads/through_roads.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;

namespace {

/// Links the nodes in order and returns their ids.
std::vector<int> path(RoadGraph& g, const std::vector<Vec2>& points, int from = -1) {
  std::vector<int> ids;
  int prev = from;
  for (const Vec2& p : points) {
    const int id = g.addNode(p, NodeType::Secondary);
    if (prev >= 0) g.link(prev, id);
    ids.push_back(id);
    prev = id;
  }
  return ids;
}

/// Largest turn (degrees) along the nodes' current positions.
double largestTurn(const RoadGraph& g, const std::vector<int>& ids) {
  double worst = 0;
  for (std::size_t i = 1; i + 1 < ids.size(); ++i) {
    const Vec2 a = g.nodes[ids[i]].p - g.nodes[ids[i - 1]].p, b = g.nodes[ids[i + 1]].p - g.nodes[ids[i]].p;
    worst = std::max(worst, std::atan2(std::fabs(cross(a, b)), dot(a, b)) * 180 / M_PI);
  }
  return worst;
}

}  // namespace

TEST(ThroughRoads, DigitalLineBandIsHalfACellAlongTheGridAndSeventyOneHundredthsDiagonally) {
  EXPECT_DOUBLE_EQ(digitalLineBand({1, 0}), 0.5);
  EXPECT_NEAR(digitalLineBand({std::sqrt(0.5), std::sqrt(0.5)}), std::sqrt(0.5), 1e-12);
  // A 45-degree staircase of cell centres lies within the band of the diagonal; a cell off it not.
  EXPECT_TRUE(consistentWithSegment({{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {2.5, 1.5}, {2.5, 2.5}}, {0.5, 0.5},
                                    {2.5, 2.5}, 0.0));
  EXPECT_FALSE(consistentWithSegment({{0.5, 0.5}, {1.5, -0.5}, {2.5, 2.5}}, {0.5, 0.5}, {2.5, 2.5}, 0.25));
}

TEST(ThroughRoads, CrossingWithJoggedNodeBecomesTwoStraightRoadsThroughTheCrossing) {
  // An east-west and a north-south street on cell centres crossing at (0, 0); the crossing node and
  // its four neighbours were left jogged by smoothing (their placements, the cells, are exact).
  RoadGraph g;
  const int centre = g.addNode({0, 0}, NodeType::Secondary);
  std::vector<std::vector<int>> arms;
  for (const Vec2& d : {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)}) {
    std::vector<Vec2> points;
    for (int k = 1; k <= 8; ++k) points.push_back(d * static_cast<double>(k));
    arms.push_back(path(g, points, centre));
  }
  g.nodes[centre].p = {0.6, 0.4};
  g.nodes[arms[0][0]].p = {1.1, 0.45};
  g.nodes[arms[1][0]].p = {-0.9, 0.3};
  g.nodes[arms[2][0]].p = {0.5, 1.1};
  g.nodes[arms[3][0]].p = {0.4, -1.0};
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.pairs, 2u);
  EXPECT_EQ(s.nodesPlaced, 1u);
  EXPECT_NEAR(g.nodes[centre].p.x, 0.0, 1e-9);
  EXPECT_NEAR(g.nodes[centre].p.y, 0.0, 1e-9);
  for (int k : arms[0]) EXPECT_NEAR(g.nodes[k].p.y, 0.0, 1e-9);
  for (int k : arms[1]) EXPECT_NEAR(g.nodes[k].p.y, 0.0, 1e-9);
  for (int k : arms[2]) EXPECT_NEAR(g.nodes[k].p.x, 0.0, 1e-9);
  for (int k : arms[3]) EXPECT_NEAR(g.nodes[k].p.x, 0.0, 1e-9);

  // Off, the graph stays as B6 left it.
  RoadGraph untouched = g;
  untouched.nodes[centre].p = {0.6, 0.4};
  ThroughRoadOptions off;
  off.enabled = false;
  straightenThroughRoads(untouched, off);
  EXPECT_DOUBLE_EQ(untouched.nodes[centre].p.x, 0.6);
}

TEST(ThroughRoads, DiagonalStaircaseBetweenDeadEndsBecomesItsLine) {
  // A 4-connected staircase at 45 degrees through cell centres, smoothing having left it as it is.
  std::vector<Vec2> points{{0.5, 0.5}};
  for (int k = 0; k < 10; ++k) {
    points.push_back(points.back() + Vec2(1, 0));
    points.push_back(points.back() + Vec2(0, 1));
  }
  RoadGraph g;
  const std::vector<int> ids = path(g, points);
  EXPECT_GT(largestTurn(g, ids), 89.0);
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.straightChains, 1u);
  EXPECT_LT(largestTurn(g, ids), 1e-6);
  for (int k : ids) EXPECT_NEAR(g.nodes[k].p.x - g.nodes[k].p.y, 0.0, 1e-9);
}

TEST(ThroughRoads, StaircaseOffItsFittedLinesBandButOnADigitalLineIsDrawnStraight) {
  // The 2x2 corners of a primary at 87 degrees (the synthetic 60-degree grid's avenue) between two dead
  // ends: a run at x = 48, a step at y = 35, a run at x = 47 and an end at (47.33, 30.89). Their total
  // least-squares line leaves the step's corners just outside its band (0.53 pw) and the line between
  // the ends leaves (47, 35) 0.58 pw off, but x = 47.5 + 0.05 (y - 35) holds every corner within the band
  // and both ends within half of it: a digital straight line, drawn straight.
  const std::vector<Vec2> points{{48, 42},    {48, 40},    {48, 39}, {48, 38},    {48, 37},      {48, 36},
                                 {48, 35.67}, {48, 35.33}, {48, 35}, {47.67, 35}, {47.33, 35},   {47, 35},
                                 {47, 34.67}, {47, 34.33}, {47, 34}, {47, 33},    {47.33, 30.89}};
  auto run = [&](bool rule) {
    RoadGraph g;
    const std::vector<int> ids = path(g, points);
    ThroughRoadOptions options;
    options.digitalStraightRoads = rule;
    const ThroughRoadStats s = straightenThroughRoads(g, options);
    return std::make_pair(s.straightChains, largestTurn(g, ids));
  };
  const auto [fitted, fittedTurn] = run(false);
  EXPECT_EQ(fitted, 0u);
  EXPECT_GT(fittedTurn, 30.0);
  const auto [digital, digitalTurn] = run(true);
  EXPECT_EQ(digital, 1u);
  EXPECT_LT(digitalTurn, 1e-6);
  // A curve whose cells leave every line's band stays a curve with the rule too (a bow of 1.2 pw over 16).
  std::vector<Vec2> bow;
  for (int k = 0; k <= 16; ++k) bow.push_back({static_cast<double>(k), 1.2 * std::sin(M_PI * k / 16)});
  RoadGraph g;
  path(g, bow);
  EXPECT_EQ(straightenThroughRoads(g, {}).straightChains, 0u);
}

TEST(ThroughRoads, CurveBeyondTheBandStaysACurve) {
  // A quarter circle of radius 10 pw: its middle lies 2.9 pw off the chord, far outside the band.
  std::vector<Vec2> points;
  for (int k = 0; k <= 16; ++k) {
    const double a = M_PI / 2 * k / 16;
    points.push_back({10 * std::cos(a), 10 * std::sin(a)});
  }
  RoadGraph g;
  const std::vector<int> ids = path(g, points);
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.straightChains, 0u);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    EXPECT_DOUBLE_EQ(g.nodes[ids[k]].p.x, points[k].x);
    EXPECT_DOUBLE_EQ(g.nodes[ids[k]].p.y, points[k].y);
  }
}

TEST(ThroughRoads, StraightRoadBetweenEndsALittleOffItsLineIsDrawnStraight) {
  // A street along row y = 0.5 whose cells hold two placements 0.45 pw up in its middle (within the band of
  // 0.5 of their fitted line), between dead ends; one end was left 0.15 pw below the row. The segment between
  // the ends misses the two placements' band (0.53 > 0.50 pw), but the placements form a straight line
  // and both ends lie within half its band: the road is drawn straight between the ends.
  std::vector<Vec2> points;
  for (int k = 0; k <= 20; ++k) points.push_back({k + 0.5, k == 9 || k == 10 ? 0.95 : 0.5});
  RoadGraph g;
  const std::vector<int> ids = path(g, points);
  g.nodes[ids.front()].p = {0.5, 0.35};
  ThroughRoadOptions segmentOnly;
  segmentOnly.endOffset = 0.0;
  RoadGraph before = g;
  EXPECT_EQ(straightenThroughRoads(before, segmentOnly).straightChains, 0u);
  EXPECT_DOUBLE_EQ(before.nodes[ids[9]].p.y, 0.95);
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.straightChains, 1u);
  EXPECT_LT(largestTurn(g, ids), 1e-6);
  EXPECT_NEAR(g.nodes[ids[9]].p.y, 0.35 + 0.15 * 9 / 20, 1e-3);  // on the segment, near x = 9.5
  // An end a whole band off (0.5 pw below the row) is not near the line: the road keeps its nodes.
  RoadGraph farEnd;
  const std::vector<int> farIds = path(farEnd, points);
  farEnd.nodes[farIds.front()].p = {0.5, 0.0};
  EXPECT_EQ(straightenThroughRoads(farEnd, {}).straightChains, 0u);
  EXPECT_DOUBLE_EQ(farEnd.nodes[farIds[9]].p.y, 0.95);
}

TEST(ThroughRoads, StraightRoadBetweenCrossingsLeavesTheCrossingsCellsOut) {
  // A street along row y = 0.5 between two crossings (north-south streets through its ends). Next to
  // the west crossing a cell of the crossing bulges a whole cell up (1.41 pw from the crossing's
  // placement, within the inner radius), and smoothing left a jog in the middle of the street. Without
  // the crossing's cells the street's placements are a straight line: it is drawn straight.
  RoadGraph g;
  std::vector<Vec2> points{{0.5, 0.5}, {1.5, 1.5}};
  for (int k = 2; k <= 20; ++k) points.push_back({k + 0.5, 0.5});
  const std::vector<int> ids = path(g, points);
  for (int end : {ids.front(), ids.back()}) {
    const Vec2 at = g.nodes[end].placed;
    std::vector<Vec2> north, south;
    for (int k = 1; k <= 6; ++k) {
      north.push_back(at + Vec2(0, k));
      south.push_back(at - Vec2(0, k));
    }
    path(g, north, end);
    path(g, south, end);
  }
  g.nodes[ids[10]].p.y = 0.8;
  RoadGraph whole = g;
  ThroughRoadOptions options;
  options.innerRadius = 1.0;  // the bulging cell counts as the street's
  // With the fitted line only: the bulge and the row beyond it also lie on a digital straight line of
  // slope -1/36 (one cell a row up, then the row), which digitalStraightRoads accepts.
  options.digitalStraightRoads = false;
  straightenThroughRoads(whole, options);
  EXPECT_DOUBLE_EQ(whole.nodes[ids[10]].p.y, 0.8);
  straightenThroughRoads(g, {});
  EXPECT_NEAR(g.nodes[ids[10]].p.y, 0.5, 1e-9);
}

TEST(ThroughRoads, ApproachThatCurvesBeforeItsAnchorKeepsItsCurve) {
  // A T-junction: a street along y = 0 through (0, 0) and a stem going north on x = 0 for 5 pw, then
  // curving east. The first stem node beyond the window (1, 6) anchors the approach; the stem's
  // cells up to it are no straight line, so the approach is drawn straight only up to (0, 5).
  RoadGraph g;
  const int centre = g.addNode({0, 0}, NodeType::Secondary);
  std::vector<Vec2> east, west;
  for (int k = 1; k <= 8; ++k) {
    east.push_back({static_cast<double>(k), 0});
    west.push_back({-static_cast<double>(k), 0});
  }
  path(g, east, centre);
  path(g, west, centre);
  const std::vector<int> stem =
      path(g, {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}, {1, 6}, {2, 6.6}, {3, 7}, {4, 7.2}}, centre);
  RoadGraph curving = g;
  straightenThroughRoads(curving, {});
  EXPECT_DOUBLE_EQ(curving.nodes[stem[4]].p.x, 0.0);
  // Drawing every approach straight cuts the curve: (0, 5) moves onto the piece to (1, 6).
  ThroughRoadOptions every;
  every.straightApproachesOnly = false;
  straightenThroughRoads(g, every);
  EXPECT_NEAR(g.nodes[stem[4]].p.x, 30.0 / 37.0, 1e-9);  // its projection onto the piece
}

TEST(ThroughRoads, TJunctionStemMeetsTheThroughRoadAtItsOwnAngleWithoutAHook) {
  // A through road along y = 0 and a stem leaving (0, 0) at 60 degrees whose first node hooks
  // towards the east, as the cells of a junction pull it.
  RoadGraph g;
  const int centre = g.addNode({0.3, 0.2}, NodeType::Secondary);
  std::vector<Vec2> east, west, stem;
  for (int k = 1; k <= 8; ++k) {
    east.push_back({static_cast<double>(k), 0});
    west.push_back({-static_cast<double>(k), 0});
    stem.push_back(Vec2(0.5, std::sqrt(0.75)) * static_cast<double>(k));
  }
  stem[0] = {1.0, 0.2};
  path(g, east, centre);
  path(g, west, centre);
  std::vector<int> stemIds{centre};
  for (int k : path(g, stem, centre)) stemIds.push_back(k);
  EXPECT_GT(largestTurn(g, stemIds), 40.0);
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.pairs, 1u);
  EXPECT_EQ(s.nodesPlaced, 1u);
  // The node is on the through road where the stem's line meets it, and the stem runs straight.
  EXPECT_NEAR(g.nodes[centre].p.y, 0.0, 1e-9);
  EXPECT_NEAR(g.nodes[centre].p.x, 0.0, 1e-9);
  EXPECT_LT(largestTurn(g, stemIds), 1.0);
}

TEST(ThroughRoads, ApproachWhoseSkeletonHooksThroughABulgeOfCellsIsDrawnStraight) {
  // Cells (internal frame, 21 x 21): a street along y = 10.5 (row 10) crossed by one along x = 10.5
  // (column 10), whose cells bulge east by one cell just south of the crossing (as where another road's
  // band touches it). The skeleton hooks east there: the south arm's first node a lies 1.4 pw off its
  // line, beyond its placement's reach (1 pw), but the straight piece from the crossing runs on road
  // cells all along and every cell stays covered: the approach is drawn straight, a's placement left
  // out of its straightness check (issue 20, the
  // 45-degree grid's 94-degree hook); with the rule off it keeps its hook.
  auto run = [](bool rule) {
    Grid<std::uint8_t> cells(21, 21, static_cast<std::uint8_t>(LandUse::Residential));
    const auto road = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
    for (int k = 0; k < 21; ++k) cells.at(k, 10) = cells.at(10, k) = road;
    cells.at(11, 11) = road;
    RoadGraph g;
    const int centre = g.addNode({10.5, 10.5}, NodeType::Secondary);
    std::vector<Vec2> east, west, north, south{{11.9, 9.6}};
    for (int k = 1; k <= 10; ++k) {
      east.push_back({10.5 + k, 10.5});
      west.push_back({10.5 - k, 10.5});
      north.push_back({10.5, 10.5 + k});
      if (k >= 2) south.push_back({10.5, 10.5 - k});
    }
    path(g, east, centre);
    path(g, west, centre);
    path(g, north, centre);
    std::vector<int> ids{centre};
    for (int k : path(g, south, centre)) ids.push_back(k);
    for (RoadNode& n : g.nodes) n.placed = n.p;
    ThroughRoadOptions options;
    options.cells = &cells;
    options.stemThroughBands = rule;
    straightenThroughRoads(g, options);
    double off = 0;
    for (int k : ids) off = std::max(off, std::fabs(g.nodes[k].p.x - 10.5));
    return std::make_pair(largestTurn(g, ids), off);
  };
  const auto [hooked, hookedOff] = run(false);
  EXPECT_GT(hooked, 40.0);
  EXPECT_GT(hookedOff, 1.3);
  const auto [turn, off] = run(true);
  EXPECT_LT(turn, 20.0);  // the crossing moves a little towards the bulge; no hook
  EXPECT_LT(off, 1.0);
}

namespace {

/// The alive road nodes with three or more links.
std::vector<int> junctions(const RoadGraph& g) {
  std::vector<int> out;
  for (std::size_t i = 0; i < g.nodes.size(); ++i)
    if (g.nodes[i].alive && g.nodes[i].links.size() >= 3) out.push_back(static_cast<int>(i));
  return out;
}

/// Runs the stage on a graph built by hand, each node placed where it lies (its cell).
ThroughRoadStats runPlaced(RoadGraph& g, const ThroughRoadOptions& options) {
  for (RoadNode& n : g.nodes) n.placed = n.p;
  g.sortLinksClockwise();
  return straightenThroughRoads(g, options);
}

/// The nodes of the road from `from` through `next` and on through nodes of two links.
std::vector<int> road(const RoadGraph& g, int from, int next) {
  std::vector<int> ids{from};
  for (int k : followChain(g, from, next)) ids.push_back(k);
  return ids;
}

}  // namespace

TEST(JunctionClusters, TwoPrimariesSharingCellsAtAShallowCrossingBecomeOneCrossing) {
  // Two primary roads cross at (0, 0) at 27 degrees: one along y = 0, one along (cos 27, sin 27). Their
  // bands overlap for several cells, so the graph has two Y-junctions, A at (-3, 0) and B at (3, 0),
  // joined by a shared chain along y = 0, each holding one arm of either road.
  const Vec2 d(std::cos(27 * M_PI / 180), std::sin(27 * M_PI / 180));
  RoadGraph g;
  const int a = g.addNode({-3, 0}, NodeType::Primary), b = g.addNode({3, 0}, NodeType::Primary);
  path(g, {{-2, 0}, {-1, 0}, {0, 0}, {1, 0}, {2, 0}}, a);
  g.link(static_cast<int>(g.nodes.size()) - 1, b);
  std::vector<Vec2> west, east, southWest, northEast;
  for (int k = 4; k <= 12; ++k) {
    west.push_back({-static_cast<double>(k), 0});
    east.push_back({static_cast<double>(k), 0});
    southWest.push_back(d * -static_cast<double>(k));
    northEast.push_back(d * static_cast<double>(k));
  }
  path(g, west, a);
  path(g, southWest, a);
  path(g, east, b);
  path(g, northEast, b);
  for (RoadNode& n : g.nodes) n.type = NodeType::Primary;
  g.sortLinksClockwise();

  RoadGraph off = g;
  ThroughRoadOptions noClusters;
  noClusters.junctionSpan = 0;
  const ThroughRoadStats kept = straightenThroughRoads(off, noClusters);
  EXPECT_EQ(kept.clustersConsolidated, 0u);
  EXPECT_EQ(junctions(off).size(), 2u);

  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.clusters, 1u);
  EXPECT_EQ(s.clustersConsolidated, 1u);
  EXPECT_EQ(s.junctionsRemoved, 1u);
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 1u);
  const int x = left[0];
  EXPECT_NEAR(g.nodes[x].p.x, 0.0, 1e-6);
  EXPECT_NEAR(g.nodes[x].p.y, 0.0, 1e-6);
  EXPECT_EQ(g.nodes[x].links.size(), 4u);
  // Both roads run straight through the one crossing: each of its four arms lies wholly on one of the
  // two lines, two arms on each (ids are renumbered by the stage, so the arms are found from the node).
  int onFirst = 0, onSecond = 0;
  for (int q : g.nodes[x].links) {
    bool first = true, second = true;
    for (int k : road(g, x, q)) {
      first = first && std::fabs(g.nodes[k].p.y) < 1e-6;
      second = second && std::fabs(cross(d, g.nodes[k].p)) < 1e-6;
    }
    onFirst += first;
    onSecond += second;
    EXPECT_GE(road(g, x, q).size(), 9u);  // the arm reaches its far end (12 pw)
  }
  EXPECT_EQ(onFirst, 2);
  EXPECT_EQ(onSecond, 2);
  // The approaches drawn straight from the crossing (4 pw to the first node left in place) are cut into
  // links no longer than the graph's longest before (1 pw; the straight roads drawn after it may space
  // them up to 4/3 pw), so the rest of the stage's neighbourhood queries stay their size.
  for (std::size_t k = 0; k < g.nodes.size(); ++k)
    for (int q : g.nodes[k].links)
      if (g.nodes[k].alive) EXPECT_LE(distance(g.nodes[k].p, g.nodes[q].p), 1.5);
}

TEST(JunctionClusters, ALoopInsideACrossingGoesAndTheRoadsRunStraightThroughIt) {
  // A north-south and an east-west street crossing at (0, 0), whose cells made a small ring of four
  // junctions around the crossing, (0, 1), (1, 0), (0, -1), (-1, 0), each holding one street's arm.
  RoadGraph g;
  const std::vector<Vec2> dirs{{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
  std::vector<int> ring;
  for (const Vec2& d : dirs) ring.push_back(g.addNode(d, NodeType::Secondary));
  for (std::size_t k = 0; k < ring.size(); ++k) g.link(ring[k], ring[(k + 1) % ring.size()]);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    std::vector<Vec2> points;
    for (int t = 2; t <= 9; ++t) points.push_back(dirs[k] * static_cast<double>(t));
    path(g, points, ring[k]);
  }
  g.sortLinksClockwise();

  RoadGraph off = g;
  ThroughRoadOptions noClusters;
  noClusters.junctionSpan = 0;
  straightenThroughRoads(off, noClusters);
  EXPECT_EQ(junctions(off).size(), 4u);

  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.clustersConsolidated, 1u);
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(g.nodes[left[0]].p.x, 0.0, 1e-6);
  EXPECT_NEAR(g.nodes[left[0]].p.y, 0.0, 1e-6);
  EXPECT_EQ(g.nodes[left[0]].links.size(), 4u);
  // Each arm runs straight on its axis from the crossing (ids are renumbered by the stage).
  int axes = 0;
  for (int q : g.nodes[left[0]].links) {
    bool onAxis = true;
    const std::vector<int> arm = road(g, left[0], q);
    for (int k : arm) onAxis = onAxis && std::fabs(g.nodes[k].p.x * g.nodes[k].p.y) < 1e-9;
    axes += onAxis && arm.size() >= 8;
  }
  EXPECT_EQ(axes, 4);
  // No loop is left: every other node has two links or ends a street.
  for (const RoadNode& n : g.nodes)
    if (n.alive && &n != &g.nodes[left[0]]) EXPECT_LE(n.links.size(), 2u);
}

TEST(JunctionClusters, JunctionsTheLinesKeepApartStayApart) {
  // A street along y = 0 with a stem north at x = -2 and a stem south at x = 2: a jog of two
  // T-junctions 4 pw apart, which the cells say are two junctions (the stems' lines are 4 pw apart, far
  // outside their bands). They form a cluster, and the rebuild keeps both where the lines cross.
  RoadGraph g;
  const int a = g.addNode({-2, 0.3}, NodeType::Secondary), b = g.addNode({2, -0.3}, NodeType::Secondary);
  path(g, {{-1, 0}, {0, 0}, {1, 0}}, a);
  g.link(static_cast<int>(g.nodes.size()) - 1, b);
  std::vector<Vec2> west, east, north, south;
  for (int k = 1; k <= 8; ++k) {
    west.push_back({-2.0 - k, 0});
    east.push_back({2.0 + k, 0});
    north.push_back({-2, static_cast<double>(k)});
    south.push_back({2, -static_cast<double>(k)});
  }
  for (const auto& [from, points] :
       {std::pair<int, std::vector<Vec2>>{a, west}, {a, north}, {b, east}, {b, south}})
    path(g, points, from);
  for (int k : {a, b}) g.nodes[k].placed = {g.nodes[k].p.x, 0};
  g.sortLinksClockwise();
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.clusters, 1u);
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 2u);
  std::vector<double> xs;
  for (int k : left) {
    EXPECT_NEAR(g.nodes[k].p.y, 0.0, 1e-6);
    xs.push_back(g.nodes[k].p.x);
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], -2.0, 1e-6);
  EXPECT_NEAR(xs[1], 2.0, 1e-6);
}

namespace {

Vec2 unitAt(double degrees) {
  return {std::cos(degrees * M_PI / 180), std::sin(degrees * M_PI / 180)};
}

/// Two streets crossing at O = (0, 0), one at 42 degrees (A), one at 75 degrees (B), and a stem coming in
/// from the west at 15 degrees and ending on B at P = `offset` pw north of O; O and P are two junctions
/// joined by a short piece of B. Returns P.
Vec2 stemBesideACrossing(RoadGraph& g, double offset) {
  const Vec2 a = unitAt(42), b = unitAt(75), stem = unitAt(15), p = b * offset;
  const int o = g.addNode({0, 0}, NodeType::Secondary), q = g.addNode(p, NodeType::Secondary);
  g.link(o, q);
  std::vector<Vec2> aOut, aIn, bOut, bIn, west;
  for (int k = 1; k <= 9; ++k) {
    aOut.push_back(a * static_cast<double>(k));
    aIn.push_back(a * -static_cast<double>(k));
    bIn.push_back(b * -static_cast<double>(k));
    bOut.push_back(p + b * static_cast<double>(k));
    west.push_back(p - stem * static_cast<double>(k));
  }
  for (const auto& [from, points] :
       {std::pair<int, std::vector<Vec2>>{o, aOut}, {o, aIn}, {o, bIn}, {q, bOut}, {q, west}})
    path(g, points, from);
  g.sortLinksClockwise();
  return p;
}

}  // namespace

TEST(JunctionClusters, AStemOffTheThroughRoadsCrossingKeepsItsOwnJunction) {
  // P 1.5 pw north of O: the three lines form a thin triangle whose least-squares point lies in every
  // line's band, but O lies 1.3 pw off the stem's line (more than -smooth-reach): the through roads keep
  // their crossing at O and the stem its own junction at P, drawn straight.
  RoadGraph g;
  const Vec2 p = stemBesideACrossing(g, 1.5), stem = unitAt(15);
  const ThroughRoadStats s = straightenThroughRoads(g, {});
  EXPECT_EQ(s.clusters, 1u);
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 2u);
  int atO = -1, atP = -1;
  for (int k : left) (distance(g.nodes[k].p, {0, 0}) < 1e-6 ? atO : atP) = k;
  ASSERT_GE(atO, 0);
  ASSERT_GE(atP, 0);
  EXPECT_NEAR(distance(g.nodes[atP].p, p), 0.0, 1e-6);
  // The stem runs straight into its junction: every node of its road on its line.
  bool found = false;
  for (int n : g.nodes[atP].links) {
    const std::vector<int> r = road(g, atP, n);
    if (r.size() < 5 || dot(g.nodes[r.back()].p - p, stem) > 0) continue;
    found = true;
    for (int k : r) EXPECT_NEAR(cross(stem, g.nodes[k].p - p), 0.0, 1e-6);
  }
  EXPECT_TRUE(found);
}

TEST(JunctionClusters, AStemWithinReachOfTheThroughRoadsCrossingJoinsIt) {
  // P 0.9 pw north of O: O lies 0.78 pw off the stem's line, outside its band (0.61) but within
  // -smooth-reach (1): one junction, at the through roads' crossing O.
  RoadGraph g;
  stemBesideACrossing(g, 0.9);
  straightenThroughRoads(g, {});
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(distance(g.nodes[left[0]].p, {0, 0}), 0.0, 1e-6);
  EXPECT_EQ(g.nodes[left[0]].links.size(), 5u);
}

TEST(JunctionClusters, ARebuildLeavingACellUncoveredIsKeptWithTheStemJunctionNudgedToCoverIt) {
  // Cells (internal frame, 25 x 21): a street along y = 10.5 crossed by one along x = 10.5 at O, a stem
  // coming in from the north-east at 60 degrees onto the street at P = (12.5, 10.5), and a stub of two
  // cells south of P, (12.5, 9.5) and (12.5, 8.5). The skeleton put P's junction half a cell south, at
  // (12.5, 10.0), within 1.5 cells of the stub's end. The cluster O-P is rebuilt at the lines' crossings,
  // which leaves the stub's end 2 cells from every link: the rebuild is undone unless P (a junction on
  // one through road) is nudged south within the street's band (0.5 + slack) to cover it.
  Grid<std::uint8_t> cells(25, 21, static_cast<std::uint8_t>(LandUse::Residential));
  const auto roadCode = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
  const Vec2 p(12.5, 10.5), d = unitAt(60);
  for (int k = 0; k < 25; ++k) cells.at(k, 10) = roadCode;
  for (int k = 0; k < 21; ++k) cells.at(10, k) = roadCode;
  cells.at(12, 11) = cells.at(12, 12) = roadCode;
  for (int r = 0; r < 21; ++r)
    for (int c = 0; c < 25; ++c) {
      const Vec2 centre(c + 0.5, 21 - r - 0.5);
      if (dot(centre - p, d) > 0 && std::fabs(cross(d, centre - p)) <= 0.75) cells.at(c, r) = roadCode;
    }
  auto run = [&](bool nudge) {
    RoadGraph g;
    const int o = g.addNode({10.5, 10.5}, NodeType::Secondary),
              q = g.addNode({12.5, 10.0}, NodeType::Secondary);
    path(g, {{11.5, 10.3}}, o);
    g.link(static_cast<int>(g.nodes.size()) - 1, q);
    std::vector<Vec2> west, north, south, east, stem;
    for (int k = 1; k <= 9; ++k) {
      west.push_back({10.5 - k, 10.5});
      north.push_back({10.5, 10.5 + k});
      south.push_back({10.5, 10.5 - k});
      east.push_back({12.5 + k, 10.5});
      stem.push_back(p + d * static_cast<double>(k));
    }
    for (const auto& [from, points] :
         {std::pair<int, std::vector<Vec2>>{o, west}, {o, north}, {o, south}, {q, east}, {q, stem}})
      path(g, points, from);
    ThroughRoadOptions options;
    options.cells = &cells;
    options.slack = 0.1;
    options.nudgeToCover = nudge;
    const ThroughRoadStats s = runPlaced(g, options);
    // Every road cell near the cluster stays within the coverage radius of a link.
    double farthest = 0;
    for (int r = 0; r < 21; ++r)
      for (int c = 0; c < 25; ++c) {
        const Vec2 centre(c + 0.5, 21 - r - 0.5);
        if (cells.at(c, r) != roadCode || distance(centre, p) > 6) continue;  // the roads' ends aside
        double best = 1e9;
        for (std::size_t k = 0; k < g.nodes.size(); ++k)
          if (g.nodes[k].alive)
            for (int l : g.nodes[k].links)
              best = std::min(best, distanceToSegment(centre, g.nodes[k].p, g.nodes[l].p));
        farthest = std::max(farthest, best);
      }
    EXPECT_LE(farthest, options.coverRadius + 1e-9);
    return s;
  };
  const ThroughRoadStats off = run(false);
  EXPECT_EQ(off.clustersConsolidated, 0u);
  const ThroughRoadStats on = run(true);
  EXPECT_EQ(on.clustersNudged, 1u);
  EXPECT_EQ(on.clustersConsolidated, 1u);
}

TEST(JunctionClusters, AStemWhoseCellsGoOnThroughAThroughRoadCrossesItToTheNext) {
  // Cells (internal frame, 31 x 26): street A along y = 10.5, street B along x = 20.5, and street C at 27
  // degrees from the north-east, crossing B at (20.5, 14.07) and ending on A at X = (13.5, 10.5). The
  // skeleton has junctions on A at X (J1), at A x B (J3) and on B where C joins it (J2, (20.5, 14.5));
  // with a span of 5 (these streets' widths summed, 2, times 5: chains up to 10 pw are short) the three
  // form one cluster, and C's arm beyond B is its only fitted arm: a stem. Ended at B, C's cells between
  // B and A (2-3.5 cells from A and B) would be left uncovered and the rebuild undone; going on through
  // B to A, the cluster is rebuilt with a junction at each crossing of the lines.
  const int width = 31, height = 26;
  Grid<std::uint8_t> cells(width, height, static_cast<std::uint8_t>(LandUse::Residential));
  const auto roadCode = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
  const Vec2 x(13.5, 10.5), d = unitAt(27);
  auto cellAt = [&](double cx, double cy) -> std::uint8_t& {
    return cells.at(static_cast<int>(cx), height - 1 - static_cast<int>(cy));
  };
  for (int k = 0; k < width; ++k) cellAt(k + 0.5, 10.5) = roadCode;
  for (int k = 0; k < height; ++k) cellAt(20.5, k + 0.5) = roadCode;
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      const Vec2 centre(c + 0.5, height - r - 0.5);
      if (dot(centre - x, d) > 0 && std::fabs(cross(d, centre - x)) <= digitalLineBand(d))
        cells.at(c, r) = roadCode;
    }
  auto onC = [&](double cx) { return Vec2(cx, std::floor(x.y + (cx - x.x) * d.y / d.x) + 0.5); };
  auto run = [&](bool rule) {
    RoadGraph g;
    const int j1 = g.addNode(x, NodeType::Secondary), j3 = g.addNode({20.5, 10.5}, NodeType::Secondary),
              j2 = g.addNode(onC(20.5), NodeType::Secondary);
    std::vector<Vec2> west, aInner, east, south, bInner, north, cInner, cOut;
    for (double c = 0.5; c < x.x; c += 1) west.insert(west.begin(), Vec2(c, 10.5));
    for (double c = 14.5; c < 20.5; c += 1) aInner.push_back({c, 10.5});
    for (double c = 21.5; c < width; c += 1) east.push_back({c, 10.5});
    for (double r = 9.5; r > 0; r -= 1) south.push_back({20.5, r});
    for (double r = 11.5; r < onC(20.5).y; r += 1) bInner.push_back({20.5, r});
    for (double r = onC(20.5).y + 1; r < height; r += 1) north.push_back({20.5, r});
    for (double c = 14.5; c < 20.5; c += 1) cInner.push_back(onC(c));
    for (double c = 21.5; c < width && onC(c).y < height; c += 1) cOut.push_back(onC(c));
    path(g, west, j1);
    path(g, aInner, j1);
    g.link(static_cast<int>(g.nodes.size()) - 1, j3);
    path(g, east, j3);
    path(g, south, j3);
    path(g, bInner, j3);
    g.link(static_cast<int>(g.nodes.size()) - 1, j2);
    path(g, north, j2);
    path(g, cInner, j1);
    g.link(static_cast<int>(g.nodes.size()) - 1, j2);
    path(g, cOut, j2);
    ThroughRoadOptions options;
    options.cells = &cells;
    options.junctionSpan = 5;
    options.stemsThrough = rule;
    const ThroughRoadStats s = runPlaced(g, options);
    return std::make_pair(s, g);
  };
  const auto [off, offGraph] = run(false);
  EXPECT_EQ(off.clusters, 1u);
  EXPECT_EQ(off.clustersConsolidated, 0u);
  const auto [on, g] = run(true);
  EXPECT_EQ(on.clusters, 1u);
  EXPECT_EQ(on.clustersConsolidated, 1u);
  // A junction at each crossing of the lines: C x A, C x B, A x B.
  const Vec2 cb(20.5, x.y + (20.5 - x.x) * d.y / d.x);
  for (const Vec2& want : {x, cb, Vec2(20.5, 10.5)}) {
    double nearest = 1e9;
    for (int k : junctions(g)) nearest = std::min(nearest, distance(g.nodes[k].p, want));
    EXPECT_LT(nearest, 0.35) << want.x << "," << want.y;
  }
}

TEST(JunctionClusters, ASpurInAThroughRoadsBandGoesWithTheRebuild) {
  // Cells (internal frame, 32 x 32): a primary P along x = 20 (columns 19 and 20) and a street C at 60
  // degrees crossing it at X = (20, 15). The skeleton joined C's south-west side to P at J0 = (20, 13)
  // and its north-east side at J1 = (20, 19), and split off the cells where C's staircase runs beside
  // P's band as a spur from J2 = (20, 17): two nodes at x = 21.5, within C's band. Its two placements fit
  // a vertical stem of their own; with spursInBands the spur is C's cells and goes with the rebuild.
  const int size = 32;
  Grid<std::uint8_t> cells(size, size, static_cast<std::uint8_t>(LandUse::Residential));
  const Vec2 x(20, 15), d = unitAt(60);
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) {
      const Vec2 centre(c + 0.5, size - r - 0.5);
      if (std::fabs(cross(d, centre - x)) <= digitalLineBand(d))
        cells.at(c, r) = static_cast<std::uint8_t>(LandUse::SecondaryRoad);
      if (c == 19 || c == 20) cells.at(c, r) = static_cast<std::uint8_t>(LandUse::PrimaryRoad);
    }
  const std::vector<Vec2> spurAt{{21.5, 17.0}, {21.75, 17.75}};
  for (const Vec2& s : spurAt) EXPECT_LE(std::fabs(cross(d, s - x)), digitalLineBand(d));
  auto run = [&](bool rule) {
    RoadGraph g;
    auto primary = [&](const std::vector<Vec2>& points, int from) {
      const std::vector<int> ids = path(g, points, from);
      for (int k : ids) g.nodes[k].type = NodeType::Primary;
      return ids;
    };
    const int j0 = primary({{20, 13}}, -1)[0];
    std::vector<Vec2> south, inner02{{20, 14}, {20, 15}, {20, 16}, {20, 17}}, north{{20, 18}, {20, 19}};
    for (int y = 12; y >= 1; --y) south.push_back({20, static_cast<double>(y)});
    primary(south, j0);
    const int j2 = primary(inner02, j0).back();
    const int j1 = primary(north, j2).back();
    north.clear();
    for (int y = 20; y < size; ++y) north.push_back({20, static_cast<double>(y)});
    primary(north, j1);
    std::vector<Vec2> cSouthWest, cNorthEast;
    for (int k = 3; k <= 12; ++k) cSouthWest.push_back(x - d * k);
    for (int k = 4; k <= 14; ++k) cNorthEast.push_back(x + d * k);
    path(g, cSouthWest, j0);
    path(g, cNorthEast, j1);
    const std::vector<int> spur = path(g, spurAt, j2);
    ThroughRoadOptions options;
    options.cells = &cells;
    options.spursInBands = rule;
    const ThroughRoadStats s = runPlaced(g, options);
    return std::make_tuple(s, g, spur);
  };
  const auto [off, offGraph, offSpur] = run(false);
  EXPECT_EQ(off.clusters, 1u);
  EXPECT_TRUE(offGraph.nodes[offSpur.back()].alive);  // a dead end left in C's band
  const auto [on, g, spur] = run(true);
  EXPECT_EQ(on.clusters, 1u);
  EXPECT_EQ(on.clustersConsolidated, 1u);
  for (int k : spur) EXPECT_FALSE(g.nodes[k].alive);
  // P and C cross at X, their only junction, and no dead end is left near it.
  ASSERT_EQ(junctions(g).size(), 1u);
  EXPECT_LT(distance(g.nodes[junctions(g)[0]].p, x), 0.35);
  for (std::size_t k = 0; k < g.nodes.size(); ++k)
    if (g.nodes[k].alive && g.nodes[k].links.size() == 1) EXPECT_GT(distance(g.nodes[k].p, x), 8.0);
}

TEST(JunctionClusters, TwoStemsCrossingOnTheirWayToTheThroughRoadCrossEachOther) {
  // A street along y = 0 and two streets from the north that cross each other at X = (0, 2) and end on
  // it: P from the north-east at 60 degrees (meeting the street at (-1.15, 0)) and Q from the
  // north-west at 120 degrees (meeting it at (1.15, 0)). Their cells merged, and the skeleton joined
  // each to the nearer junction on the street: Q's arm to the western one, P's to the eastern one, two
  // junctions 2.3 pw apart. Rebuilt, both stems run straight to where they meet the street, so their
  // links cross each other: the rebuild is undone unless the stems cross at X too.
  const Vec2 p = unitAt(60), q = unitAt(120), xing(0, 2);
  const Vec2 pEnd = xing - p * (2 / p.y), qEnd = xing - q * (2 / q.y);
  auto run = [&](bool rule) {
    RoadGraph g;
    const int west = g.addNode(pEnd, NodeType::Secondary), east = g.addNode(qEnd, NodeType::Secondary);
    g.link(west, east);
    std::vector<Vec2> streetWest, streetEast, pArm, qArm;
    for (int k = 1; k <= 9; ++k) {
      streetWest.push_back(pEnd - Vec2(k, 0));
      streetEast.push_back(qEnd + Vec2(k, 0));
      pArm.push_back(xing + p * (1.0 + k));
      qArm.push_back(xing + q * (1.0 + k));
    }
    path(g, streetWest, west);
    path(g, streetEast, east);
    const std::vector<int> pIds = path(g, pArm, east), qIds = path(g, qArm, west);
    ThroughRoadOptions options;
    options.stemsCross = rule;
    const ThroughRoadStats s = runPlaced(g, options);
    return std::make_tuple(s, g, pIds.back(), qIds.back());
  };
  const auto [off, offGraph, offP, offQ] = run(false);
  EXPECT_EQ(off.clusters, 1u);
  EXPECT_EQ(off.clustersConsolidated, 0u);
  const auto [on, g, farP, farQ] = run(true);
  EXPECT_EQ(on.clustersConsolidated, 1u);
  const std::vector<int> left = junctions(g);
  ASSERT_EQ(left.size(), 3u);
  int atX = -1;
  for (int k : left)
    if (distance(g.nodes[k].p, xing) < 1e-6) atX = k;
  ASSERT_GE(atX, 0);
  // Each stem runs straight from its far end through X to the street.
  for (const auto& [far, dir] : {std::pair<int, Vec2>{farP, p}, {farQ, q}}) {
    bool found = false;
    for (int n : g.nodes[atX].links) {
      const std::vector<int> r = road(g, atX, n);
      if (r.back() != far) continue;
      found = true;
      for (int k : r) EXPECT_NEAR(cross(dir, g.nodes[k].p - xing), 0.0, 1e-6);
    }
    EXPECT_TRUE(found);
  }
}
