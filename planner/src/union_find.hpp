#pragma once
// Disjoint sets over 0 .. n-1 with path halving; the smaller id of two joined sets is
// the representative, so the result does not depend on the order of unions' arguments.

#include <algorithm>
#include <numeric>
#include <vector>

namespace ccbuild::planner::detail {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  /// Joins the sets of `a` and `b`; false when they were one already.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace ccbuild::planner::detail
