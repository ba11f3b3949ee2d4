#include "lemon_lp.hpp"

#include <lemon/gomory_hu.h>
#include <lemon/lp.h>
#include <lemon/smart_graph.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace ccbuild::planner::detail {

struct LinearProgram::Impl {
  lemon::Lp lp;
  std::vector<lemon::Lp::Col> columns;
  std::vector<lemon::Lp::Row> rows;
};

namespace {
double lemon_bound(double v) {
  if (std::isinf(v)) return v > 0 ? lemon::Lp::INF : -lemon::Lp::INF;
  return v;
}
}  // namespace

LinearProgram::LinearProgram() : impl_(std::make_unique<Impl>()) {
  impl_->lp.messageLevel(lemon::LpBase::MESSAGE_NOTHING);
  impl_->lp.min();
}

LinearProgram::~LinearProgram() = default;

int LinearProgram::add_column(double cost, double lower, double upper,
                              const std::vector<std::pair<int, double>>& entries) {
  lemon::Lp::DualExpr in_rows;
  for (const auto& [row, coef] : entries) in_rows += coef * impl_->rows[row];
  const lemon::Lp::Col c = impl_->lp.addCol(in_rows, cost);
  impl_->lp.colLowerBound(c, lemon_bound(lower));
  impl_->lp.colUpperBound(c, lemon_bound(upper));
  impl_->columns.push_back(c);
  return columns_++;
}

int LinearProgram::add_row(double lower, double upper,
                           const std::vector<std::pair<int, double>>& entries) {
  lemon::Lp::Expr e;
  for (const auto& [column, coef] : entries) e += coef * impl_->columns[column];
  impl_->rows.push_back(impl_->lp.addRow(lemon_bound(lower), e, lemon_bound(upper)));
  return rows_++;
}

namespace {
LinearProgram::Status status_of(lemon::Lp& lp, lemon::LpBase::SolveExitStatus exit) {
  if (exit != lemon::LpBase::SOLVED) return LinearProgram::Status::kFailed;
  switch (lp.primalType()) {
    case lemon::LpSolver::OPTIMAL:
      return LinearProgram::Status::kOptimal;
    case lemon::LpSolver::INFEASIBLE:
      return LinearProgram::Status::kInfeasible;
    default:
      return LinearProgram::Status::kFailed;
  }
}
}  // namespace

LinearProgram::Status LinearProgram::solve_after_rows() {
  auto status = status_of(impl_->lp, impl_->lp.solveDual());
  // The dual simplex needs a dual feasible start; fall back to the primal one.
  if (status == Status::kFailed) status = status_of(impl_->lp, impl_->lp.solvePrimal());
  return status;
}

LinearProgram::Status LinearProgram::solve_after_columns() {
  auto status = status_of(impl_->lp, impl_->lp.solvePrimal());
  if (status == Status::kFailed) status = status_of(impl_->lp, impl_->lp.solveDual());
  return status;
}

double LinearProgram::objective() const {
  return impl_->lp.primal();
}
double LinearProgram::primal(int column) const {
  return impl_->lp.primal(impl_->columns[column]);
}
double LinearProgram::dual(int row) const {
  return impl_->lp.dual(impl_->rows[row]);
}

CutTree gomory_hu_tree(int nodes, const std::vector<std::pair<int, int>>& edges,
                       const std::vector<double>& capacity) {
  using Graph = lemon::SmartGraph;
  Graph graph;
  graph.reserveNode(nodes);
  for (int i = 0; i < nodes; ++i) graph.addNode();
  Graph::EdgeMap<std::int64_t> cap(graph);
  for (std::size_t e = 0; e < edges.size(); ++e)
    cap[graph.addEdge(graph.nodeFromId(edges[e].first), graph.nodeFromId(edges[e].second))] =
        static_cast<std::int64_t>(std::floor(capacity[e] * 1e6));
  CutTree out;
  out.parent.assign(nodes, -1);
  out.value.assign(nodes, 0.0);
  if (nodes < 2) return out;
  lemon::GomoryHu<Graph, Graph::EdgeMap<std::int64_t>> tree(graph, cap);
  tree.run();
  for (int i = 0; i < nodes; ++i) {
    const Graph::Node parent = tree.predNode(graph.nodeFromId(i));
    if (parent == lemon::INVALID) continue;
    out.parent[i] = graph.id(parent);
    out.value[i] = static_cast<double>(tree.predValue(graph.nodeFromId(i))) * 1e-6;
  }
  return out;
}

}  // namespace ccbuild::planner::detail
