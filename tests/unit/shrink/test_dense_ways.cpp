// Back to vector without new crossings (spec §B.11; issue 19 "topology: no new crossings"): densified
// ways, crossing-safe simplification, and the crossing guard of seam carving.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "urbanvec/core/segment_contact.hpp"
#include "urbanvec/shrink/back_to_vector.hpp"
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

/// Pairs of segments (no shared point) of two ways that touch or cross after carving and did not before,
/// and pairs of one way that cross (a way may touch itself where its points collapsed onto one spot).
int newContacts(const std::vector<std::vector<int>>& dense, const std::vector<Vec2>& before,
                const std::vector<Vec2>& after) {
  std::vector<std::pair<int, int>> segs;
  std::vector<size_t> wayOf;
  for (size_t w = 0; w < dense.size(); ++w)
    for (size_t i = 1; i < dense[w].size(); ++i)
      segs.push_back({dense[w][i - 1], dense[w][i]}), wayOf.push_back(w);
  int count = 0;
  for (size_t i = 0; i < segs.size(); ++i)
    for (size_t j = i + 1; j < segs.size(); ++j) {
      const auto [a, b] = segs[i];
      const auto [c, d] = segs[j];
      if (a == c || a == d || b == c || b == d) continue;
      auto at = [](const std::vector<Vec2>& v, int k) { return v[static_cast<size_t>(k)]; };
      const SegmentContact now = segmentContact(at(after, a), at(after, b), at(after, c), at(after, d));
      if ((wayOf[i] == wayOf[j] ? now == SegmentContact::Crossing : now != SegmentContact::None) &&
          segmentContact(at(before, a), at(before, b), at(before, c), at(before, d)) == SegmentContact::None)
        ++count;
    }
  return count;
}

TEST(DenseWays, CrossingGuardRemovesEverySeamWithoutMakingWaysMeet) {
  // Random wandering ways, densified to one point per pixel, on random energies: without the guard
  // the seams make segments meet that did not; with it none do, every requested seam still goes (the
  // image has room), and only a few pixels are frozen.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int unguarded = 0;
  size_t frozen = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const int w = 40, h = 36;
    const RasterFrame frame{0.0, static_cast<double>(h), 1.0, w, h};
    std::vector<Vec2> pos;
    std::vector<std::vector<int>> ways;
    for (int k = 0; k < 7; ++k) {
      std::vector<int> way;
      Vec2 p{2 + 36 * unit(rng), 2 + 32 * unit(rng)};
      for (int step = 0; step < 6; ++step) {
        way.push_back(static_cast<int>(pos.size()));
        pos.push_back(p);
        p = {std::clamp(p.x + 12 * (unit(rng) - 0.5), 0.5, w - 0.5),
             std::clamp(p.y + 12 * (unit(rng) - 0.5), 0.5, h - 0.5)};
      }
      ways.push_back(way);
    }
    std::vector<Vec2> shadow = pos;
    const auto dense = densifyWays(ways, 1.0, pos, shadow);
    std::vector<float> energy(static_cast<size_t>(w * h));
    for (float& e : energy) e = static_cast<float>(std::floor(8 * unit(rng)));  // many ties
    const SeamWays sw = seamWaysOf(dense, pos, frame);
    for (bool guarded : {false, true}) {
      const CarveResult c =
          carveSeams(energy, w, h, 10, 8, trial % 2 ? SeamOrder::Interleaved : SeamOrder::Blocks, {},
                     guarded ? &sw : nullptr);
      const PointMapper mapper(frame, c);
      std::vector<Vec2> after(pos.size());
      for (size_t i = 0; i < pos.size(); ++i) ASSERT_TRUE(mapper.map(pos[i], true, after[i]));
      const int meets = newContacts(dense, pos, after);
      if (!guarded) {
        unguarded += meets;
        continue;
      }
      EXPECT_EQ(meets, 0) << "trial " << trial;
      EXPECT_EQ(c.verticalRemoved, 10) << "trial " << trial;
      EXPECT_EQ(c.horizontalRemoved, 8) << "trial " << trial;
      frozen += c.crossingFrozen;
    }
  }
  EXPECT_GT(unguarded, 10) << "the test must exercise the guard";
  EXPECT_GT(frozen, 0u);
  EXPECT_LT(frozen, 12u * 40u) << "only the pixels where a crossing would arise are frozen";
}

TEST(DenseWays, CrossingGuardLetsSeamsGoBetweenWaysAPixelApart) {
  // Two vertical ways in adjacent columns 1 and 2 of a 4-pixel-wide image, zero energy: the old whole
  // separation froze both columns (2 seams at most); the guard also lets the column of one way go, its
  // points collapsing onto the edge of the other way's pixel, half a pixel apart: 3 seams.
  const int w = 4, h = 6;
  const RasterFrame frame{0.0, static_cast<double>(h), 1.0, w, h};
  std::vector<Vec2> pos;
  std::vector<std::vector<int>> ways(2);
  for (int k = 0; k < 2; ++k)
    for (int r = 0; r < h; ++r) {
      ways[static_cast<size_t>(k)].push_back(static_cast<int>(pos.size()));
      pos.push_back({1.5 + k, h - r - 0.5});
    }
  const SeamWays sw = seamWaysOf(ways, pos, frame);
  const CarveResult c = carveSeams(std::vector<float>(static_cast<size_t>(w * h), 0.0f), w, h, 3, 0,
                                   SeamOrder::Blocks, {}, &sw);
  EXPECT_EQ(c.verticalRemoved, 3);
  const PointMapper mapper(frame, c);
  std::vector<Vec2> after(pos.size());
  for (size_t i = 0; i < pos.size(); ++i) ASSERT_TRUE(mapper.map(pos[i], true, after[i]));
  for (size_t r = 0; r < static_cast<size_t>(h); ++r)
    EXPECT_NEAR(after[static_cast<size_t>(h) + r].x - after[r].x, 0.5, 1e-12) << "row " << r;
  EXPECT_EQ(newContacts(ways, pos, after), 0);
}

TEST(DenseWays, GuardSaysWhenItsPixelsBlockTheSeams) {
  // Ten random ways packed into a 12x10 image, zero energy: without the guard all 10 seams go; with it
  // the last ones cannot (every path would make ways meet), no line is frozen from edge to edge, and
  // the result says that a path would exist without the guard's pixels (the reason the report gives).
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int w = 12, h = 10;
  const RasterFrame frame{0.0, static_cast<double>(h), 1.0, w, h};
  std::vector<Vec2> pos;
  std::vector<std::vector<int>> ways;
  for (int k = 0; k < 10; ++k) {
    std::vector<int> way;
    Vec2 p{0.1 + 11.8 * unit(rng), 0.1 + 9.8 * unit(rng)};
    for (int step = 0; step < 4; ++step) {
      way.push_back(static_cast<int>(pos.size()));
      pos.push_back(p);
      p = {std::clamp(p.x + 8 * (unit(rng) - 0.5), 0.1, w - 0.1),
           std::clamp(p.y + 8 * (unit(rng) - 0.5), 0.1, h - 0.1)};
    }
    ways.push_back(way);
  }
  std::vector<Vec2> shadow = pos;
  const auto dense = densifyWays(ways, 1.0, pos, shadow);
  const std::vector<float> energy(static_cast<size_t>(w * h), 0.0f);
  EXPECT_EQ(carveSeams(energy, w, h, 10, 0, SeamOrder::Blocks).verticalRemoved, 10);
  const SeamWays sw = seamWaysOf(dense, pos, frame);
  const CarveResult c = carveSeams(energy, w, h, 10, 0, SeamOrder::Blocks, {}, &sw);
  EXPECT_LT(c.verticalRemoved, 10);
  EXPECT_GT(c.verticalRemoved, 0);
  EXPECT_EQ(c.verticalBlockedAt, -1);
  EXPECT_TRUE(c.verticalBlockedByGuard);
  const PointMapper mapper(frame, c);
  std::vector<Vec2> after(pos.size());
  for (size_t i = 0; i < pos.size(); ++i) ASSERT_TRUE(mapper.map(pos[i], true, after[i]));
  EXPECT_EQ(newContacts(dense, pos, after), 0);
}

TEST(DenseWays, GuardKeepsTheOrderOfTwoLandmarks) {
  // Landmark A at x 5.9 (row 2), landmark B at x 6.1 (row 6), both frozen. The cheapest seam runs in
  // column 6 above row 6 (right of A) and column 5 from row 6 (left of B): it would move B one pixel
  // left of A. Guarded, the seam goes elsewhere and A stays left of B; every seam is still removed.
  const int w = 12, h = 8;
  const RasterFrame frame{0.0, static_cast<double>(h), 1.0, w, h};
  std::vector<float> energy(static_cast<size_t>(w * h), 1.0f);
  for (int r = 0; r < h; ++r) energy[static_cast<size_t>(r * w + (r < 6 ? 6 : 5))] = 0.0f;
  energy[static_cast<size_t>(2 * w + 5)] = energy[static_cast<size_t>(6 * w + 6)] =
      std::numeric_limits<float>::infinity();
  const std::vector<Vec2> pos{{5.9, h - 2.5}, {6.1, h - 6.5}};
  SeamWays sw = seamWaysOf({}, pos, frame);
  sw.places = {{0}, {1}};
  for (bool guarded : {false, true}) {
    const CarveResult c = carveSeams(energy, w, h, 3, 0, SeamOrder::Blocks, {}, guarded ? &sw : nullptr);
    EXPECT_EQ(c.verticalRemoved, 3);
    const PointMapper mapper(frame, c);
    Vec2 a, b;
    ASSERT_TRUE(mapper.map(pos[0], true, a));
    ASSERT_TRUE(mapper.map(pos[1], true, b));
    if (guarded) {
      EXPECT_LT(a.x, b.x);
      EXPECT_GT(c.orderFrozen, 0u);
    } else {
      EXPECT_GT(a.x, b.x) << "the test must exercise the guard";
    }
  }
}

}  // namespace
}  // namespace urbanvec::shrink
