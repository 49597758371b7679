// core/uniform_grid.hpp: the library's one bucket grid.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "urbanvec/core/uniform_grid.hpp"

using namespace urbanvec;

TEST(UniformGrid, ABoxQueryFindsEverySegmentItCoversAndClampsOutsidePoints) {
  UniformGrid<int> grid({0, 0}, {100, 100}, 10);
  EXPECT_EQ(grid.columns(), 11);
  grid.insert({5, 5}, {95, 5}, 1);     // a long segment across ten buckets
  grid.insert({50, 50}, {50, 50}, 2);  // a point
  grid.insert({-40, 120}, 3);          // outside: the corner bucket
  auto found = [&](Vec2 a, Vec2 b) {
    std::set<int> ids;
    grid.forBox(a, b, [&](const std::vector<int>& bucket) { ids.insert(bucket.begin(), bucket.end()); });
    return ids;
  };
  EXPECT_EQ(found({70, 0}, {71, 1}), std::set<int>{1});  // far from the segment's ends
  EXPECT_EQ(found({45, 45}, {55, 55}), std::set<int>{2});
  EXPECT_EQ(found({-10, 99}, {1, 200}), std::set<int>{3});
  EXPECT_TRUE(found({30, 30}, {39, 39}).empty());
}

TEST(UniformGrid, RingsVisitEveryBucketOnceThenStop) {
  UniformGrid<std::pair<int, int>> grid({0, 0}, {49, 29}, 10);  // 5 x 3 buckets
  for (int j = 0; j < grid.rows(); ++j)
    for (int i = 0; i < grid.columns(); ++i) grid.insert({i * 10.0 + 5, j * 10.0 + 5}, {i, j});
  std::multiset<std::pair<int, int>> seen;
  int ring = 0;
  while (grid.forRing(1, 2, ring, [&](const auto& bucket) { seen.insert(bucket.begin(), bucket.end()); })) {
    for (const auto& [i, j] : seen) EXPECT_LE(std::max(std::abs(i - 1), std::abs(j - 2)), ring);
    ++ring;
  }
  EXPECT_EQ(seen.size(), 15u);
  const std::set<std::pair<int, int>> distinct(seen.begin(), seen.end());
  EXPECT_EQ(distinct.size(), 15u);
  EXPECT_EQ(ring, 4);  // rings 0-3 reach the farthest column, 4 lies wholly outside
}
