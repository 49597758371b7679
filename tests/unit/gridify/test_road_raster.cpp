// Rasterization rules of gridify (issue 2 §2 "Tests: unit tests for the rasterization rules").
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "urbanvec/gridify/road_raster.hpp"

using namespace urbanvec;
using namespace urbanvec::gridify;

namespace {

std::size_t countClass(const Grid<std::uint8_t>& g, LandUse use) {
  std::size_t n = 0;
  for (std::uint8_t v : g.cells) n += v == static_cast<std::uint8_t>(use);
  return n;
}

/// Number of 4-connected components of road cells (or, with `road` false, of the other cells: the
/// blocks vectorize A2 finds).
int roadComponents(const Grid<std::uint8_t>& g, bool road = true) {
  Grid<int> seen(g.width, g.height, 0);
  int components = 0;
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c) {
      if ((g.at(c, r) != 0) != road || seen.at(c, r)) continue;
      ++components;
      std::vector<Cell> stack{{c, r}};
      seen.at(c, r) = 1;
      while (!stack.empty()) {
        auto [x, y] = stack.back();
        stack.pop_back();
        for (auto [dx, dy] : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}}) {
          if (g.inside(x + dx, y + dy) && (g.at(x + dx, y + dy) != 0) == road && !seen.at(x + dx, y + dy)) {
            seen.at(x + dx, y + dy) = 1;
            stack.push_back({x + dx, y + dy});
          }
        }
      }
    }
  return components;
}

}  // namespace

TEST(TraverseCells, DiagonalBecomesFourConnectedStaircase) {
  std::vector<Cell> cells;
  traverseCells({0.5, 0.5}, {5.5, 5.5}, cells);  // through cell corners exactly
  ASSERT_EQ(cells.front(), Cell(0, 0));
  ASSERT_EQ(cells.back(), Cell(5, 5));
  EXPECT_EQ(cells.size(), 11u);  // 5 steps right + 5 steps down + start
  for (size_t i = 1; i < cells.size(); ++i)
    EXPECT_EQ(std::abs(cells[i].first - cells[i - 1].first) + std::abs(cells[i].second - cells[i - 1].second),
              1);
}

TEST(RoadRaster, DiagonalSecondaryIsOneCellWideStaircase) {
  RoadRaster out = rasterizeRoads({{{{2.3, 2.6}, {27.7, 21.2}}, LandUse::SecondaryRoad}}, 30, 25);
  const RoadWidthReport report = checkRoadWidths(out.classes);
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.secondaryBlocks2x2, 0u);
  EXPECT_EQ(report.diagonalOnlyLinks, 0u);
  EXPECT_EQ(roadComponents(out.classes), 1);
  // A 4-connected path from (2,2) to (27,21) has exactly |dx| + |dy| + 1 cells.
  EXPECT_EQ(countClass(out.classes, LandUse::SecondaryRoad), 25u + 19u + 1u);
  EXPECT_EQ(countClass(out.classes, LandUse::PrimaryRoad), 0u);
  EXPECT_TRUE(out.rasterized[0]);
}

TEST(RoadRaster, PrimaryIsTwoCellsWideEverywhere) {
  RoadRaster out =
      rasterizeRoads({{{{3.2, 4.1}, {30.6, 18.3}, {31.0, 35.2}, {8.4, 37.9}}, LandUse::PrimaryRoad}}, 40, 42);
  const RoadWidthReport report = checkRoadWidths(out.classes);
  EXPECT_EQ(report.primaryOutside2x2, 0u);
  EXPECT_EQ(report.primaryBlocks3x3, 0u);
  EXPECT_EQ(report.diagonalOnlyLinks, 0u);
  EXPECT_EQ(roadComponents(out.classes), 1);
  // A straight horizontal primary is exactly 2 rows tall.
  RoadRaster straight = rasterizeRoads({{{{2.0, 10.2}, {30.0, 10.2}}, LandUse::PrimaryRoad}}, 35, 20);
  std::set<int> rows;
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 35; ++c)
      if (straight.classes.at(c, r) == static_cast<std::uint8_t>(LandUse::PrimaryRoad)) rows.insert(r);
  EXPECT_EQ(rows, (std::set<int>{9, 10}));
}

TEST(RoadRaster, DualCarriagewayMergesIntoOneTwoWideRoad) {
  // Two carriageways 2 cells apart would paint a 4-wide band; they merge into one 2-wide road.
  for (double gap : {1.0, 2.0}) {
    RoadRaster out = rasterizeRoads({{{{10.1, 1.0}, {10.1, 28.0}}, LandUse::PrimaryRoad},
                                     {{{10.1 + gap, 1.0}, {10.1 + gap, 28.0}}, LandUse::PrimaryRoad}},
                                    25, 30);
    const RoadWidthReport report = checkRoadWidths(out.classes);
    EXPECT_TRUE(report.ok()) << "gap " << gap << ": 3x3 " << report.primaryBlocks3x3 << " outside "
                             << report.primaryOutside2x2;
    EXPECT_EQ(roadComponents(out.classes), 1);
  }
  // Diagonal carriageways too.
  RoadRaster diagonal = rasterizeRoads({{{{2.0, 2.0}, {25.0, 25.0}}, LandUse::PrimaryRoad},
                                        {{{4.2, 2.0}, {27.2, 25.0}}, LandUse::PrimaryRoad}},
                                       32, 32);
  EXPECT_TRUE(checkRoadWidths(diagonal.classes).ok());
}

TEST(RoadRaster, ParallelSecondaryRoadsNeverFormTwoByTwoBlocks) {
  RoadRaster out = rasterizeRoads({{{{1.5, 5.5}, {20.5, 5.5}}, LandUse::SecondaryRoad},
                                   {{{1.5, 6.5}, {20.5, 6.5}}, LandUse::SecondaryRoad},
                                   {{{3.2, 0.4}, {18.7, 14.9}}, LandUse::SecondaryRoad}},
                                  25, 16);
  const RoadWidthReport report = checkRoadWidths(out.classes);
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(roadComponents(out.classes), 1);
  EXPECT_GT(out.adjustments, 0u);
}

TEST(RoadRaster, StreetsCrossingAtASlantKeepTheirFourBlocksApart) {
  // Two perpendicular secondary streets at 30-60 degrees to the grid, crossing at several sub-cell
  // offsets: their staircases can overlap in a 2x2 window none of whose cells can go without cutting
  // an arm off; the crossing is redrawn as a plus, so the four quadrants stay four blocks (issue 20:
  // 19 raw blocks for 32 faces on a street grid at 60 degrees before).
  int cases = 0;
  for (double angle = 30; angle <= 60; angle += 5)
    for (double offset = 0; offset < 1; offset += 0.125) {
      const double t = angle * M_PI / 180;
      const Vec2 centre{20 + offset, 20 + 0.37 * offset}, u{std::cos(t), std::sin(t)}, v{-u.y, u.x};
      const std::vector<PixelRoad> roads = {{{centre - u * 30, centre + u * 30}, LandUse::SecondaryRoad},
                                            {{centre - v * 30, centre + v * 30}, LandUse::SecondaryRoad}};
      const RoadRaster raster = rasterizeRoads(roads, 41, 41);
      EXPECT_TRUE(checkRoadWidths(raster.classes).ok()) << angle << " " << offset;
      EXPECT_EQ(roadComponents(raster.classes), 1) << angle << " " << offset;
      EXPECT_EQ(roadComponents(raster.classes, false), 4) << angle << " " << offset;
      ++cases;
    }
  EXPECT_EQ(cases, 56);
}

TEST(RoadRaster, PrimaryWinsOverSecondaryAndClassCodes) {
  RoadRaster out = rasterizeRoads({{{{1.5, 8.0}, {28.5, 8.0}}, LandUse::PrimaryRoad},
                                   {{{15.5, 0.5}, {15.5, 15.5}}, LandUse::SecondaryRoad}},
                                  30, 16);
  EXPECT_EQ(out.classes.at(15, 7), 3);  // the crossing is primary
  EXPECT_EQ(out.classes.at(15, 8), 3);
  EXPECT_EQ(out.classes.at(15, 2), 2);  // secondary elsewhere
  EXPECT_EQ(out.classes.at(15, 13), 2);
  EXPECT_TRUE(checkRoadWidths(out.classes).ok());
  EXPECT_EQ(roadComponents(out.classes), 1);
}

TEST(RoadWidthCheck, FindsEachViolation) {
  Grid<std::uint8_t> g(6, 6, 0);
  g.at(1, 1) = g.at(2, 1) = g.at(1, 2) = g.at(2, 2) = 2;  // 2x2 secondary
  g.at(4, 4) = 3;                                         // lone primary cell
  g.at(5, 5) = 2;                                         // diagonal-only to (4,4)
  const RoadWidthReport r = checkRoadWidths(g);
  EXPECT_EQ(r.secondaryBlocks2x2, 1u);
  EXPECT_EQ(r.primaryOutside2x2, 1u);
  EXPECT_EQ(r.diagonalOnlyLinks, 1u);
  Grid<std::uint8_t> wide(4, 4, 3);
  EXPECT_EQ(checkRoadWidths(wide).primaryBlocks3x3, 4u);
}

TEST(TruthRoads, OnlyThePiecesNearRoadCellsAreKept) {
  // Road cells along row 2 from column 0 to 9; the centreline follows them, then leaves at column 10
  // for 10 more cells over land.
  Grid<std::uint8_t> classes(30, 10, 0);
  for (int c = 0; c < 10; ++c) classes.at(c, 2) = 2;
  const LineString line{{0.5, 2.5}, {20.5, 2.5}};
  const MultiLineString parts = partsOnRoadCells(line, classes, 1.0);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_DOUBLE_EQ(parts[0].front().x, 0.5);
  // The last road cell's centre is (9.5, 2.5): the kept piece ends at the last quarter-cell sample
  // within 1 cell of it, 10.5, and keeps no inner vertex on the straight run.
  EXPECT_NEAR(parts[0].back().x, 10.5, 1e-9);
  EXPECT_EQ(parts[0].size(), 2u);
  // A centreline on its own diagonal staircase stays whole.
  Grid<std::uint8_t> stairs(12, 12, 0);
  for (int k = 0; k < 10; ++k) stairs.at(k, k) = stairs.at(k + 1, k) = 2;
  const MultiLineString diagonal = partsOnRoadCells({{0.5, 0.5}, {10.0, 10.0}}, stairs, 1.0);
  ASSERT_EQ(diagonal.size(), 1u);
  EXPECT_NEAR(length(diagonal[0]), length(LineString{{0.5, 0.5}, {10.0, 10.0}}), 1e-9);
}
