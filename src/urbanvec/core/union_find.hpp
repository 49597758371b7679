// Disjoint sets over the ids 0..n-1 (union-find with path halving): the library's one union-find,
// used by the cadastre's pre-block clustering and split-vertex merging and the shrink's cluster
// connection. The root of a set is always its lowest id, so a set's representative does not depend on
// the order of the unions, and renumbering sets in order of their roots is deterministic.
#pragma once

#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace urbanvec {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  std::size_t size() const { return parent_.size(); }

  /// The root (lowest id) of x's set; halves the path on the way.
  int find(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x)
      x = parent_[static_cast<std::size_t>(x)] =
          parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
    return x;
  }

  /// Joins the sets of a and b; returns the root of the union (the lower of the two roots).
  int unite(int a, int b) {
    a = find(a), b = find(b);
    if (a > b) std::swap(a, b);
    if (a != b) parent_[static_cast<std::size_t>(b)] = a;
    return a;
  }

  /// True when a and b are in one set.
  bool same(int a, int b) { return find(a) == find(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace urbanvec
