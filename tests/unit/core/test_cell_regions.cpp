// Cell regions traced along cell edges (core/cell_regions.hpp) against GEOS's union of the cells' squares.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "urbanvec/core/cell_regions.hpp"
#include "urbanvec/core/geos.hpp"

using namespace urbanvec;

namespace {

Grid<std::uint8_t> drawn(const std::vector<std::string>& rows) {
  Grid<std::uint8_t> g(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()), 0);
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c) g.at(c, r) = rows[r][c] == '#';
  return g;
}

size_t holeCount(const MultiPolygon& m) {
  size_t n = 0;
  for (const Polygon& p : m) n += p.holes.size();
  return n;
}

/// Traced regions cover exactly the union of the cells' squares: equal areas, nothing in the
/// symmetric difference, every polygon valid, the same polygons and holes as GEOS's union.
void expectSameAsUnion(const Grid<std::uint8_t>& mask) {
  const geos::Context ctx;
  const MultiPolygon traced = cellRegions(mask);
  std::vector<geos::GeomPtr> squares;
  const int top = mask.frameDy + mask.height;
  for (int r = 0; r < mask.height; ++r)
    for (int c = 0; c < mask.width; ++c)
      if (mask.at(c, r)) {
        const double x0 = mask.frameDx + c, y0 = top - r - 1;
        squares.push_back(
            ctx.polygon(Polygon{{{x0, y0}, {x0 + 1, y0}, {x0 + 1, y0 + 1}, {x0, y0 + 1}, {x0, y0}}, {}}));
      }
  geos::GeomPtr all = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(squares));
  geos::GeomPtr united = ctx.own(GEOSUnaryUnion_r(ctx.handle(), all.get()), "union");
  const MultiPolygon expected = ctx.toPolygons(united.get());
  ASSERT_EQ(traced.size(), expected.size());
  EXPECT_EQ(holeCount(traced), holeCount(expected));
  for (const Polygon& p : traced) {
    EXPECT_LT(signedArea(p.outer), 0.0) << "outer rings run clockwise";
    for (const Ring& h : p.holes) EXPECT_GT(signedArea(h), 0.0) << "holes run counter-clockwise";
    EXPECT_EQ(GEOSisValid_r(ctx.handle(), ctx.polygon(p).get()), 1);
  }
  geos::GeomPtr mine = ctx.multiPolygon(traced);
  geos::GeomPtr diff = ctx.own(GEOSSymDifference_r(ctx.handle(), mine.get(), united.get()), "difference");
  double a = 0.0;
  GEOSArea_r(ctx.handle(), diff.get(), &a);
  EXPECT_EQ(a, 0.0);
  EXPECT_DOUBLE_EQ(area(traced), static_cast<double>(std::count(mask.cells.begin(), mask.cells.end(), 1)));
}

}  // namespace

TEST(CellRegions, RingsHoldOnlyTurningPoints) {
  const MultiPolygon m = cellRegions(drawn({"....", ".##.", ".##.", "...."}));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].outer,
            (Ring{{1, 3}, {3, 3}, {3, 1}, {1, 1}, {1, 3}}));  // from the top-left corner, clockwise
  EXPECT_TRUE(m[0].holes.empty());
}

TEST(CellRegions, DiagonalContactsAndHoles) {
  // Two cells touching at a corner are two regions.
  const MultiPolygon diagonal = cellRegions(drawn({"#.", ".#"}));
  EXPECT_EQ(diagonal.size(), 2u);
  // A ring of cells with a hole; a hole touching the outer ring at a corner; two holes touching.
  expectSameAsUnion(drawn({"#####", "#...#", "#.#.#", "#...#", "#####"}));
  expectSameAsUnion(drawn({".####", "#...#", "#...#", "#####"}));
  expectSameAsUnion(drawn({"#####", "#.#.#", "##.##", "#.#.#", "#####"}));
  const MultiPolygon touching = cellRegions(drawn({"####", "#.##", "##.#", "####"}));
  ASSERT_EQ(touching.size(), 1u);
  EXPECT_EQ(touching[0].holes.size(), 2u);
}

TEST(CellRegions, RandomMasksMatchTheUnionOfTheirCells) {
  std::mt19937 rng(7);
  for (int k = 0; k < 40; ++k) {
    Grid<std::uint8_t> mask(3 + k % 17, 2 + (k * 7) % 19, 0);
    mask.frameDx = k % 3;
    mask.frameDy = k % 5;
    std::bernoulli_distribution fill(0.3 + 0.1 * (k % 5));
    for (auto& c : mask.cells) c = fill(rng);
    SCOPED_TRACE(k);
    expectSameAsUnion(mask);
  }
}
