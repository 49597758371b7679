// Stages A4 and B1–B6 on small drawn grids and hand-made graphs with known answers (spec §11.1–11.2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../test_grids.hpp"
#include "urbanvec/vectorize/roads/curve_smoothing.hpp"
#include "urbanvec/vectorize/roads/cycle_removal.hpp"
#include "urbanvec/vectorize/roads/intersection_simplification.hpp"
#include "urbanvec/vectorize/roads/patch_cleaning.hpp"
#include "urbanvec/vectorize/roads/road_connection.hpp"
#include "urbanvec/vectorize/roads/road_graph_build.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"
#include "urbanvec/vectorize/roads/road_smoothing.hpp"
#include "urbanvec/vectorize/roads/straightening.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;
using namespace urbanvec::vectorize::testing;

namespace {

std::vector<int> aliveNodes(const RoadGraph& g) {
  std::vector<int> out;
  for (size_t i = 0; i < g.nodes.size(); ++i)
    if (g.nodes[i].alive) out.push_back(static_cast<int>(i));
  return out;
}

int countDegree(const RoadGraph& g, int degree) {
  int k = 0;
  for (int i : aliveNodes(g)) k += g.degree(i) == degree;
  return k;
}

/// A polyline graph a - m - b of secondary nodes with equal link lengths and angle `degrees` at m.
RoadGraph bend(double degrees) {
  RoadGraph g;
  const double half = degrees * M_PI / 360.0;
  const int a = g.addNode({-std::sin(half) * 3, std::cos(half) * 3}, NodeType::Secondary);
  const int m = g.addNode({0, 0}, NodeType::Secondary);
  const int b = g.addNode({std::sin(half) * 3, std::cos(half) * 3}, NodeType::Secondary);
  g.link(a, m);
  g.link(m, b);
  return g;
}

}  // namespace

TEST(RoadGraph, PlusShapedSecondaryCrossingGivesOneFourWayIntersection) {
  auto cells = drawGrid({
      "rrrsrrr",
      "rrrsrrr",
      "rrrsrrr",
      "sssssss",
      "rrrsrrr",
      "rrrsrrr",
      "rrrsrrr",
  });
  const RoadGraphBuild b = buildRoadGraph(cells, {});
  EXPECT_EQ(countDegree(b.graph, 4), 1);
  EXPECT_EQ(countDegree(b.graph, 3), 0);
  EXPECT_EQ(countDegree(b.graph, 1), 4);
  for (int i : aliveNodes(b.graph))
    if (b.graph.degree(i) == 4) {
      EXPECT_DOUBLE_EQ(b.graph.nodes[i].p.x, 3.5);
      EXPECT_DOUBLE_EQ(b.graph.nodes[i].p.y, 3.5);
      // Clockwise from north: N, E, S, W.
      std::vector<double> az;
      for (int j : b.graph.nodes[i].links) az.push_back(azimuth(b.graph.nodes[i].p, b.graph.nodes[j].p));
      EXPECT_TRUE(std::is_sorted(az.begin(), az.end()));
      EXPECT_NEAR(az[0], 0.0, 1e-12);
    }
}

TEST(RoadGraph, StraightTwoWidePrimaryGivesOneCentrelineOnItsMiddleLine) {
  auto cells = drawGrid({
      "rrrrrrrrrr",
      "PPPPPPPPPP",
      "PPPPPPPPPP",
      "rrrrrrrrrr",
  });
  const RoadGraphBuild b = buildRoadGraph(cells, {});
  const std::vector<int> nodes = aliveNodes(b.graph);
  ASSERT_EQ(nodes.size(), 9u);  // n - 1 for a road n = 10 patches long
  for (int i : nodes) {
    EXPECT_EQ(b.graph.nodes[i].type, NodeType::Primary);
    EXPECT_DOUBLE_EQ(b.graph.nodes[i].p.y, 2.0);  // boundary between rows 1 and 2 (H = 4)
    EXPECT_LE(b.graph.degree(i), 2);
  }
  EXPECT_EQ(countDegree(b.graph, 1), 2);
  // Thesis variant: centre of the south-east neighbour, half a patch off the centreline.
  auto cells2 = cells;
  RoadGraphOptions thesis;
  thesis.primaryNodeAtCorner = false;
  const RoadGraphBuild t = buildRoadGraph(cells2, thesis);
  for (int i : aliveNodes(t.graph)) EXPECT_DOUBLE_EQ(t.graph.nodes[i].p.y, 1.5);
}

TEST(RoadGraph, TwoByTwoRoadSquareIsOpened) {
  // The square is cols 2-3, rows 2-3; the road enters at its south-west and leaves at its north-east.
  auto cells = drawGrid({
      "rrrrrr",
      "rrrrrr",
      "rrssss",
      "ssssrr",
      "rrrrrr",
  });
  const RoadGraphBuild b = buildRoadGraph(cells, {});
  EXPECT_EQ(b.squaresOpened, 1u);
  // NW is the first patch (N-W, N-E, S-E, S-W order) whose two outside neighbours are not road.
  EXPECT_EQ(cells.at(2, 2), kRemovedRoad);
  // No cycle is left and the road is still one piece: nodes = links + 1.
  EXPECT_EQ(b.graph.aliveCount(), b.graph.linkCount() + 1);
}

TEST(RoadGraph, LongLinksAreSplitBelowTwoPatchWidths) {
  RoadGraph g;
  const int a = g.addNode({0, 0}, NodeType::Primary);
  const int b = g.addNode({5, 0}, NodeType::Primary);
  const int c = g.addNode({5, 2}, NodeType::Secondary);
  g.link(a, b);
  g.link(b, c);
  const std::size_t added = subdivideLongLinks(g, 2.0);
  EXPECT_EQ(added, 2u + 1u);  // 5 -> 3 parts, 2 -> 2 parts
  for (size_t i = 0; i < g.nodes.size(); ++i)
    for (int j : g.nodes[i].links) EXPECT_LT(distance(g.nodes[i].p, g.nodes[j].p), 2.0);
  EXPECT_EQ(g.nodes.back().type, NodeType::Secondary);  // inserted on the mixed link: secondary
}

TEST(RoadGraph, IntersectionClusterCollapsesToItsMean) {
  RoadGraph g;
  // Two adjacent degree-3 nodes, each with two outside arms of two nodes (a one-node dead end would
  // itself count as an intersection: "linked only to other intersections").
  const int p = g.addNode({0, 0}, NodeType::Secondary), q = g.addNode({1, 0}, NodeType::Secondary);
  g.link(p, q);
  auto arm = [&](int from, Vec2 a) {
    const int n1 = g.addNode(a, NodeType::Secondary);
    g.link(from, n1);
    g.link(n1, g.addNode(a * 2.0, NodeType::Secondary));
  };
  arm(p, {-1, 1});
  arm(p, {-1, -1});
  arm(q, {2, 1});
  arm(q, {2, -1});
  EXPECT_EQ(simplifyIntersectionClusters(g, true), 1u);
  g.compact();
  ASSERT_EQ(countDegree(g, 4), 1);
  for (const RoadNode& n : g.nodes)
    if (n.links.size() == 4) EXPECT_EQ(n.p, Vec2(0.5, 0));
}

TEST(Straightening, FitIsOrthogonalSoNorthSouthRoadsWork) {
  Vec2 c, d;
  EXPECT_NEAR(fitLine({{3, 0}, {3, 1}, {3, 2}, {3, 5}}, c, d), 0.0, 1e-12);
  EXPECT_NEAR(std::fabs(d.y), 1.0, 1e-12);
  EXPECT_NEAR(fitLine({{0, 0}, {1, 1}, {2, 0}}, c, d), std::sqrt(2.0 / 3.0), 1e-9);
}

TEST(Straightening, PairsWithSmallResidualAreSnappedOntoTheirLine) {
  // A crossing whose east-west road meanders by a quarter patch.
  RoadGraph g;
  const int centre = g.addNode({0, 0.1}, NodeType::Secondary);
  int prevE = centre, prevW = centre, prevN = centre;
  for (int k = 1; k <= 6; ++k) {
    const double wiggle = (k % 2 ? 0.25 : -0.2);
    const int e = g.addNode({static_cast<double>(k), wiggle}, NodeType::Secondary);
    const int w = g.addNode({-static_cast<double>(k), -wiggle}, NodeType::Secondary);
    const int n = g.addNode({0.05 * k, static_cast<double>(k)}, NodeType::Secondary);
    g.link(prevE, e);
    g.link(prevW, w);
    g.link(prevN, n);
    prevE = e;
    prevW = w;
    prevN = n;
  }
  g.sortLinksClockwise();
  const StraighteningStats s = straightenIntersections(g, {});
  EXPECT_EQ(s.intersections, 1u);
  EXPECT_GE(s.pairsSnapped, 1u);
  // The east-west pair (best residual among the pairs) is on one line within 5 pw of the centre.
  std::vector<Vec2> ew;
  for (const RoadNode& n : g.nodes)
    if (std::fabs(n.p.x) > 0.5 && std::fabs(n.p.x) <= 4.5 && std::fabs(n.p.y) < 1.0) ew.push_back(n.p);
  ew.push_back(g.nodes[centre].p);
  Vec2 c, d;
  EXPECT_LT(fitLine(ew, c, d), 1e-9);
  // Residual above the limit: nothing moves.
  RoadGraph g2 = bend(90);
  const int extra = g2.addNode({0, -3}, NodeType::Secondary);
  g2.link(1, extra);
  StraighteningOptions strict;
  strict.maxResidual = 0.0;
  const Vec2 before = g2.nodes[0].p;
  EXPECT_EQ(straightenIntersections(g2, strict).pairsSnapped, 0u);
  EXPECT_EQ(g2.nodes[0].p, before);
}

TEST(RoadSmoothing, DeadEndsIntersectionsAndConnectionNodesStayPut) {
  auto cells = drawGrid({
      "rrrrsrrrr",
      "rrrrsrrrr",
      "rrrrsrrrr",
      "sssssrrrr",
      "rrrrssrrr",
      "rrrrrsrrr",
      "rrrrrssss",
      "rrrrrrrrr",
  });
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  g.nodes[3].psConnection = true;
  const RoadGraph before = g;
  RoadSmoothingOptions noSecondStraightening;
  noSecondStraightening.straightAngle = 180.0;
  smoothRoads(g, noSecondStraightening);
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const RoadNode& n = before.nodes[i];
    if (n.links.size() != 2 || n.intersection || n.psConnection) EXPECT_EQ(g.nodes[i].p, n.p) << i;
  }
}

TEST(Smoothing, StaircaseDiagonalRoadIsStraightWithinAQuarterCell) {
  std::vector<std::string> rows = blank(24, 24);
  // A 4-connected staircase from the north-west to the south-east.
  for (int k = 0; k < 23; ++k) {
    rows[k][k] = 's';
    rows[k][k + 1] = 's';
  }
  rows[23][23] = 's';
  auto cells = drawGrid(rows);
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  smoothRoads(g, {});
  smoothCurves(g, {});
  std::vector<Vec2> pts;
  for (const RoadNode& n : g.nodes)
    if (n.alive) pts.push_back(n.p);
  Vec2 c, d;
  fitLine(pts, c, d);
  EXPECT_NEAR(std::fabs(d.x), std::sqrt(0.5), 0.02);  // still the diagonal
  for (const RoadNode& n : g.nodes) {
    // Only the two fixed dead ends keep their staircase corner offset.
    if (n.links.size() < 2) continue;
    EXPECT_LE(std::fabs(cross(d, n.p - c)), 0.25) << n.p.x << "," << n.p.y;
  }
}

TEST(Connection, SecondaryRoadMeetingAPrimaryIsLinkedToIt) {
  auto cells = drawGrid({
      "rrrrsrrrrr",
      "rrrrsrrrrr",
      "rrrrsrrrrr",
      "PPPPPPPPPP",
      "PPPPPPPPPP",
      "rrrrrrrrrr",
  });
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  const RoadConnectionStats s = connectRoads(g, {});
  EXPECT_EQ(s.connections, 1u);
  // One connected network with one T intersection on the primary centreline.
  EXPECT_EQ(g.aliveCount(), g.linkCount() + 1);
  EXPECT_EQ(countDegree(g, 3), 1);
  for (const RoadNode& n : g.nodes)
    if (n.links.size() == 3) EXPECT_EQ(n.type, NodeType::Primary);
}

/// The primary nodes with a link to a secondary node, and how many such links each has.
std::vector<std::pair<int, int>> primariesWithSecondaryLinks(const RoadGraph& g) {
  std::vector<std::pair<int, int>> out;
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const RoadNode& n = g.nodes[i];
    if (!n.alive || n.type != NodeType::Primary) continue;
    int k = 0;
    for (int m : n.links) k += g.nodes[m].type == NodeType::Secondary;
    if (k) out.push_back({static_cast<int>(i), k});
  }
  return out;
}

TEST(Connection, AStreetCrossingAPrimaryAtASlantMeetsItAtOneNode) {
  // A 45-degree secondary staircase crossing a 2-wide primary (rows 10-11): its two ends lie about
  // 4 cells apart along the street, 3 along the primary. Linked each to its closest primary node they
  // make two T-junctions; paired (issue 20) they make one 4-way crossing.
  std::vector<std::string> rows(22, std::string(32, 'r'));
  for (int k = 0; k < 22; ++k) {
    rows[k][k + 4] = 's';
    rows[k][k + 5] = 's';
  }
  rows[10] = rows[11] = std::string(32, 'P');
  auto cells = drawGrid(rows);
  cleanIntersectionPatches(cells);  // A3, as the pipeline runs it
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  const RoadConnectionStats s = connectRoads(g, {});
  EXPECT_EQ(s.crossings, 1u);
  const auto joined = primariesWithSecondaryLinks(g);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_EQ(joined[0].second, 2);
  EXPECT_EQ(countDegree(g, 4), 1);

  auto cells2 = drawGrid(rows);
  cleanIntersectionPatches(cells2);
  RoadGraph g2 = buildRoadGraph(cells2, {}).graph;
  RoadConnectionOptions documents;
  documents.crossingAngle = 0;  // each end to its closest primary node
  EXPECT_EQ(connectRoads(g2, documents).crossings, 0u);
  EXPECT_EQ(primariesWithSecondaryLinks(g2).size(), 2u);
  EXPECT_EQ(countDegree(g2, 4), 0);
}

TEST(CycleRemoval, ShortCycleLosesItsShortestSegmentUntilNoneIsLeft) {
  // A 2x3 block ring (14 nodes) and a 3x3 block ring (16 nodes) sharing the middle road.
  auto cells = drawGrid({
      "rrrrrrrrrrr",
      "rssssssssrr",
      "rsrrsrrrsrr",
      "rsrrsrrrsrr",
      "rsrrsrrrsrr",
      "rssssssssrr",
      "rrrrrrrrrrr",
  });
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  ASSERT_EQ(boundedRoadFaces(g).size(), 2u);
  const CycleRemovalStats s = removeShortCycles(g, {});
  EXPECT_EQ(s.segmentsRemoved, 1u);
  // The shortest chain of the 14-node face was the shared middle road: what remains is the outer ring
  // of 22 nodes, above the limit.
  const auto faces = boundedRoadFaces(g);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].size(), 22u);
  for (const auto& f : faces) EXPECT_GT(f.size(), 15u);
}

TEST(CycleRemoval, KeepLandCyclesRemovesOnlySmallLoopsAroundRoadCells) {
  // A grid of road cells but one unused cell (column 9, bottom row), and three square loops: A around
  // 4 road cells (2.56 pw^2), B around road cells only but 13 pw^2, C around the unused cell.
  auto squares = [] {
    RoadGraph g;
    for (const double x0 : {0.2, 4.2, 9.2}) {
      const double side = x0 == 4.2 ? 3.6 : 1.6;
      const int a = g.addNode({x0, 0.2}, NodeType::Secondary),
                b = g.addNode({x0 + side, 0.2}, NodeType::Secondary);
      const int c = g.addNode({x0 + side, 0.2 + side}, NodeType::Secondary);
      const int d = g.addNode({x0, 0.2 + side}, NodeType::Secondary);
      g.link(a, b), g.link(b, c), g.link(c, d), g.link(d, a);
    }
    return g;
  };
  Grid<std::uint8_t> cells(12, 4, static_cast<std::uint8_t>(LandUse::SecondaryRoad));
  cells.at(9, 3) = static_cast<std::uint8_t>(LandUse::Unused);  // internal y = 4 - 3 - 0.5 = 0.5
  RoadGraph g = squares();
  ASSERT_EQ(boundedRoadFaces(g).size(), 3u);
  CycleRemovalOptions land;
  land.landUse = &cells;
  land.keepLandCycles = true;
  const CycleRemovalStats s = removeShortCycles(g, land);
  EXPECT_EQ(s.segmentsRemoved, 1u);  // A only
  EXPECT_EQ(boundedRoadFaces(g).size(), 2u);
  // The documents' rule with the developed-land flag: no face encloses developed land, all three go.
  RoadGraph d = squares();
  CycleRemovalOptions developed;
  developed.landUse = &cells;
  EXPECT_EQ(removeShortCycles(d, developed).segmentsRemoved, 3u);
  EXPECT_EQ(boundedRoadFaces(d).size(), 0u);
}

TEST(IntersectionSimplification, SharpDeadEndsAndCloseNodesGo) {
  RoadGraph g;
  const int x = g.addNode({0, 0}, NodeType::Secondary);
  const int e = g.addNode({1, 0}, NodeType::Secondary), w = g.addNode({-1, 0}, NodeType::Secondary);
  const int s = g.addNode({0, -1}, NodeType::Secondary);
  const int e2 = g.addNode({2, 0}, NodeType::Secondary), w2 = g.addNode({-2, 0}, NodeType::Secondary);
  const int s2 = g.addNode({0, -2}, NodeType::Secondary);
  g.link(e, e2);
  g.link(w, w2);
  g.link(s, s2);
  const int sharp = g.addNode({0.8, 0.6}, NodeType::Secondary);  // 37 degrees from the east road
  const int close = g.addNode({0, 0.4}, NodeType::Secondary);    // 0.4 pw north, leads on
  const int far = g.addNode({0, 1.5}, NodeType::Secondary);
  for (int n : {e, w, s, sharp, close}) g.link(x, n);
  g.link(close, far);
  const IntersectionSimplificationStats st = simplifyIntersections(g, {});
  EXPECT_EQ(st.deadEndsRemoved, 1u);
  // The removed dead end's link is recorded for the coverage check (removed on purpose).
  ASSERT_EQ(st.removedLinks.size(), 1u);
  EXPECT_EQ(st.removedLinks[0][0], Vec2(0, 0));
  EXPECT_EQ(st.removedLinks[0][1], Vec2(0.8, 0.6));
  EXPECT_EQ(st.nodesContracted, 1u);
  // The crossing keeps four arms, the northern one now linked straight to `far`.
  ASSERT_EQ(countDegree(g, 4), 1);
  for (const RoadNode& n : g.nodes) {
    EXPECT_NE(n.p, Vec2(0.8, 0.6));
    EXPECT_NE(n.p, Vec2(0, 0.4));
  }
}

TEST(IntersectionSimplification, RoadEndMetByAPerimeterAtASharpAngleStays) {
  // A primary road ends at `end`; the node before it, `i`, also carries an external block perimeter
  // leaving 26 degrees from the road's last link.
  auto graph = [] {
    RoadGraph g;
    const int w2 = g.addNode({-3, 0}, NodeType::Primary), w = g.addNode({-1.5, 0}, NodeType::Primary);
    const int i = g.addNode({0, 0}, NodeType::Primary), end = g.addNode({1, 1.6}, NodeType::Primary);
    const int p = g.addNode({2, 0.6}, NodeType::Perimeter), p2 = g.addNode({3.5, 0}, NodeType::Perimeter);
    g.link(w2, w);
    g.link(w, i);
    g.link(i, end);
    g.link(i, p);
    g.link(p, p2);
    return g;
  };
  RoadGraph g = graph();
  EXPECT_EQ(simplifyIntersections(g, {}).deadEndsRemoved, 0u);
  EXPECT_EQ(g.aliveCount(), 6u);
  // The literal reading counts the perimeter as another road and cuts the road's end off.
  RoadGraph literal = graph();
  IntersectionSimplificationOptions allLinks;
  allLinks.deadEndRoadsOnly = false;
  EXPECT_EQ(simplifyIntersections(literal, allLinks).deadEndsRemoved, 1u);
}

TEST(CurveSmoothing, InsertsThreeTwoOneOrNoNodesPerSideByAngle) {
  const CurveSmoothingOptions defaults;
  EXPECT_EQ(defaults.passes, 8);
  for (const auto& [angle, perSide] :
       std::vector<std::pair<double, int>>{{80, 3}, {120, 2}, {150, 1}, {170, 0}}) {
    RoadGraph g = bend(angle);
    const RoadGraph original = g;
    CurveSmoothingOptions noPasses;
    noPasses.passes = 0;
    const CurveSmoothingStats s = smoothCurves(g, noPasses);
    EXPECT_EQ(s.nodesInserted, static_cast<size_t>(2 * perSide)) << angle;
    // Inserted nodes lie on the original links.
    for (size_t i = 3; i < g.nodes.size(); ++i) {
      const Vec2 p = g.nodes[i].p;
      const double onA = std::fabs(cross(original.nodes[0].p - original.nodes[1].p, p - original.nodes[1].p));
      const double onB = std::fabs(cross(original.nodes[2].p - original.nodes[1].p, p - original.nodes[1].p));
      EXPECT_LT(std::min(onA, onB), 1e-9);
    }
    RoadGraph h = bend(angle);
    EXPECT_EQ(smoothCurves(h, defaults).passes, 8);
  }
}

namespace {

/// Connected components among the alive nodes.
int componentCount(const RoadGraph& g) {
  std::vector<int> seen(g.nodes.size(), 0);
  int components = 0;
  for (int start : aliveNodes(g)) {
    if (seen[start]) continue;
    ++components;
    std::vector<int> stack{start};
    seen[start] = 1;
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      for (int m : g.nodes[n].links)
        if (!seen[m]) seen[m] = 1, stack.push_back(m);
    }
  }
  return components;
}

}  // namespace

TEST(RoadGraph, TwoWidePrimariesMeetingAKnightsStepApartAreLinked) {
  // The vertical road's window (4,0) and the horizontal road's last window (3,2) touch along an edge
  // with no window overlapping both, as rasterized junctions at an angle leave them.
  const std::vector<std::string> rows = {
      "rrrrPPrr",
      "rrrrPPrr",
      "PPPPPrrr",
      "PPPPPrrr",
  };
  auto cells = drawGrid(rows);
  EXPECT_EQ(componentCount(buildRoadGraph(cells, {}).graph), 1);
  RoadGraphOptions documentsOnly;
  documentsOnly.linkPrimaryKnightSteps = false;
  auto cells2 = drawGrid(rows);
  EXPECT_EQ(componentCount(buildRoadGraph(cells2, documentsOnly).graph), 2);
}

TEST(Connection, SecondaryCellBridgingTwoPrimariesAtACornerKeepsThemConnected) {
  // The primaries touch only diagonally, at (4,1)-(5,2); the secondary cell (5,1) joins them.
  const std::vector<std::string> rows = {
      "PPPPPrrrrr", "PPPPPsrrrr", "rrrrrPPrrr", "rrrrrPPrrr", "rrrrrPPrrr", "rrrrrPPrrr",
  };
  auto cells = drawGrid(rows);
  const PatchCleaningStats cleaning = cleanIntersectionPatches(cells);
  EXPECT_EQ(cleaning.bridgesKept, 1u);
  EXPECT_EQ(cells.at(5, 1), static_cast<std::uint8_t>(LandUse::SecondaryRoad));
  RoadGraph g = buildRoadGraph(cells, {}).graph;
  const RoadConnectionStats s = connectRoads(g, {});
  EXPECT_EQ(s.bridges, 1u);
  EXPECT_EQ(componentCount(g), 1);

  // The documents' rules alone remove the bridge and leave two roads.
  auto cells2 = drawGrid(rows);
  PatchCleaningOptions documentsOnly;
  documentsOnly.keepPrimaryBridges = false;
  cleanIntersectionPatches(cells2, {}, documentsOnly);
  EXPECT_EQ(cells2.at(5, 1), kRemovedRoad);
  RoadGraph g2 = buildRoadGraph(cells2, {}).graph;
  connectRoads(g2, {});
  EXPECT_EQ(componentCount(g2), 2);
}

namespace {

/// Farthest distance, in cells, from a road cell's centre to the graph's links (internal frame).
double farthestRoadCell(const Grid<std::uint8_t>& cells, const RoadGraph& g) {
  double worst = 0.0;
  for (int row = 0; row < cells.height; ++row)
    for (int col = 0; col < cells.width; ++col) {
      if (!isRoadCode(cells.at(col, row))) continue;
      const Vec2 centre{col + 0.5, cells.height - row - 0.5};
      double best = 1e9;
      for (size_t a = 0; a < g.nodes.size(); ++a)
        if (g.nodes[a].alive)
          for (int b : g.nodes[a].links)
            best = std::min(best, distanceToSegment(centre, g.nodes[a].p, g.nodes[b].p));
      worst = std::max(worst, best);
    }
  return worst;
}

/// A 2-wide primary turning back on itself: east along the top, down, west along the bottom.
Grid<std::uint8_t> primaryHairpin() {
  std::vector<std::string> rows = blank(26, 16);
  for (int c = 2; c < 22; ++c) rows[3][c] = rows[4][c] = rows[11][c] = rows[12][c] = 'P';
  for (int r = 3; r <= 12; ++r) rows[r][20] = rows[r][21] = 'P';
  return drawGrid(rows);
}

}  // namespace

TEST(Smoothing, BendsOfTwoWidePrimariesKeepTheirOuterCellsWithinOneAndAHalfCells) {
  Grid<std::uint8_t> cells = primaryHairpin();
  RoadGraph limited = buildRoadGraph(cells, {}).graph;
  RoadGraph unlimited = limited;
  smoothRoads(limited, {});
  smoothCurves(limited, {});
  EXPECT_LE(farthestRoadCell(cells, limited), 1.5);
  for (const RoadNode& n : limited.nodes)
    if (n.alive)
      EXPECT_LE(distance(n.p, n.placed), smoothingShiftLimit(n.type, kDefaultSmoothingReach) + 1e-12);
  // The documents' unlimited averaging cuts the corners: the outer corner cells end up farther.
  RoadSmoothingOptions roads;
  roads.reach = 0.0;
  CurveSmoothingOptions curves;
  curves.reach = 0.0;
  smoothRoads(unlimited, roads);
  smoothCurves(unlimited, curves);
  EXPECT_GT(farthestRoadCell(cells, unlimited), 1.5);
}

TEST(Connection, PrimaryStubJoinedByASecondaryRoadKeepsItsCells) {
  // A 3-row primary stub hangs south of an east-west primary; a secondary road meets the stub from
  // the west. The connection link makes the stub's nodes, its one-node dead end included ("linked
  // only to other intersections"), one intersection cluster with the junction above.
  std::vector<std::string> rows = blank(16, 12);
  for (int c = 0; c < 16; ++c) rows[2][c] = rows[3][c] = 'P';
  for (int r = 4; r <= 6; ++r) rows[r][7] = rows[r][8] = 'P';
  for (int c = 0; c < 7; ++c) rows[5][c] = 's';
  const Grid<std::uint8_t> cells = drawGrid(rows);
  auto run = [&](double maxClusterRadius) {
    Grid<std::uint8_t> work = cells;
    RoadGraphOptions build;
    build.maxClusterRadius = maxClusterRadius;
    RoadGraph g = buildRoadGraph(work, build).graph;
    RoadConnectionOptions connection;
    connection.maxClusterRadius = maxClusterRadius;
    connectRoads(g, connection);
    EXPECT_EQ(componentCount(g), 1);
    return farthestRoadCell(cells, g);
  };
  EXPECT_LE(run(RoadConnectionOptions{}.maxClusterRadius), 1.5);
  // The documents' unbounded clusters put the stub and the junction at one mean: the stub's end
  // patches are left about 2 cells from any road.
  EXPECT_GT(run(0.0), 1.5);
}

TEST(Smoothing, AMoveThatWouldUncoverARoadCellIsCutBack) {
  // A zigzag of secondary nodes on a 10 x 10 grid; only the middle node (5.5, 5.5) may move, and the
  // mean of it and its neighbours (4.5, 6.5), (6.5, 6.5) lies at y = 6.17. The road cell centred at
  // (5.5, 4.5), 1 cell below it, would end up 1.67 cells from every link.
  RoadGraph g;
  const std::vector<Vec2> chain = {{2.5, 5.5}, {3.5, 5.5}, {4.5, 6.5}, {5.5, 5.5},
                                   {6.5, 6.5}, {7.5, 5.5}, {8.5, 5.5}};
  for (const Vec2& p : chain) g.addNode(p, NodeType::Secondary);
  for (int k = 0; k + 1 < static_cast<int>(chain.size()); ++k) g.link(k, k + 1);
  Grid<std::uint8_t> cells(10, 10, 0);
  for (const Vec2& p : chain) cells.at(static_cast<int>(p.x), static_cast<int>(10 - p.y)) = 2;
  cells.at(5, 5) = 2;  // centre (5.5, 4.5)
  std::vector<char> movable(chain.size(), 0);
  movable[3] = 1;
  RoadGraph free = g;
  averagePass(free, movable, 0.0);
  EXPECT_NEAR(free.nodes[3].p.y, 6.5 - 1.0 / 3.0, 1e-9);
  averagePass(g, movable, 0.0, &cells, 1.5);
  // Halved once: 1.33 cells from the cell.
  EXPECT_NEAR(g.nodes[3].p.y, 5.5 + 1.0 / 3.0, 1e-9);
  EXPECT_LE(distance(g.nodes[3].p, {5.5, 4.5}), 1.5);
}

namespace {

/// An intersection at `centre` with one chain of secondary nodes per arm, the chain's first node
/// linked to the intersection.
RoadGraph intersectionWithArms(const Vec2& centre, const std::vector<std::vector<Vec2>>& arms) {
  RoadGraph g;
  const int x = g.addNode(centre, NodeType::Secondary);
  for (const std::vector<Vec2>& arm : arms) {
    int previous = x;
    for (const Vec2& p : arm) {
      const int node = g.addNode(p, NodeType::Secondary);
      g.link(previous, node);
      previous = node;
    }
  }
  return g;
}

/// B5 on `g` with the coverage guard over `cells` when `guard`; the farthest road cell from the result.
double farthestAfterB5(RoadGraph& g, const Grid<std::uint8_t>& cells, bool guard,
                       IntersectionSimplificationStats& stats) {
  IntersectionSimplificationOptions options;
  if (guard) options.coverCells = &cells;
  stats = simplifyIntersections(g, options);
  return farthestRoadCell(cells, g);
}

}  // namespace

TEST(IntersectionSimplification, AContractionThatWouldUncoverARoadCellIsNotMade) {
  // An intersection at (5.6, 5.5) with arms west, south and east-then-north: the east arm's first
  // node lies 0.45 pw from the intersection, so B5 contracts it and links the intersection straight
  // to (6.05, 9.5). The road cell centred at (7.5, 7.5) is 1.45 cells from the old arm and would be
  // 1.67 from the new one.
  const RoadGraph graph = intersectionWithArms(
      {5.6, 5.5}, {{{3.6, 5.5}, {2.6, 5.5}}, {{5.6, 3.5}, {5.6, 2.5}}, {{6.05, 5.5}, {6.05, 9.5}}});
  Grid<std::uint8_t> cells(12, 12, 0);
  cells.at(7, 4) = static_cast<std::uint8_t>(LandUse::SecondaryRoad);  // centre (7.5, 7.5)
  IntersectionSimplificationStats st;
  RoadGraph literal = graph;
  EXPECT_GT(farthestAfterB5(literal, cells, false, st), 1.6);
  EXPECT_EQ(st.nodesContracted, 1u);
  RoadGraph guarded = graph;
  EXPECT_NEAR(farthestAfterB5(guarded, cells, true, st), 1.45, 1e-9);
  EXPECT_EQ(st.nodesContracted, 0u);
  EXPECT_EQ(st.contractionsKept, 1u);
  EXPECT_EQ(guarded.aliveCount(), 7u);
  EXPECT_EQ(countDegree(guarded, 3), 1);
}

TEST(IntersectionSimplification, AChainOfContractionsStopsBeforeItUncoversARoadCell) {
  // North of the intersection (5.5, 5.8) the road turns back on itself: (5.5, 6.25) then (5.5, 5.35),
  // both within 0.5 pw, then away south-west. The road cell centred at (5.5, 7.5) is 1.25 cells from
  // the first link; contracting both nodes leaves it 1.7 cells from every road.
  const RoadGraph graph = intersectionWithArms(
      {5.5, 5.8},
      {{{3.5, 5.8}, {2.5, 5.8}}, {{7.5, 5.8}, {8.5, 5.8}}, {{5.5, 6.25}, {5.5, 5.35}, {2.5, 1.5}}});
  Grid<std::uint8_t> cells(12, 12, 0);
  cells.at(5, 4) = static_cast<std::uint8_t>(LandUse::SecondaryRoad);  // centre (5.5, 7.5)
  IntersectionSimplificationStats st;
  RoadGraph literal = graph;
  EXPECT_NEAR(farthestAfterB5(literal, cells, false, st), 1.7, 1e-9);
  EXPECT_EQ(st.nodesContracted, 2u);
  RoadGraph guarded = graph;
  EXPECT_NEAR(farthestAfterB5(guarded, cells, true, st), 1.25, 1e-9);
  EXPECT_EQ(st.contractionsKept, 1u);
}

TEST(IntersectionSimplification, ZeroDeadEndAngleRemovesNoDeadEnd) {
  // A dead end exactly along another arm: rounded cosines of parallel links can exceed cos 0 = 1.
  RoadGraph g;
  const int x = g.addNode({0, 0}, NodeType::Secondary);
  const int far = g.addNode({19, 12}, NodeType::Secondary), dead = g.addNode({76, 48}, NodeType::Secondary);
  const int s = g.addNode({0, -3}, NodeType::Secondary), s2 = g.addNode({0, -6}, NodeType::Secondary);
  const int far2 = g.addNode({40, 30}, NodeType::Secondary);
  for (int arm : {far, dead, s}) g.link(x, arm);
  g.link(s, s2);
  g.link(far, far2);
  IntersectionSimplificationOptions keep;
  keep.deadEndAngle = 0.0;
  EXPECT_EQ(simplifyIntersections(g, keep).deadEndsRemoved, 0u);
}

TEST(RoadOutput, SegmentsRunBetweenEndsInWalkOrderAndRingsStartAtTheirLowestNode) {
  RoadGraph g;
  // A ring of four degree-2 nodes first (ids 0-3, linked 0-3-2-1-0 so that node 0's first link is 3),
  // then a path 4-5-6 whose node 6 is an intersection with two dead ends 7 and 8.
  for (const Vec2& p : {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}) g.addNode(p, NodeType::Secondary);
  g.link(0, 3);
  g.link(3, 2);
  g.link(2, 1);
  g.link(1, 0);
  for (const Vec2& p : {Vec2(5, 0), Vec2(6, 0), Vec2(7, 0), Vec2(8, 1), Vec2(8, -1)})
    g.addNode(p, NodeType::Secondary);
  g.link(6, 5);  // the chain 4-5-6 is listed from 6 first; its walk still starts at end 4
  g.link(5, 4);
  g.link(6, 7);
  g.link(6, 8);
  const RoadNetwork net = buildRoadNetwork(g);
  ASSERT_EQ(net.segments.size(), 4u);
  // Ends are numbered by node id (4, 6, 7, 8), then the ring's start node.
  EXPECT_EQ(net.segments[0].points, (LineString{{5, 0}, {6, 0}, {7, 0}}));  // from end 4, its only slot
  EXPECT_EQ(net.segments[1].points, (LineString{{7, 0}, {8, 1}}));          // from 6, slot 1 (slot 0 used)
  EXPECT_EQ(net.segments[2].points, (LineString{{7, 0}, {8, -1}}));
  EXPECT_EQ(net.segments[3].points, (LineString{{0, 0}, {0, 1}, {1, 1}, {1, 0}, {0, 0}}));  // via link 3
  EXPECT_EQ(net.segments[3].fromNode, net.segments[3].toNode);
  EXPECT_EQ(net.nodes.size(), 5u);
  EXPECT_EQ(net.nodes[4].kind, NetworkNodeKind::Road);
}

// The "any" query the node-moving stages ask (issue 21): it must see every node `within` returns and no
// other, and stop at the first that qualifies.
TEST(NodeIndex, AnyWithinVisitsExactlyTheNodesWithinAndStopsAtTheFirstHit) {
  RoadGraph g;
  for (int row = 0; row < 40; ++row)
    for (int col = 0; col < 40; ++col)
      g.addNode({col * 0.7 + 0.05 * (row % 3), row * 0.9 + 0.03 * (col % 5)}, NodeType::Secondary);
  const NodeIndex index(g, 4.0);
  for (const Vec2& p : {Vec2{13.3, 17.1}, Vec2{0.0, 0.0}, Vec2{27.2, 35.0}, Vec2{-3.0, 5.0}}) {
    for (double r : {0.5, 2.0, 6.1, 9.0}) {
      std::vector<int> seen;
      EXPECT_FALSE(index.anyWithin(p, r, [&](int k) {
        seen.push_back(k);
        return false;
      }));
      std::sort(seen.begin(), seen.end());
      EXPECT_EQ(seen, index.within(p, r)) << p.x << " " << p.y << " r " << r;
      if (seen.size() < 2) continue;
      int visits = 0;
      const int wanted = seen[seen.size() / 2];
      EXPECT_TRUE(index.anyWithin(p, r, [&](int k) {
        ++visits;
        return k == wanted;
      }));
      EXPECT_LE(visits, static_cast<int>(seen.size()));
      int afterHit = 0;
      bool hit = false;
      index.anyWithin(p, r, [&](int k) {
        if (hit) ++afterHit;
        hit = hit || k == wanted;
        return k == wanted;
      });
      EXPECT_EQ(afterHit, 0);
    }
  }
}
