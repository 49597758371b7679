// Unit tests of the cadastre module (issue 17; spec pueyo-urban-data.md H.1).
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "urbanvec/cadastre/cadastre.hpp"
#include "urbanvec/cadastre/circuits.hpp"
#include "urbanvec/cadastre/extrusion.hpp"
#include "urbanvec/cadastre/floor_labels.hpp"
#include "urbanvec/cadastre/geometric_adjustment.hpp"
#include "urbanvec/cadastre/pre_blocks.hpp"
#include "urbanvec/cadastre/segment_cleaning.hpp"
#include "urbanvec/cadastre/vertex_collapsing.hpp"
#include "urbanvec/cadastre/vertex_merging.hpp"
#include "urbanvec/core/error.hpp"

namespace urbanvec::cadastre {
namespace {

std::vector<CadLine> square(double x, double y, double s, std::uint8_t layer) {
  return {{{{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}, {x, y}}, layer}};
}

void append(std::vector<CadLine>& a, const std::vector<CadLine>& b) {
  a.insert(a.end(), b.begin(), b.end());
}

TEST(VertexCollapsing, ChainAtSixTenthsOfTheThresholdDoesNotDrift) {
  // H.1.6: free ends along a line 0.6 T apart must not all collapse into one vertex.
  std::vector<CadLine> lines;
  for (int i = 0; i < 10; ++i) lines.push_back({{{i * 0.6, 0.0}, {i * 0.6, 10.0 + i}}, kBlockLayer});
  CollapseStats stats;
  const Linework lw = collapseVertices(lines, 1.0, stats);
  int bottom = 0;
  for (const Vec2& v : lw.vertices) bottom += v.y < 1.0 ? 1 : 0;
  EXPECT_GE(bottom, 5);  // every cluster spans less than the threshold: at least 10 * 0.6 / 1 ends stay apart
  for (const Vec2& v : lw.vertices) EXPECT_LE(std::abs(v.y), 0.0 + (v.y > 1.0 ? 1e9 : 0.0));
}

TEST(VertexCollapsing, CloseEndsMergeToTheirMean) {
  std::vector<CadLine> lines = {{{{0.0, 0.0}, {10.0, 0.0}}, kBlockLayer},
                                {{{10.3, 0.0}, {10.3, 10.0}}, kBlockLayer}};
  CollapseStats stats;
  const Linework lw = collapseVertices(lines, 1.0, stats);
  ASSERT_EQ(lw.vertices.size(), 3u);
  EXPECT_NEAR(lw.vertices[1].x, 10.15, 1e-12);
  EXPECT_EQ(stats.inputVertices, 4u);
  EXPECT_NEAR(stats.collapsedShare(), 0.25, 1e-12);
}

TEST(VertexCollapsing, SoundVerticesStayApartButFreeEndsJoin) {
  // A 0.4 m edge of a clean drawing is kept (its ends are joined by a segment and both are sound).
  std::vector<CadLine> lines = {{{{0, 0}, {5, 0}, {5.4, 0}, {5.4, 5}, {0, 5}, {0, 0}}, kBuildingLayer}};
  CollapseStats stats;
  const Linework lw = collapseVertices(lines, 1.0, stats, {}, false, true);
  EXPECT_EQ(lw.vertices.size(), 5u);
  EXPECT_EQ(lw.segments.size(), 5u);
}

TEST(VertexCollapsing, ClosestFirstJoinsEveryCopyWhateverTheDrawingOrder) {
  // A 3 x 1.2 m building drawn as four sides, each twice, every end moved on its own by up to 0.25 m:
  // copies of two corners of a short side can be within the threshold (0.75 m) of each other, but a
  // corner's own copies are closer; each corner must become the mean of its four copies, in any order.
  const Vec2 corner[4] = {{0, 0}, {3, 0}, {3, 1.2}, {0, 1.2}};
  const Vec2 jitter[16] = {{0.2, 0.1},   {-0.1, 0.2},  {0.15, -0.15}, {-0.2, -0.1}, {0.1, 0.2},  {0.2, -0.05},
                           {-0.15, 0.1}, {0.05, -0.2}, {-0.2, 0.15},  {0.1, -0.1},  {0.2, 0.05}, {-0.05, 0.2},
                           {0.15, 0.15}, {-0.1, -0.2}, {0.05, 0.1},   {-0.2, 0.05}};
  std::vector<CadLine> lines;
  for (int copy = 0; copy < 2; ++copy)
    for (int side = 0; side < 4; ++side) {
      const int j = 8 * copy + 2 * side;
      lines.push_back({{corner[side] + jitter[j], corner[(side + 1) % 4] + jitter[j + 1]}, kBuildingLayer});
    }
  std::vector<CadLine> reversed(lines.rbegin(), lines.rend());
  for (const auto* drawing : {&lines, &reversed}) {
    CollapseStats stats;
    const Linework lw = collapseVertices(*drawing, 0.75, stats, {}, false, true, true);
    ASSERT_EQ(lw.vertices.size(), 4u);  // one vertex per corner
    for (int k = 0; k < 4; ++k) {
      // At the mean of the corner's four copies: starts of side k, ends of side k - 1, both drawings.
      Vec2 mean;
      for (int copy = 0; copy < 2; ++copy)
        mean += (jitter[8 * copy + 2 * k] + jitter[8 * copy + 2 * ((k + 3) % 4) + 1]) / 4.0;
      double nearest = 1e9;
      for (const Vec2& v : lw.vertices) nearest = std::min(nearest, distance(v, corner[k] + mean));
      EXPECT_LT(nearest, 1e-9);
    }
  }
}

TEST(SegmentCleaning, TracedTwiceGivesOneCopyAndPartialOverlapsSplit) {
  Linework lw;
  lw.vertices = {{0, 0}, {10, 0}, {3, 0.05}, {7, -0.05}};
  lw.segments = {{0, 1, kBlockLayer}, {1, 0, kLotLayer}, {2, 3, kBuildingLayer}};
  SegmentCleaningStats stats;
  cleanSegments(lw, 0.5, stats);
  // 0-1 split at 2 and 3: 0-2, 2-3, 3-1; the partial copy 2-3 is one of them.
  ASSERT_EQ(lw.segments.size(), 3u);
  EXPECT_EQ(stats.duplicateSegments, 2u);
  for (const Segment& s : lw.segments)
    if ((s.a == 2 && s.b == 3) || (s.a == 3 && s.b == 2))
      EXPECT_EQ(s.layers, kBlockLayer | kLotLayer | kBuildingLayer);
}

TEST(CellGrid, QueriesGiveEachCellsIdsInInsertionOrderAndEraseUnlinksOneEntry) {
  CellGrid grid(1.0);
  auto ids = [&](double x0, double y0, double x1, double y1) {
    std::vector<int> out;
    grid.query(x0, y0, x1, y1, [&](int id) { out.push_back(id); });
    return out;
  };
  for (int id : {5, 3, 9, 3}) grid.insert({0.5, 0.5}, id);
  grid.insertBox(0.2, 0.2, 1.5, 0.4, 7);  // cells (0,0) and (1,0)
  EXPECT_EQ(ids(0.1, 0.1, 0.2, 0.2), (std::vector<int>{5, 3, 9, 3, 7}));
  EXPECT_EQ(ids(1.1, 0.1, 1.2, 0.2), (std::vector<int>{7}));
  grid.erase({0.5, 0.5}, 7);   // the tail
  grid.erase({0.5, 0.5}, 3);   // the first 3 only
  grid.erase({0.5, 0.5}, 42);  // absent: nothing
  grid.erase({9.5, 9.5}, 5);   // empty cell: nothing
  EXPECT_EQ(ids(0.1, 0.1, 0.2, 0.2), (std::vector<int>{5, 9, 3}));
  grid.insert({0.5, 0.5}, 8);  // appended after the new tail
  grid.erase({0.5, 0.5}, 5);   // the head
  EXPECT_EQ(ids(0.1, 0.1, 0.2, 0.2), (std::vector<int>{9, 3, 8}));
  std::vector<std::vector<int>> cells;
  grid.forEachCell([&](const std::vector<int>& c) { cells.push_back(c); });
  ASSERT_EQ(cells.size(), 2u);
  std::sort(cells.begin(), cells.end());
  EXPECT_EQ(cells[0], (std::vector<int>{7}));
  EXPECT_EQ(cells[1], (std::vector<int>{9, 3, 8}));
}

TEST(SegmentCleaning, CornersWhereLinesMeetStayOffANearbyLineFreeEndsMoveOntoIt) {
  // A lot line along y = 0; a closed building 0.4 m above it (a real 0.4 m strip, its two lower
  // corners within the threshold of the lot line); a lot line coming down at x = 2 stopping 0.3 m short
  // (an undershoot: a free end).
  Linework lw;
  lw.vertices = {{0, 0}, {10, 0}, {5, 0.4}, {8, 0.4}, {8, 5}, {5, 5}, {2, 5}, {2, 0.3}};
  lw.segments = {{0, 1, kLotLayer},      {2, 3, kBuildingLayer}, {3, 4, kBuildingLayer},
                 {4, 5, kBuildingLayer}, {5, 2, kBuildingLayer}, {6, 7, kLotLayer}};
  const Linework drawn = lw;
  SegmentCleaningStats stats;
  cleanSegments(lw, 0.75, stats);
  EXPECT_EQ(stats.cornersKeptOff, 2u);
  EXPECT_EQ(lw.vertices[2], drawn.vertices[2]);
  EXPECT_EQ(lw.vertices[3], drawn.vertices[3]);
  EXPECT_EQ(lw.vertices[7], Vec2(2, 0));  // the free end moved onto the lot line and splits it
  EXPECT_EQ(lw.segments.size(), 7u);
  // -snap-joined (every vertex within reach moves): the corners fold onto the lot line too.
  Linework all = drawn;
  cleanSegments(all, 0.75, stats, {}, true);
  EXPECT_EQ(stats.cornersKeptOff, 0u);
  EXPECT_EQ(all.vertices[2], Vec2(5, 0));
  EXPECT_EQ(all.vertices[3], Vec2(8, 0));
  EXPECT_EQ(all.segments.size(), 8u);
  // A vertex on the block layer still moves (a block corner whose copies split needs it).
  Linework block = drawn;
  for (Segment& s : block.segments)
    if (s.layers == kBuildingLayer) s.layers = kBuildingLayer | kBlockLayer;
  cleanSegments(block, 0.75, stats);
  EXPECT_EQ(stats.cornersKeptOff, 0u);
  EXPECT_EQ(block.vertices[2], Vec2(5, 0));
}

TEST(Circuits, FigureEightHasOneOutlineAndTwoInteriorCircuits) {
  Linework lw;
  lw.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 1}, {2, 2}, {1, 2}};
  lw.segments = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}, {2, 4, 1}, {4, 5, 1}, {5, 6, 1}, {6, 2, 1}};
  GraphStats gs;
  const PlanarGraph g = structuredGraph(lw, kBlockLayer, 0.5, gs);
  const Circuits c = findCircuits(g, 0.0);
  ASSERT_EQ(c.outlines.size(), 1u);
  EXPECT_EQ(c.faces.size(), 2u);
  EXPECT_NEAR(std::abs(signedArea(c.outlines[0])), 2.0, 1e-12);
}

TEST(Circuits, RingInsideABlockIsAHole) {
  Linework lw;
  lw.vertices = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {4, 4}, {6, 4}, {6, 6}, {4, 6}};
  lw.segments = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}, {4, 5, 1}, {5, 6, 1}, {6, 7, 1}, {7, 4, 1}};
  GraphStats gs;
  const Circuits c = findCircuits(structuredGraph(lw, kBlockLayer, 0.5, gs), 0.0);
  ASSERT_EQ(c.outlines.size(), 2u);
  EXPECT_EQ(c.depth[1], 1);
  ASSERT_EQ(c.faces.size(), 2u);
  EXPECT_NEAR(area(c.faces[0]) + area(c.faces[1]), 100.0, 1e-9);
}

TEST(Circuits, ThinFaceIsASliverUnlessAKeepPointLiesInside) {
  // A 10 x 0.2 m strip (mean width 0.196 m) and a 0.5 x 0.1 m speck (0.05 m2), side by side.
  Linework lw;
  lw.vertices = {{0, 0}, {10, 0}, {10, 0.2}, {0, 0.2}, {20, 0}, {20.5, 0}, {20.5, 0.1}, {20, 0.1}};
  lw.segments = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}, {4, 5, 1}, {5, 6, 1}, {6, 7, 1}, {7, 4, 1}};
  GraphStats gs;
  const PlanarGraph g = structuredGraph(lw, kBlockLayer, 0.05, gs);
  const Circuits dropped = findCircuits(g, 0.1, 0.34);
  EXPECT_EQ(dropped.faces.size(), 0u);
  EXPECT_EQ(dropped.slivers, 2u);
  // A point inside the strip keeps it; a point inside the speck does not (under the minimum area), nor
  // does a point outside every face.
  const Circuits kept = findCircuits(g, 0.1, 0.34, {{5, 0.1}, {20.25, 0.05}, {5, 3}});
  ASSERT_EQ(kept.faces.size(), 1u);
  EXPECT_NEAR(area(kept.faces[0]), 2.0, 1e-9);
  EXPECT_EQ(kept.thinKept, 1u);
  EXPECT_EQ(kept.slivers, 1u);
  const Circuits outside = findCircuits(g, 0.1, 0.34, {{5, 0.3}, {11, 0.1}});
  EXPECT_EQ(outside.faces.size(), 0u);
  EXPECT_EQ(outside.thinKept, 0u);
}

TEST(Pipeline, LabelledThinPartOfACleanDrawingIsKept) {
  // A clean drawing: a block, a 10 x 10 m building and beside it a 10 x 0.25 m wall drawn as a part
  // with II floors (mean width 0.24 m, under the 0.34 m sliver width).
  std::vector<CadLine> lines = square(0, 0, 40, kBlockLayer);
  append(lines, square(5, 5, 10, kBuildingLayer));
  lines.push_back({{{5, 15}, {5, 15.25}, {15, 15.25}, {15, 15}}, kBuildingLayer});
  const std::vector<CadLabel> labels = {{{10, 10}, "III"}, {{10, 15.12}, "II"}};
  CadastreOptions o;
  auto wall = [](const CadastreResult& r) {
    int n = 0;
    for (const BuildingOut& b : r.buildings)
      if (b.floors == 2) {
        ++n;
        EXPECT_NEAR(area(b.shape), 2.5, 1e-6);
      }
    return n;
  };
  const CadastreResult kept = structureCadastre(lines, labels, o);
  EXPECT_EQ(wall(kept), 1);
  EXPECT_EQ(kept.report.labelledThinKept, 1u);
  o.keepLabelledThin = false;
  const CadastreResult dropped = structureCadastre(lines, labels, o);
  EXPECT_EQ(wall(dropped), 0);
  EXPECT_EQ(dropped.report.labelledThinKept, 0u);
}

TEST(PreBlocks, UndershootAndFringeAreRepaired) {
  // A square whose last side stops 0.8 m short of the corner, plus a dangling spur.
  Linework lw;
  lw.vertices = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0.8}, {10, 5}, {13, 5}};
  lw.segments = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 4, 1}, {5, 6, 1}};
  GraphStats gs;
  const Circuits c = findCircuits(structuredGraph(lw, kBlockLayer, 2.0, gs), 0.0);
  ASSERT_EQ(c.faces.size(), 1u);
  EXPECT_NEAR(area(c.faces[0]), 100.0, 1e-9);
  EXPECT_EQ(gs.fringeEdgesRemoved, 1u);
  EXPECT_EQ(gs.undershootsToSegment + gs.cornersClosed + gs.undershootsToVertex, 1u);
}

TEST(FloorLabels, RomanArabicAndSuffixes) {
  EXPECT_EQ(parseFloorLabel("III").above, 3);
  const FloorLabel b = parseFloorLabel("-I+III");
  EXPECT_EQ(b.above, 3);
  EXPECT_EQ(b.below, 1);
  const FloorLabel t = parseFloorLabel("II+TZA");
  EXPECT_EQ(t.above, 2);
  EXPECT_EQ(t.ignoredParts, 1);
  EXPECT_EQ(parseFloorLabel(" 4 ").above, 4);
  EXPECT_EQ(parseFloorLabel("IV").above, 4);
  EXPECT_EQ(parseFloorLabel("XIV").above, 14);
  EXPECT_FALSE(parseFloorLabel("PATIO").valid);
  EXPECT_FALSE(parseFloorLabel("").valid);
}

TEST(FloorLabels, HeightFormulaAndSeededOffset) {
  EXPECT_DOUBLE_EQ(floorHeight(1, 3.0, 2.5, 0.0, 0, 0), 3.0);
  EXPECT_DOUBLE_EQ(floorHeight(3, 3.0, 2.5, 0.0, 0, 0), 8.0);
  EXPECT_DOUBLE_EQ(floorHeight(0, 3.0, 2.5, 0.5, 7, 0), 0.0);
  const double h = floorHeight(2, 3.0, 2.5, 0.3, 7, 11);
  EXPECT_NEAR(h, 5.5, 0.3);
  EXPECT_NE(h, 5.5);
  EXPECT_DOUBLE_EQ(h, floorHeight(2, 3.0, 2.5, 0.3, 7, 11));
}

TEST(Pipeline, BlocksParcelsBuildingsAndHeights) {
  // Two blocks 6 m apart; block A has two lots and a building with III floors; drawn with a gap.
  std::vector<CadLine> lines;
  append(lines, square(0, 0, 40, kBlockLayer));
  append(lines, square(46, 0, 40, kBlockLayer));
  lines.push_back({{{20, 0.3}, {20, 40}}, kLotLayer});  // starts 0.3 m short of the block side
  append(lines, square(5, 5, 10, kBuildingLayer));
  std::vector<CadLabel> labels = {{{10, 10}, "III"}, {{30, 30}, "NOTE"}};
  CadastreOptions o;
  const CadastreResult r = structureCadastre(lines, labels, o);
  EXPECT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.subBlocks.size(), 2u);
  EXPECT_EQ(r.parcels.size(), 3u);
  EXPECT_EQ(r.report.labelsNotNumbers, 1u);
  int withFloors = 0;
  for (const BuildingOut& b : r.buildings)
    if (b.floors > 0) {
      ++withFloors;
      EXPECT_EQ(b.floors, 3);
      EXPECT_DOUBLE_EQ(b.height, 8.0);
      EXPECT_NEAR(area(b.shape), 100.0, 1e-6);
      EXPECT_EQ(b.block, 0);
    }
  EXPECT_EQ(withFloors, 1);
  // Every block's area is covered by its parcels (a partition).
  double parcelArea = 0;
  for (const AreaOut& p : r.parcels) parcelArea += area(p.shape);
  EXPECT_NEAR(parcelArea, 3200.0, 1e-6);
}

/// A deterministic uniform generator (the same numbers on every platform).
struct Lcg {
  std::uint64_t s;
  double next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  }
};

/// Rectangles drawn as a messy CAD drawing: each side as 2-point segments, split at a random point
/// (30 %), drawn twice (50 %), every segment end moved on its own within `jitter` and 15 % of ends
/// over- or undershot along the segment by 0.1-0.6 m. Returns the drawing; `corners` gets the truth.
std::vector<CadLine> messyRectangles(int count, double jitter, std::vector<Vec2>& corners,
                                     std::uint64_t seed) {
  Lcg rng{seed};
  std::vector<CadLine> lines;
  for (int k = 0; k < count; ++k) {
    const double x = 30.0 * (k % 6), y = 30.0 * (k / 6);
    const double w = 3.0 + 9.0 * rng.next(), h = 3.0 + 9.0 * rng.next(), a = 0.5 * rng.next();
    const Vec2 u{std::cos(a), std::sin(a)}, v{-std::sin(a), std::cos(a)};
    const Vec2 c[4] = {{x, y}, Vec2{x, y} + u * w, Vec2{x, y} + u * w + v * h, Vec2{x, y} + v * h};
    for (const Vec2& p : c) corners.push_back(p);
    for (int i = 0; i < 4; ++i) {
      std::vector<std::pair<Vec2, Vec2>> pieces;
      const Vec2 p = c[i], q = c[(i + 1) % 4];
      if (rng.next() < 0.3) {
        const Vec2 m = p + (q - p) * (0.2 + 0.6 * rng.next());
        pieces = {{p, m}, {m, q}};
      } else {
        pieces = {{p, q}};
      }
      for (const auto& [s0, s1] : pieces)
        for (int copy = 0; copy < (rng.next() < 0.5 ? 2 : 1); ++copy) {
          Vec2 e[2] = {s0, s1};
          for (Vec2& end : e) {
            const double r = jitter * std::sqrt(rng.next()), t = 6.283185307179586 * rng.next();
            end += Vec2{r * std::cos(t), r * std::sin(t)};
          }
          const Vec2 dir = (e[1] - e[0]) / length(e[1] - e[0]);
          for (int end = 0; end < 2; ++end)
            if (rng.next() < 0.15) {
              const double shot = (0.1 + 0.5 * rng.next()) * (rng.next() < 0.5 ? -1 : 1);
              e[end] += dir * (end == 1 ? shot : -shot);
            }
          lines.push_back({{e[0], e[1]}, kBuildingLayer});
        }
    }
  }
  return lines;
}

/// Root mean square distance from each truth corner to the nearest of `vertices`.
double cornerError(const std::vector<Vec2>& corners, const std::vector<Vec2>& vertices) {
  double sum = 0.0;
  for (const Vec2& c : corners) {
    double best = 1e300;
    for (const Vec2& v : vertices) best = std::min(best, distance(c, v));
    sum += best * best;
  }
  return std::sqrt(sum / static_cast<double>(corners.size()));
}

/// The drawing collapsed (0.75 m, closest first, free ends only) and its segments cleaned: the linework
/// the geometric adjustment works on.
Linework cleanedLinework(const std::vector<CadLine>& lines) {
  CollapseStats cs;
  Linework lw = collapseVertices(lines, 0.75, cs, {}, false, true, true);
  SegmentCleaningStats ss;
  cleanSegments(lw, 0.75, ss);
  return lw;
}

TEST(GeometricAdjustment, FitBeatsTheMeanOfTheCopies) {
  // 36 rectangles drawn with 0.3 m of jitter per copy and shot ends: the fit (copies across their
  // segment, ends shot along their line down-weighted, straight split points, right angles) places
  // the corners closer to the truth than the mean of their copies.
  std::vector<Vec2> corners;
  const std::vector<CadLine> lines = messyRectangles(36, 0.3, corners, 7);
  const Linework lw = cleanedLinework(lines);
  AdjustmentStats as;
  const std::vector<Vec2> fitted = adjustedVertices(lw, AdjustmentOptions{}, as);
  const double before = cornerError(corners, lw.vertices), after = cornerError(corners, fitted);
  EXPECT_NEAR(as.noise, 0.15, 0.05);  // per-axis spread of a copy uniform in a 0.3 m disc
  EXPECT_GT(as.rightConstraints, 80u);
  EXPECT_GT(as.straightConstraints, 30u);
  // Measured: mean 0.161 m, robust fit alone 0.157, with the constraints 0.147 (0.131 with reach 2).
  EXPECT_LT(after, 0.93 * before) << "mean " << before << " fit " << after;
  // Each part helps: without the constraints, and without the robust weight along the segments.
  AdjustmentOptions plain;
  plain.straightAngle = plain.rightAngle = 0.0;
  const double unconstrained = cornerError(corners, adjustedVertices(lw, plain, as));
  EXPECT_LT(after, 0.96 * unconstrained);
  EXPECT_LT(unconstrained, 0.99 * before);
  plain.huber = 1e9;  // plain least squares: the mean of the copies again
  EXPECT_NEAR(cornerError(corners, adjustedVertices(lw, plain, as)), before, 0.02 * before);
}

/// A segment a-b drawn once, with its two ends as copies at the vertices' positions.
void drawSegment(Linework& lw, int a, int b) {
  lw.segments.push_back({a, b, kBuildingLayer});
  lw.copies.push_back({a, b, lw.vertices[static_cast<size_t>(a)]});
  lw.copies.push_back({b, a, lw.vertices[static_cast<size_t>(b)]});
}

/// A 10 m square whose corner (0, 0) is split over vertex 0 (end of the bottom side) and vertex 4 (end
/// of the left side), 0.16 m apart.
Linework splitCornerSquare() {
  Linework lw;
  lw.vertices = {{0.05, 0.1}, {10, 0}, {10, 10}, {0, 10}, {-0.1, -0.02}};
  drawSegment(lw, 0, 1);
  drawSegment(lw, 1, 2);
  drawSegment(lw, 2, 3);
  drawSegment(lw, 3, 4);
  return lw;
}

TEST(VertexMerging, CopiesOfOneCornerBecomeOneVertex) {
  Linework lw = splitCornerSquare();
  MergeStats ms;
  mergeSplitVertices(lw, 0.5, 0.34, ms);
  EXPECT_EQ(ms.merged, 1u);
  ASSERT_EQ(lw.vertices.size(), 4u);
  EXPECT_EQ(lw.segments.size(), 4u);
  // At the mean of the copies of both (one copy each).
  EXPECT_LT(distance(lw.vertices[0], Vec2{-0.025, 0.04}), 1e-9);
  for (const Segment& s : lw.segments) EXPECT_TRUE(s.a >= 0 && s.a < 4 && s.b >= 0 && s.b < 4 && s.a != s.b);
  for (const EndCopy& c : lw.copies) EXPECT_TRUE(c.vertex >= 0 && c.vertex < 4 && c.other != c.vertex);
  // Every vertex has two segments: the square is closed at the corner.
  std::vector<int> degree(4, 0);
  for (const Segment& s : lw.segments) ++degree[static_cast<size_t>(s.a)], ++degree[static_cast<size_t>(s.b)];
  EXPECT_EQ(degree, (std::vector<int>{2, 2, 2, 2}));
  // Farther apart than the merge distance: left alone.
  Linework far = splitCornerSquare();
  mergeSplitVertices(far, 0.1, 0.34, ms);
  EXPECT_EQ(ms.merged, 0u);
  EXPECT_EQ(far.vertices.size(), 5u);
}

TEST(VertexMerging, TrueShortEdgesFacesAndCrossingsAreKept) {
  // A drawn segment between them: a true short edge of the drawing, kept.
  Linework edge = splitCornerSquare();
  drawSegment(edge, 4, 0);
  MergeStats ms;
  mergeSplitVertices(edge, 0.5, 0.34, ms);
  EXPECT_EQ(ms.merged, 0u);
  EXPECT_EQ(ms.refusedDrawn, 1u);
  EXPECT_EQ(edge.vertices.size(), 5u);
  // Both joined to one vertex 3 m away, 0.4 m apart: a wedge wider than a sliver, kept.
  Linework wedge;
  wedge.vertices = {{0, 0}, {0.4, 0}, {0.2, 3}};
  drawSegment(wedge, 0, 2);
  drawSegment(wedge, 1, 2);
  mergeSplitVertices(wedge, 0.5, 0.34, ms);
  EXPECT_EQ(ms.merged, 0u);
  EXPECT_EQ(ms.refusedFace, 1u);
  // The same wedge 0.1 m wide is a sliver: merged into one line.
  wedge.vertices[1] = {0.1, 0};
  mergeSplitVertices(wedge, 0.5, 0.34, ms);
  EXPECT_EQ(ms.merged, 1u);
  EXPECT_EQ(wedge.segments.size(), 1u);
  // Merging at (0.2, 0) would swing the segment up from (0.4, 0) across the segment (0.1..0.3, 0.5).
  Linework crossing;
  crossing.vertices = {{0, 0}, {0, -5}, {0.4, 0}, {0.4, 5}, {0.1, 0.5}, {0.3, 0.5}};
  drawSegment(crossing, 0, 1);
  drawSegment(crossing, 2, 3);
  drawSegment(crossing, 4, 5);
  mergeSplitVertices(crossing, 0.5, 0.34, ms);
  EXPECT_EQ(ms.merged, 0u);
  EXPECT_EQ(ms.refusedCrossing, 1u);
  EXPECT_EQ(crossing.vertices.size(), 6u);
}

TEST(GeometricAdjustment, CleanDrawingDoesNotMove) {
  // Copies that coincide (a clean drawing, however close to square or straight) stay where they are:
  // an 88-degree corner and a 176-degree bend are kept.
  std::vector<CadLine> lines = {{{{0, 0}, {10, 0}, {20, 0.7}, {20.35, 10}, {0, 10}, {0, 0}}, kBuildingLayer},
                                {{{10, 0}, {10, 10}}, kLotLayer}};
  const Linework lw = cleanedLinework(lines);
  AdjustmentStats as;
  const std::vector<Vec2> fitted = adjustedVertices(lw, AdjustmentOptions{}, as);
  ASSERT_EQ(fitted.size(), lw.vertices.size());
  for (size_t i = 0; i < fitted.size(); ++i) EXPECT_LT(distance(fitted[i], lw.vertices[i]), 1e-6);
  EXPECT_EQ(as.verticesMoved, 0u);
}

TEST(GeometricAdjustment, ShapesBeyondTheNoiseAreLeftAlone) {
  // A 20 m wall bent by 4 degrees in its middle (0.7 m off the straight line) and an 80-degree corner,
  // drawn with jitter: neither is straightened nor squared.
  std::vector<Vec2> truth = {
      {0, 0}, {10, 0}, {20, 0.7}, {20 + 10 * std::cos(1.396), 0.7 + 10 * std::sin(1.396)}};
  Lcg rng{3};
  std::vector<CadLine> lines;
  for (int copy = 0; copy < 3; ++copy)
    for (size_t i = 1; i < truth.size(); ++i) {
      Vec2 e[2] = {truth[i - 1], truth[i]};
      for (Vec2& end : e) end += Vec2{0.2 * (rng.next() - 0.5), 0.2 * (rng.next() - 0.5)};
      lines.push_back({{e[0], e[1]}, kBuildingLayer});
    }
  const Linework lw = cleanedLinework(lines);
  AdjustmentStats as;
  const std::vector<Vec2> fitted = adjustedVertices(lw, AdjustmentOptions{}, as);
  EXPECT_EQ(as.straightConstraints, 0u);
  EXPECT_EQ(as.rightConstraints, 0u);
  EXPECT_LT(cornerError(truth, fitted), 0.1);
}

TEST(Pipeline, AdjustmentMovesOutputVerticesOnly) {
  // A noisy drawing of rectangles: the adjusted run keeps the same elements (topology is decided on
  // the means of the copies) and moves their vertices; -no-adjust reports no adjustment.
  std::vector<Vec2> corners;
  std::vector<CadLine> lines = messyRectangles(12, 0.3, corners, 11);
  append(lines, square(-20, -20, 220, kBlockLayer));
  CadastreOptions o;
  const CadastreResult fit = structureCadastre(lines, {}, o);
  o.adjust = false;
  const CadastreResult mean = structureCadastre(lines, {}, o);
  ASSERT_EQ(fit.buildings.size(), mean.buildings.size());
  EXPECT_EQ(fit.parcels.size(), mean.parcels.size());
  EXPECT_GT(fit.report.verticesAdjusted, 0u);
  EXPECT_NEAR(fit.report.adjustmentNoise, 0.15, 0.05);
  EXPECT_EQ(mean.report.verticesAdjusted, 0u);
  std::size_t moved = 0, all = 0;
  for (size_t i = 0; i < fit.buildings.size(); ++i) {
    EXPECT_NEAR(area(fit.buildings[i].shape), area(mean.buildings[i].shape),
                0.1 * area(mean.buildings[i].shape) + 1.0);
    for (size_t k = 0; k < fit.buildings[i].shape.size() && k < mean.buildings[i].shape.size(); ++k) {
      const Ring& a = fit.buildings[i].shape[k].outer;
      const Ring& b = mean.buildings[i].shape[k].outer;
      for (size_t j = 0; j < a.size() && j < b.size(); ++j, ++all)
        moved += distance(a[j], b[j]) > 1e-3 ? 1 : 0;
    }
  }
  EXPECT_GT(moved, all / 2);
}

TEST(Pipeline, RejectsBadThresholds) {
  std::vector<CadLine> lines = square(0, 0, 10, kBlockLayer);
  CadastreOptions o;
  o.collapsingThreshold = 3.0;
  o.blockThreshold = 2.0;
  try {
    structureCadastre(lines, {}, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
  }
  o.collapsingThreshold = 0.0;
  EXPECT_THROW(structureCadastre(lines, {}, o), Error);
}

TEST(Extrusion, PrismsAreWatertightWithOutwardNormals) {
  BuildingOut b;
  Polygon p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {{{4, 4}, {4, 6}, {6, 6}, {6, 4}, {4, 4}}}};
  b.shape = {p};
  b.height = 5.5;
  BuildingOut courtyard;
  courtyard.shape = {Polygon{{{20, 0}, {25, 0}, {25, 5}, {20, 5}, {20, 0}}, {}}};
  const Mesh m = extrudeBuildings({b, courtyard});
  // Every directed edge appears once and its reverse once: closed and consistently oriented.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u);
  }
  // Signed volume (divergence theorem) = area x height > 0: normals point out.
  double volume = 0;
  for (const auto& t : m.triangles) {
    const auto& a = m.vertices[static_cast<size_t>(t[0])];
    const auto& c = m.vertices[static_cast<size_t>(t[1])];
    const auto& d = m.vertices[static_cast<size_t>(t[2])];
    volume += (a[0] * (c[1] * d[2] - c[2] * d[1]) - a[1] * (c[0] * d[2] - c[2] * d[0]) +
               a[2] * (c[0] * d[1] - c[1] * d[0])) /
              6.0;
  }
  EXPECT_NEAR(volume, 96.0 * 5.5, 1e-6);
  for (int o : m.triangleObject) EXPECT_EQ(o, 0);  // the 0-height courtyard makes no prism
}

TEST(Extrusion, CityJsonLod1) {
  BuildingOut b;
  b.shape = {Polygon{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {}}};
  b.height = 8.0;
  b.floors = 3;
  const auto doc = nlohmann::json::parse(cityJsonText({b}, 32628));
  EXPECT_EQ(doc["type"], "CityJSON");
  EXPECT_EQ(doc["version"], "1.1");
  EXPECT_EQ(doc["vertices"].size(), 8u);
  const auto& obj = doc["CityObjects"]["building_0"];
  EXPECT_EQ(obj["type"], "Building");
  EXPECT_EQ(obj["geometry"][0]["lod"], "1");
  EXPECT_EQ(obj["geometry"][0]["boundaries"][0].size(), 6u);  // 4 walls + floor + roof
  EXPECT_EQ(doc["metadata"]["referenceSystem"], "https://www.opengis.net/def/crs/EPSG/0/32628");
}

}  // namespace
}  // namespace urbanvec::cadastre
