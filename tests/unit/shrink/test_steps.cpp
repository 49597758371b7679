// The skeleton steps of city shrinking (spec §B.2-§B.7, §H.2 items 1-5) and the whole pipeline on a
// synthetic grid city (§H.2 items 6-8).
#include <gtest/gtest.h>

#include <cmath>

#include "urbanvec/core/error.hpp"
#include "urbanvec/shrink/cleaning.hpp"
#include "urbanvec/shrink/cluster_connection.hpp"
#include "urbanvec/shrink/dead_end_connection.hpp"
#include "urbanvec/shrink/indirect_streets.hpp"
#include "urbanvec/shrink/shrink.hpp"
#include "urbanvec/shrink/street_selection.hpp"

namespace urbanvec::shrink {
namespace {

int addNode(City& city, double x, double y) {
  city.nodes.push_back({static_cast<std::int64_t>(city.nodes.size()) + 1, {x, y}, true});
  return static_cast<int>(city.nodes.size()) - 1;
}

/// n x n grid of nodes `spacing` metres apart; one way per row (ids 100+r) and per column (200+c).
City gridCity(int n, double spacing, std::vector<std::vector<int>>* gridOut = nullptr) {
  City city;
  std::vector<std::vector<int>> g(static_cast<size_t>(n), std::vector<int>(static_cast<size_t>(n)));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      g[static_cast<size_t>(r)][static_cast<size_t>(c)] = addNode(city, c * spacing, r * spacing);
  for (int r = 0; r < n; ++r) {
    CityWay w{100 + r, {}, r == n / 2 ? "primary" : "residential", "row"};
    for (int c = 0; c < n; ++c) w.nodes.push_back(g[static_cast<size_t>(r)][static_cast<size_t>(c)]);
    city.streets.push_back(w);
  }
  for (int c = 0; c < n; ++c) {
    CityWay w{200 + c, {}, "residential", "column"};
    for (int r = 0; r < n; ++r) w.nodes.push_back(g[static_cast<size_t>(r)][static_cast<size_t>(c)]);
    city.streets.push_back(w);
  }
  if (gridOut) *gridOut = g;
  return city;
}

TEST(Cleaning, DropsNodesOutsideTheBoundsAndShortPieces) {
  City city;
  for (int i = 0; i < 6; ++i) addNode(city, i, 0);
  city.nodes[2].inBounds = false;
  city.nodes[4].inBounds = false;
  city.streets.push_back({1, {0, 1, 2, 3, 4, 5}, "residential", ""});
  city.streets.push_back({2, {0, 0}, "residential", ""});
  const CleaningStats stats = cleanCity(city, {});
  ASSERT_EQ(city.streets.size(), 1u);  // [0 1] kept; [3] and [5] are single nodes; way 2 collapses
  EXPECT_EQ(city.streets[0].nodes, (std::vector<int>{0, 1}));
  EXPECT_EQ(stats.nodesOutsideBounds, 2);
  EXPECT_EQ(stats.emptyWays, 3);
  City kept = city;
  CleaningOptions keepAll;
  keepAll.removeOutsideBounds = false;
  City again;
  for (int i = 0; i < 3; ++i) addNode(again, i, 0);
  again.nodes[1].inBounds = false;
  again.streets.push_back({1, {0, 1, 2}, "residential", ""});
  cleanCity(again, keepAll);
  EXPECT_EQ(again.streets[0].nodes.size(), 3u);
}

TEST(Selection, WeightsFollowTheThesisFormulas) {
  City city;
  const int a = addNode(city, 0, 0), b = addNode(city, 100, 0), c = addNode(city, 300, 0),
            d = addNode(city, 100, 50);
  city.streets.push_back({1, {a, b, c}, "primary", ""});  // longest, 1 intersection (b)
  city.streets.push_back({2, {b, d}, "footway", ""});     // shortest, 1 intersection
  city.streets.push_back({3, {c, d}, "tertiary", ""});
  std::vector<Place> places(1);
  places[0].appearW = 0.6;
  places[0].streetIds = {3};
  const StreetGraph g = buildStreetGraph(city.nodes, city.streets);
  const auto importance = findImportantStreets(city, places, {});
  const Selection s = selectStreets(city, g, importance, {});
  // Street 1: strT 0.25 + 0.1 * nInt/nInt_M (2/2: b and c are shared) + 0.1 * (300 - 50)/(300 - 50).
  EXPECT_NEAR(s.scores[0].impW, 0.25 + 0.1 + 0.1, 1e-12);
  // Street 2: other highway 0.05 + 0.1 * 2/2 + 0 (shortest).
  EXPECT_NEAR(s.scores[1].impW, 0.05 + 0.1, 1e-12);
  EXPECT_NEAR(s.scores[2].impW, 0.5 + 0.5 * 0.6, 1e-12);
  EXPECT_NEAR(s.scores[0].impD, s.scores[0].impW / 300.0, 1e-12);
  SelectionOptions o;
  EXPECT_DOUBLE_EQ(streetTypeWeight("motorway", o), 0.30);
  EXPECT_DOUBLE_EQ(streetTypeWeight("secondary", o), 0.20);
  EXPECT_DOUBLE_EQ(streetTypeWeight("residential", o), 0.10);
  EXPECT_DOUBLE_EQ(streetTypeWeight("service", o), 0.05);
}

TEST(Selection, KeepsRoundShfTimesTheStreetsMostImportantFirst) {
  City city = gridCity(6, 100.0);  // 12 streets
  std::vector<Place> places(1);
  places[0].appearW = 0.0;
  places[0].streetIds = {201};
  const StreetGraph g = buildStreetGraph(city.nodes, city.streets);
  const auto importance = findImportantStreets(city, places, {});
  SelectionOptions o;
  o.shrinkFactor = 0.2;  // round(2.4) = 2
  const Selection s = selectStreets(city, g, importance, o);
  EXPECT_EQ(s.selectedCount, 2);
  EXPECT_TRUE(s.selected[7]);  // the place's street (0.5) beats every unimportant one (< 0.5)
  EXPECT_TRUE(s.selected[3]);  // the primary row
}

TEST(IndirectStreets, NearestStreetOfALandmarkAndStreetsInsideABoundingArea) {
  City city = gridCity(5, 100.0);
  Place building;
  building.appearW = 0.9;
  const int p0 = addNode(city, 130, 120), p1 = addNode(city, 170, 120), p2 = addNode(city, 170, 175),
            p3 = addNode(city, 130, 175);
  building.shapes = {{p0, p1, p2, p3, p0}};
  Place area;
  area.appearW = 0.3;
  const int q0 = addNode(city, 250, 250), q1 = addNode(city, 450, 250), q2 = addNode(city, 450, 450),
            q3 = addNode(city, 250, 450);
  area.boundingRing = {q0, q1, q2, q3, q0};
  SelectionOptions o;
  o.proximityThreshold = 30.0;
  IndirectStats stats;
  const auto imp = findImportantStreets(city, {building, area}, o, &stats);
  // p0/p1 are 20 m from row 1 (y = 100); p2/p3 are 25 m from row 2 (y = 200); the columns are 30 m
  // away at most for p0 (x = 100) and p1... (x = 200): exactly 30 m, within the threshold.
  EXPECT_TRUE(imp[1].important && imp[1].indirect);
  EXPECT_TRUE(imp[2].important);
  EXPECT_DOUBLE_EQ(imp[1].appearW, 0.9);
  EXPECT_FALSE(imp[0].important);
  EXPECT_FALSE(imp[5 + 0].important);  // column x = 0
  // Nodes inside the area (300..400 x 300..400): rows 3, 4 and columns 3, 4.
  for (int w : {3, 4, 8, 9}) EXPECT_TRUE(imp[static_cast<size_t>(w)].important) << w;
  EXPECT_DOUBLE_EQ(imp[3].appearW, 0.3);
  EXPECT_EQ(stats.insideBounding, 4);
}

TEST(Connection, JoinsClustersByTheCheapestPathAndDropsUnimportantIslands) {
  City city = gridCity(5, 100.0);
  // An island street away from the grid.
  const int i0 = addNode(city, 1000, 1000), i1 = addNode(city, 1100, 1000);
  city.streets.push_back({300, {i0, i1}, "primary", ""});
  const StreetGraph g = buildStreetGraph(city.nodes, city.streets);
  std::vector<StreetImportance> imp(city.streets.size());
  imp[0].important = true;  // row 0
  imp[4].important = true;  // row 4
  Selection sel;
  sel.scores.resize(city.streets.size());
  for (auto& s : sel.scores) s.impW = 0.1, s.length = 400;
  sel.selected.assign(city.streets.size(), 0);
  sel.selected[0] = sel.selected[4] = sel.selected[10] = 1;
  ConnectionStats stats;
  const std::vector<char> in = connectClusters(city, g, sel, imp, {}, &stats);
  EXPECT_EQ(stats.clusters, 3);
  EXPECT_EQ(stats.joined, 1);
  EXPECT_EQ(stats.unreachable, 1);
  EXPECT_EQ(in[10], 0);  // the island holds no important street
  EXPECT_EQ(stats.removedClusters, 1);
  int connectors = 0;
  for (size_t w = 5; w < 10; ++w) connectors += in[w] == 2;
  EXPECT_EQ(connectors, 1);  // one column joins row 0 and row 4
  EXPECT_EQ(stats.components, 1);
  ConnectionOptions keep;
  keep.removeUnimportantClusters = false;
  EXPECT_EQ(connectClusters(city, g, sel, imp, keep)[10], 1);
}

TEST(DeadEnds, ConnectedWithinMSegmentsAsNewWaysWithoutNewDeadEnds) {
  std::vector<std::vector<int>> grid;
  City city = gridCity(5, 100.0, &grid);
  // Skeleton: the perimeter (rows 0 and 4, columns 0 and 4) plus the lower half of column 2, whose
  // top (2, 2) is the one dead end.
  city.streets.push_back({400, {grid[0][2], grid[1][2], grid[2][2]}, "residential", ""});
  const StreetGraph g = buildStreetGraph(city.nodes, city.streets);
  std::vector<char> in(city.streets.size(), 0);
  for (int w : {0, 4, 5, 9}) in[static_cast<size_t>(w)] = 1;
  in.back() = 1;
  DeadEndStats stats;
  EXPECT_TRUE(connectDeadEnds(city, g, in, 1, -1, &stats).empty());
  EXPECT_EQ(stats.deadEnds, 1);
  EXPECT_EQ(stats.remaining, 1);
  const std::vector<CityWay> added = connectDeadEnds(city, g, in, 3, -7, &stats);
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(stats.connected, 1);
  EXPECT_EQ(added[0].osmId, -7);
  // The shortest connection: 2 segments (200 m) to the perimeter; of the ties (to (2,0), (2,4) and
  // (4,2)) the lowest node, (2,0).
  EXPECT_EQ(added[0].nodes, (std::vector<int>{grid[2][2], grid[2][1], grid[2][0]}));
}

TEST(Pipeline, LandmarksTranslateNodesMoveByWholePixelsTowardsTheOrigin) {
  City city = gridCity(21, 50.0);  // 1 km square
  Place museum;
  museum.id = "m";
  museum.name = "Museum";
  museum.appearW = 1.0;
  const int a = addNode(city, 520, 520), b = addNode(city, 580, 520), c = addNode(city, 580, 560),
            d = addNode(city, 540, 590);
  museum.shapes = {{a, b, c, d, a}};
  Place hall;  // a long, low landmark: seams could pass between its corners
  hall.id = "h";
  hall.appearW = 0.8;
  const int h0 = addNode(city, 210, 260), h1 = addNode(city, 790, 260), h2 = addNode(city, 790, 290),
            h3 = addNode(city, 210, 290);
  hall.shapes = {{h0, h1, h2, h3, h0}};
  Place tower;
  tower.id = "t";
  tower.appearW = 0.7;
  tower.shapes = {{addNode(city, 120, 880)}};
  ShrinkOptions o;
  o.carving.imageSize = 100;
  o.carving.verticalSeams = 20;
  o.carving.horizontalSeams = 15;
  o.selection.shrinkFactor = 0.3;
  const ShrinkResult r = shrinkCity({city, {museum, hall, tower}}, o);
  EXPECT_EQ(r.report.value("image_width"), 100);
  EXPECT_EQ(r.report.value("seams_vertical"), 20);
  EXPECT_EQ(r.report.value("final_height"), 85);
  EXPECT_LE(r.measures.landmarkMaxDeviation, 1e-6);
  EXPECT_NEAR(r.report.value("area_ideal"), 80.0 * 85.0 / 10000.0, 1e-12);
  EXPECT_NEAR(r.measures.areaKept, 0.68, 0.08);
  EXPECT_EQ(r.measures.intersectionsKept, r.measures.intersectionsBefore);
  EXPECT_EQ(r.measures.newDeadEnds, 0);
  EXPECT_EQ(r.measures.componentsAfter, 1);
  EXPECT_EQ(r.measures.orderViolationsX + r.measures.orderViolationsY, 0);
  ASSERT_EQ(r.places.size(), 3u);
  const Polygon& moved = std::get<Polygon>(r.places[0].geometry);
  const Vec2 shift = moved.outer[0] - Vec2{520, 520};
  const double cell = r.report.value("cell_size");
  EXPECT_LE(shift.x, 1e-9);   // towards lower column indices: west
  EXPECT_GE(shift.y, -1e-9);  // towards lower row indices: north
  EXPECT_NEAR(std::fmod(std::abs(shift.x) + 1e-9, cell), 0.0, 1e-6);
  EXPECT_LE(-shift.x, cell * 20 + 1e-9);
  EXPECT_LE(shift.y, cell * 15 + 1e-9);
  EXPECT_EQ(r.seams.size(), 35u);
  EXPECT_FALSE(r.fullStreets.empty());
  // Same input, same output.
  const ShrinkResult again = shrinkCity({city, {museum, hall, tower}}, o);
  ASSERT_EQ(again.streets.size(), r.streets.size());
  for (size_t i = 0; i < r.streets.size(); ++i) EXPECT_EQ(again.streets[i].line, r.streets[i].line);
}

TEST(Pipeline, RejectsOutOfRangeOptionsAndTooManySeams) {
  City city = gridCity(5, 100.0);
  ShrinkOptions o;
  o.selection.shrinkFactor = 1.5;
  EXPECT_THROW(shrinkCity({city, {}}, o), Error);
  o = {};
  o.carving.imageSize = 50;
  o.carving.verticalSeams = 50;
  try {
    shrinkCity({city, {}}, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
    EXPECT_NE(std::string(e.what()).find("at most 49 can be removed"), std::string::npos) << e.what();
  }
  EXPECT_THROW(shrinkCity({City{}, {}}, ShrinkOptions{}), Error);
}

TEST(Pipeline, RotationTrickKeepsAGridStraight) {
  // A grid rotated by 30 degrees: with -rotate auto the seams run along its streets.
  City city = gridCity(15, 60.0);
  const Vec2 centre{420, 420};
  for (CityNode& n : city.nodes) {
    const Vec2 d = n.p - centre;
    const double t = 30.0 * M_PI / 180.0;
    n.p = {centre.x + std::cos(t) * d.x - std::sin(t) * d.y,
           centre.y + std::sin(t) * d.x + std::cos(t) * d.y};
  }
  ShrinkOptions o;
  o.carving.imageSize = 120;
  o.carving.verticalSeams = 20;
  o.carving.horizontalSeams = 20;
  o.selection.shrinkFactor = 1.0;
  o.carving.freezeAllStreetNodes = true;
  const ShrinkResult plain = shrinkCity({city, {}}, o);
  o.post.autoRotate = true;
  const ShrinkResult rotated = shrinkCity({city, {}}, o);
  EXPECT_NEAR(rotated.report.value("rotation_degrees"), -30.5, 1.0);
  EXPECT_GT(rotated.measures.rightAngleShareAfter, plain.measures.rightAngleShareAfter);
}

}  // namespace
}  // namespace urbanvec::shrink
