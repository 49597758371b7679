// core/union_find.hpp: the library's one union-find.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "urbanvec/core/union_find.hpp"

using namespace urbanvec;

TEST(UnionFind, TheRootOfASetIsItsLowestIdWhateverTheOrderOfTheUnions) {
  UnionFind uf(8);
  EXPECT_EQ(uf.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(uf.find(i), i);
  EXPECT_EQ(uf.unite(6, 3), 3);
  EXPECT_EQ(uf.unite(7, 6), 3);
  EXPECT_EQ(uf.unite(5, 1), 1);
  EXPECT_EQ(uf.unite(7, 5), 1);  // two sets {3,6,7} and {1,5}: the union's root is 1
  for (int i : {1, 3, 5, 6, 7}) EXPECT_EQ(uf.find(i), 1);
  for (int i : {0, 2, 4}) EXPECT_EQ(uf.find(i), i);
  EXPECT_TRUE(uf.same(3, 5));
  EXPECT_FALSE(uf.same(0, 2));
  EXPECT_EQ(uf.unite(3, 7), 1);  // already one set
}

TEST(UnionFind, AgreesWithANaiveLabellingOnRandomUnions) {
  std::mt19937 rng(7);
  const int n = 500;
  UnionFind uf(n);
  std::vector<int> label(n);
  for (int i = 0; i < n; ++i) label[static_cast<size_t>(i)] = i;
  std::uniform_int_distribution<int> pick(0, n - 1);
  for (int k = 0; k < 400; ++k) {
    const int a = pick(rng), b = pick(rng);
    uf.unite(a, b);
    const int la = label[static_cast<size_t>(a)], lb = label[static_cast<size_t>(b)];
    const int lo = std::min(la, lb), hi = std::max(la, lb);
    for (int& l : label)
      if (l == hi) l = lo;  // the naive set's label is its lowest id too
    if (k % 50 == 0)
      for (int i = 0; i < n; ++i) ASSERT_EQ(uf.find(i), label[static_cast<size_t>(i)]) << i;
  }
  for (int i = 0; i < n; ++i) EXPECT_EQ(uf.find(i), label[static_cast<size_t>(i)]) << i;
}
