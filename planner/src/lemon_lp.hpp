#pragma once
// LEMON's LP interface (GLPK underneath) and its global minimum cut, behind plain types.
// Like lemon_matching.hpp, this header must stay C++17-clean: its source is compiled as
// C++17 because LEMON 1.3.1 does not build as C++20.

#include <memory>
#include <utility>
#include <vector>

namespace ccbuild::planner::detail {

/// A minimisation LP grown by rows (cuts) and columns (priced edges), re-solved warm.
class LinearProgram {
 public:
  enum class Status { kOptimal, kInfeasible, kFailed };

  LinearProgram();
  ~LinearProgram();
  LinearProgram(const LinearProgram&) = delete;
  LinearProgram& operator=(const LinearProgram&) = delete;

  /// A column with objective `cost`, bounds [lower, upper] (upper may be +infinity), and
  /// coefficients in existing rows.
  int add_column(double cost, double lower, double upper,
                 const std::vector<std::pair<int, double>>& entries = {});
  /// A row lower <= sum coef * column <= upper (either side may be infinite).
  int add_row(double lower, double upper, const std::vector<std::pair<int, double>>& entries);

  /// Dual simplex after adding rows, primal simplex after adding columns (both warm).
  Status solve_after_rows();
  Status solve_after_columns();

  double objective() const;
  double primal(int column) const;
  /// The row's dual value (>= 0 for an active lower bound of a minimisation).
  double dual(int row) const;
  int rows() const { return rows_; }
  int columns() const { return columns_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int rows_ = 0, columns_ = 0;
};

/// Gomory-Hu tree of an undirected graph with non-negative capacities: for every node
/// but the root, the tree edge to its parent with the minimum cut value between the two
/// (`parent[root] = -1`). Removing a tree edge splits the nodes into the two shores of a
/// minimum cut; these n - 1 fundamental cuts hold a minimum T-odd cut for every T
/// (Padberg and Rao).
struct CutTree {
  std::vector<int> parent;
  std::vector<double> value;
};
CutTree gomory_hu_tree(int nodes, const std::vector<std::pair<int, int>>& edges,
                       const std::vector<double>& capacity);

}  // namespace ccbuild::planner::detail
