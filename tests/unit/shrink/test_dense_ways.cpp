// Back to vector without new crossings (spec §B.11; issue 19 "topology: no new crossings"): densified
// ways, crossing-safe simplification, and the way separation of seam carving.
#include <gtest/gtest.h>

#include <vector>

#include "urbanvec/shrink/dense_ways.hpp"
#include "urbanvec/shrink/seam_carving.hpp"

namespace urbanvec::shrink {
namespace {

TEST(DenseWays, DensifySharesTheSyntheticPointsOfASharedSegment) {
  std::vector<Vec2> pos{{0, 0}, {10, 0}, {10, 5}};
  std::vector<Vec2> shadow = pos;
  const auto dense = densifyWays({{0, 1}, {1, 0, 2}}, 1.0, pos, shadow);
  ASSERT_EQ(dense[0].size(), 11u);  // 9 synthetic points, 1 m apart
  EXPECT_EQ(pos.size(), 3u + 9u + 11u);
  // The second way runs 1 -> 0 over the same points, reversed.
  for (size_t i = 0; i < 11; ++i) EXPECT_EQ(dense[1][i], dense[0][10 - i]);
  for (size_t i = 1; i < dense[1].size(); ++i)
    EXPECT_LE(distance(pos[static_cast<size_t>(dense[1][i])], pos[static_cast<size_t>(dense[1][i - 1])]),
              1.0 + 1e-12);
}

TEST(DenseWays, SimplifyKeepsPointsWhoseShortcutWouldCrossAnotherWay) {
  // Way 0: a bump from (0,0) over (5,2) to (10,0) of synthetic points; way 1: a short street at
  // y = 1 under the bump. Dropping the bump's top points would cross way 1; a straight stretch
  // elsewhere is simplified away.
  std::vector<Vec2> pos{{0, 0}, {10, 0}, {4, 1}, {6, 1}, {2.5, 1.0}, {5, 2}, {7.5, 1.0}, {20, 0}, {15, 0}};
  const std::vector<std::vector<int>> ways{{0, 4, 5, 6, 1, 8, 7}, {2, 3}};
  std::vector<char> removable(pos.size(), 0), carved(pos.size(), 0);
  removable[4] = removable[5] = removable[6] = removable[8] = 1;
  SimplifyStats stats;
  const auto out = simplifyWithoutCrossings(ways, pos, removable, carved, 5.0, &stats);
  EXPECT_EQ(out[1], (std::vector<int>{2, 3}));
  EXPECT_EQ(out[0].front(), 0);
  EXPECT_EQ(out[0].back(), 7);
  EXPECT_NE(std::find(out[0].begin(), out[0].end(), 5), out[0].end()) << "the bump's top must stay";
  EXPECT_EQ(std::find(out[0].begin(), out[0].end(), 8), out[0].end()) << "the straight stretch is simplified";
  EXPECT_EQ(stats.removed, static_cast<int>(ways[0].size() - out[0].size()));
  // Without the other way the whole bump goes (tolerance 5 m); the other way inside the pocket of the
  // bump (no crossing, but it would change sides) keeps it in the first case.
  const auto alone = simplifyWithoutCrossings({ways[0]}, pos, removable, carved, 5.0);
  EXPECT_EQ(alone[0], (std::vector<int>{0, 1, 7}));
}

TEST(DenseWays, StraighteningMovesThatCrossOrJumpAnotherWayAreReverted) {
  // Way 0: a bent street (0,0)-(5,3)-(10,0); way 1: a short street at y = 1..2 under the bend, way 2:
  // a street far away that moves and crosses nothing. Straightening way 0 (its bend point to (5,0))
  // would pass over way 1: way 0 keeps its carved line; way 2 keeps its move.
  const std::vector<Vec2> from{{0, 0}, {5, 3}, {10, 0}, {5, 1}, {5, 2}, {0, 10}, {5, 13}, {10, 10}};
  std::vector<Vec2> to = from;
  to[1] = {5, 0};
  to[6] = {5, 10};
  const std::vector<std::vector<int>> ways{{0, 1, 2}, {3, 4}, {5, 6, 7}};
  EXPECT_EQ(revertCrossingMoves(ways, from, to), 1);
  EXPECT_EQ(to[1].y, 3.0);
  EXPECT_EQ(to[6].y, 10.0);
  // Way 1 entirely inside the swept triangle (no crossing with the final line, but it changes sides).
  std::vector<Vec2> from2 = from, to2;
  from2[3] = {5, 1.5};
  from2[4] = {5.5, 1.5};
  to2 = from2;
  to2[1] = {5, 1};
  EXPECT_EQ(revertCrossingMoves(ways, from2, to2), 1);
  EXPECT_EQ(to2[1].y, 3.0);
  // Straightening that stays above way 1 is kept.
  std::vector<Vec2> to3 = from;
  to3[1] = {5, 2.5};
  EXPECT_EQ(revertCrossingMoves(ways, from, to3), 0);
  EXPECT_EQ(to3[1].y, 2.5);
}

TEST(DenseWays, SeamsNeverRemoveAPixelBetweenTwoWaysWithinAPixel) {
  // Two vertical streets in adjacent columns 3 and 4 of a 10x6 image, zero energy everywhere: without
  // separation the cheapest seams may take either; with it neither column (nor its neighbours that
  // touch the other way) can be removed, so seams go elsewhere and both ways keep their gap.
  const int w = 10, h = 6;
  std::vector<float> energy(static_cast<size_t>(w * h), 0.0f);
  std::vector<int> labels(energy.size(), -1);
  for (int r = 0; r < h; ++r)
    labels[static_cast<size_t>(r * w + 3)] = 0, labels[static_cast<size_t>(r * w + 4)] = 1;
  const std::vector<int> pieceWay{0, 1};
  const CarveResult c = carveSeams(energy, w, h, 6, 0, SeamOrder::Blocks, {}, &labels, &pieceWay);
  EXPECT_EQ(c.verticalRemoved, 6);
  for (int r = 0; r < h; ++r) {
    EXPECT_GE(c.finalRow[static_cast<size_t>(r * w + 3)], 0);
    EXPECT_GE(c.finalRow[static_cast<size_t>(r * w + 4)], 0);
    EXPECT_EQ(c.finalCol[static_cast<size_t>(r * w + 4)], c.finalCol[static_cast<size_t>(r * w + 3)] + 1);
  }
  EXPECT_EQ(c.separationFrozen, static_cast<size_t>(2 * h));
  // Two ways two columns apart: the gap column may go, but then they are neighbours and stay so.
  std::vector<int> apart(energy.size(), -1);
  for (int r = 0; r < h; ++r)
    apart[static_cast<size_t>(r * w + 2)] = 0, apart[static_cast<size_t>(r * w + 4)] = 1;
  std::vector<float> cheapGap = energy;
  for (int r = 0; r < h; ++r) cheapGap[static_cast<size_t>(r * w + 3)] = -1.0f;  // the gap goes first
  const CarveResult d = carveSeams(cheapGap, w, h, 8, 0, SeamOrder::Blocks, {}, &apart, &pieceWay);
  for (int r = 0; r < h; ++r) {
    EXPECT_LT(d.finalRow[static_cast<size_t>(r * w + 3)], 0);
    EXPECT_GE(d.finalRow[static_cast<size_t>(r * w + 2)], 0);
    EXPECT_GE(d.finalRow[static_cast<size_t>(r * w + 4)], 0);
  }
  EXPECT_EQ(d.verticalRemoved, 8 - 0 - (w - 2 - 8 < 0 ? 2 : 0));
}

TEST(DenseWays, AWayCarriedAlongBySeamsIsKeptApartFromTheWayItReaches) {
  // Way 0 in column 2, way 1 in column 4, column 3 empty; column 4 is the cheapest, then column 3. The
  // first seam takes column 4: way 1 collapses onto column 3, now next to way 0, so column 3 must not
  // go (it would put both ways in one pixel of column 2); the second seam goes elsewhere.
  const int w = 8, h = 3;
  std::vector<float> energy(static_cast<size_t>(w * h), 0.0f);
  std::vector<int> labels(energy.size(), -1);
  for (int r = 0; r < h; ++r) {
    labels[static_cast<size_t>(r * w + 2)] = 0, labels[static_cast<size_t>(r * w + 4)] = 1;
    energy[static_cast<size_t>(r * w + 4)] = -3.0f, energy[static_cast<size_t>(r * w + 3)] = -2.0f;
  }
  const std::vector<int> pieceWay{0, 1};
  const CarveResult c = carveSeams(energy, w, h, 2, 0, SeamOrder::Blocks, {}, &labels, &pieceWay);
  EXPECT_EQ(c.verticalRemoved, 2);
  for (int r = 0; r < h; ++r) {
    EXPECT_LT(c.finalRow[static_cast<size_t>(r * w + 4)], 0);
    EXPECT_GE(c.finalRow[static_cast<size_t>(r * w + 3)], 0) << "the pixel holding way 1 now";
    EXPECT_GE(c.finalRow[static_cast<size_t>(r * w + 2)], 0);
    EXPECT_EQ(c.finalCol[static_cast<size_t>(r * w + 3)], c.finalCol[static_cast<size_t>(r * w + 2)] + 1);
  }
}

}  // namespace
}  // namespace urbanvec::shrink
