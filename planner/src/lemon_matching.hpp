#pragma once
// LEMON behind plain types. LEMON 1.3.1 uses std::allocator members that C++20 removed,
// so lemon_matching.cpp alone is compiled as C++17; this header must stay C++17-clean.

#include <cstdint>
#include <utility>
#include <vector>

namespace ccbuild::planner::detail {

struct SparseMatching {
  bool perfect = false;
  std::vector<int> mate;                        ///< per node
  std::vector<std::int64_t> node_potential;     ///< LEMON's dual y, scaled by dual_scale
  std::vector<std::int64_t> blossom_value;      ///< dual z per blossom, scaled
  std::vector<std::vector<int>> blossom_nodes;  ///< nodes of each blossom
  std::int64_t dual_scale = 1;
};

/// Maximum-weight perfect matching of a graph with `nodes` nodes and the given edges and
/// integer weights, with its optimal dual solution.
SparseMatching max_weight_perfect_matching(int nodes, const std::vector<std::pair<int, int>>& edges,
                                           const std::vector<std::int64_t>& weights);

}  // namespace ccbuild::planner::detail
