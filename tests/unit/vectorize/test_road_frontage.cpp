// Road frontage (road_frontage.hpp): the parts of block outlines within a tolerance of the pavement,
// from segment-to-segment geometry, against hand-made cases and GEOS's buffer.
#include <gtest/gtest.h>

#include <cmath>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/vectorize/road_frontage.hpp"

using namespace urbanvec;
using namespace urbanvec::vectorize;

namespace {

Ring rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
}

MultiLineString frontage(const std::vector<Polygon>& pavement, const Polygon& block, double d,
                         int threads = 1) {
  return roadFacingEdges(pavement, {&block}, d, threads).front();
}

void expectLine(const LineString& got, const LineString& want, double eps) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x, want[i].x, eps) << "point " << i;
    EXPECT_NEAR(got[i].y, want[i].y, eps) << "point " << i;
  }
}

}  // namespace

// A block along a longer strip of pavement: its bottom edge lies on the strip's top edge (not equal to
// it), and its sides run d up from the strip's edge; the stretch across the ring's start is one line.
TEST(RoadFrontage, StripAlongOneSideIsOneLineAcrossTheRingStart) {
  const double d = 1e-3;
  const Polygon block{rect(0, 0, 10, 10), {}};
  const MultiLineString lines = frontage({Polygon{rect(-5, -2, 15, 0), {}}}, block, d);
  ASSERT_EQ(lines.size(), 1u);
  expectLine(lines[0], {{0, d}, {0, 0}, {10, 0}, {10, d}}, 1e-12);
  EXPECT_EQ(lines[0][1], Vec2(0, 0));  // the block's own corners, exactly
  EXPECT_EQ(lines[0][2], Vec2(10, 0));
}

// An outline edge passing a piece's corner at 0.6 d, a narrow wedge pointing at it: covered over
// ±0.8 d around the nearest point, where the edge is in the disc of radius d at the corner (a box
// around the corner would give ±d, the bands along the wedge's edges alone nothing, and GEOS's buffer
// with two segments a quadrant, whose chords cut the disc, ±0.68 d).
TEST(RoadFrontage, EdgeGrazingAPieceCornerIsCoveredWhereItIsInTheDisc) {
  const double d = 1e-2;
  const Polygon block{rect(0, 0, 10, 10), {}};
  auto wedge = [](double x) { return Polygon{{{x, 5}, {14, 4}, {14, 6}, {x, 5}}, {}}; };
  const MultiLineString lines = frontage({wedge(10 + 0.6 * d)}, block, d);
  ASSERT_EQ(lines.size(), 1u);
  expectLine(lines[0], {{10, 5 - 0.8 * d}, {10, 5 + 0.8 * d}}, 1e-12);
  // Moved away to 1.01 d: nothing.
  EXPECT_TRUE(frontage({wedge(10 + 1.01 * d)}, block, d).empty());
}

// Rings covered all round are closed lines: a block in the hole of a piece (edges equal to the hole's),
// a block inside a piece far from its edges (the stretch between no intervals at all is inside it),
// and the hole of a block filled by a piece; a block in a piece's hole far from it gets nothing.
TEST(RoadFrontage, CoveredRingsAreClosedLinesAndStretchesInsideAPieceCount) {
  const double d = 1e-3;
  const Polygon block{rect(0, 0, 10, 10), {}};
  const MultiLineString inHole = frontage({Polygon{rect(-2, -2, 12, 12), {rect(0, 0, 10, 10)}}}, block, d);
  ASSERT_EQ(inHole.size(), 1u);
  EXPECT_EQ(inHole[0], block.outer);
  const MultiLineString inside = frontage({Polygon{rect(-20, -20, 30, 30), {}}}, block, d);
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_EQ(inside[0], block.outer);
  EXPECT_TRUE(frontage({Polygon{rect(-20, -20, 30, 30), {rect(-10, -10, 20, 20)}}}, block, d).empty());
  const Polygon withHole{rect(0, 0, 10, 10), {rect(4, 4, 6, 6)}};
  const MultiLineString holeOnly = frontage({Polygon{rect(4, 4, 6, 6), {}}}, withHole, d);
  ASSERT_EQ(holeOnly.size(), 1u);
  EXPECT_EQ(holeOnly[0], withHole.holes[0]);
}

// Random rotated rectangles of pavement and random blocks: the frontage length per block is what
// GEOS's buffer (64 segments a quadrant, close to the exact band) cut with the outline gives, and the
// result is the same on 1 and 2 threads.
TEST(RoadFrontage, AgreesWithGeosBufferAndDoesNotDependOnThreads) {
  const double d = 0.3;
  std::uint64_t draw = 0;
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unitDraw(11, draw++); };
  auto box = [&](double size) {
    const Vec2 c{uniform(0, 30), uniform(0, 30)};
    const double angle = uniform(0, 3.14159), w = uniform(0.5, size), h = uniform(0.5, size);
    const Vec2 u{std::cos(angle), std::sin(angle)}, v{-u.y, u.x};
    Ring ring{c, c + u * w, c + u * w + v * h, c + v * h, c};
    return Polygon{ring, {}};
  };
  std::vector<Polygon> pavement, blocks;
  for (int i = 0; i < 120; ++i) pavement.push_back(box(4));
  for (int i = 0; i < 60; ++i) blocks.push_back(box(8));
  // Blocks that share an edge with a piece, as the outlines cut from the pavement do.
  for (int i = 0; i < 20; ++i)
    blocks.push_back(Polygon{{pavement[i].outer[1], pavement[i].outer[0], pavement[i].outer[0] + Vec2{-1, -3},
                              pavement[i].outer[1] + Vec2{2, -4}, pavement[i].outer[1]},
                             {}});
  std::vector<const Polygon*> pointers;
  for (const Polygon& b : blocks) pointers.push_back(&b);
  const std::vector<MultiLineString> one = roadFacingEdges(pavement, pointers, d, 1);
  EXPECT_EQ(roadFacingEdges(pavement, pointers, d, 2), one);

  geos::Context ctx;
  GEOSContextHandle_t h = ctx.handle();
  std::vector<geos::GeomPtr> parts;
  for (const Polygon& p : pavement) parts.push_back(ctx.polygon(p));
  geos::GeomPtr all = ctx.collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
  geos::GeomPtr band = ctx.own(GEOSBuffer_r(h, all.get(), d, 64), "band");
  int touched = 0;
  for (size_t i = 0; i < blocks.size(); ++i) {
    geos::GeomPtr outline = ctx.own(GEOSBoundary_r(h, ctx.polygon(blocks[i]).get()), "outline");
    geos::GeomPtr cut = ctx.own(GEOSIntersection_r(h, outline.get(), band.get()), "cut");
    double want = 0.0, got = 0.0;
    GEOSLength_r(h, cut.get(), &want);
    for (const LineString& l : one[i]) got += length(l);
    EXPECT_NEAR(got, want, 2e-3) << "block " << i;
    if (want > 0) ++touched;
  }
  EXPECT_GT(touched, 40);
}
