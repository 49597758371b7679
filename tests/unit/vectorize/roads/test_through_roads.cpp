// Stage B7 (through roads and straight roads, issue 20) on hand-made graphs with known answers.
#include <gtest/gtest.h>

#include <cmath>

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
