// The connected lower bound: an LP relaxation of the rural postman problem, grown by
// cutting planes and priced on the complete graph (see lower_bound.hpp for the model).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "geometry.hpp"
#include "lemon_lp.hpp"
#include "union_find.hpp"

namespace ccbuild::planner {
namespace {

using detail::UnionFind;
using detail::Vec2;

/// A cut row: x(delta(S)) >= rhs (or = rhs for the free end's degree).
struct CutRow {
  std::vector<int> members;  // sorted node ids
  double rhs = 1.0;
  bool equality = false;
};

class ConnectedBoundSolver {
 public:
  ConnectedBoundSolver(const floors::Layer& layer, Metric metric, const PathSpec& path,
                       const ConnectedBoundLimits& limits, const StopCondition& stop)
      : metric_(metric), limits_(limits), stop_(stop) {
    positions_ = layer.points;
    std::vector<std::pair<int, int>> walls;
    for (const auto& s : layer.segments) walls.emplace_back(s.start_point, s.end_point);
    if (!path.closed) {
      int start = -1;
      for (std::size_t p = 0; p < positions_.size(); ++p)
        if ((positions_[p] - path.start_m).norm() <= 1e-6) start = static_cast<int>(p);
      if (start < 0) {
        start = static_cast<int>(positions_.size());
        positions_.push_back(path.start_m);
      }
      real_ = static_cast<int>(positions_.size());
      free_end_ = real_;
      // The open path closed by a free return: the end goes to the free end, which is
      // joined to the start like a wall.
      walls.emplace_back(free_end_, start);
      start_ = start;
    } else {
      real_ = static_cast<int>(positions_.size());
    }
    nodes_ = real_ + (free_end_ >= 0 ? 1 : 0);
    odd_.assign(nodes_, 0);
    UnionFind uf(nodes_);
    for (const auto& [a, b] : walls) {
      odd_[a] ^= 1;
      odd_[b] ^= 1;
      uf.unite(a, b);
    }
    component_.assign(nodes_, -1);
    std::vector<int> id_of_root(nodes_, -1);
    for (int v = 0; v < nodes_; ++v) {
      const int r = uf.find(v);
      if (id_of_root[r] < 0) id_of_root[r] = components_++;
      component_[v] = id_of_root[r];
    }
    component_size_.assign(components_, 0);
    for (int v = 0; v < nodes_; ++v) ++component_size_[component_[v]];
    cols_of_.resize(nodes_);
    rows_of_.resize(nodes_);
    // The points in x order, for the pricing scans.
    by_x_.resize(real_);
    std::iota(by_x_.begin(), by_x_.end(), 0);
    std::sort(by_x_.begin(), by_x_.end(), [&](int a, int b) {
      return positions_[a].x() < positions_[b].x() ||
             (positions_[a].x() == positions_[b].x() && a < b);
    });
  }

  ConnectedBound run() {
    ConnectedBound out;
    if (std::count(odd_.begin(), odd_.end(), 1) == 0 && components_ <= 1) {
      out.certified = true;  // one connected Eulerian layer: no air move is needed
      if (limits_.keep_certificate) store_certificate({}, out);
      return out;
    }
    initial_columns();
    for (int v = 0; v < nodes_; ++v)
      if (odd_[v]) add_cut({v}, 1.0, v == free_end_);
    if (components_ > 1) {
      std::vector<std::vector<int>> members(components_);
      for (int v = 0; v < nodes_; ++v) members[component_[v]].push_back(v);
      for (auto& m : members) add_cut(std::move(m), 2.0, false);
    }
    if (lp_.solve_after_rows() != detail::LinearProgram::Status::kOptimal) {
      out.stopped_by = BoundStop::kLpFailed;
      return out;
    }
    // Pricing makes the bound valid on the complete graph; it runs every few rounds and
    // at the end (the scaled dual is valid in between too, only weaker).
    auto price_and_certify = [&]() {
      double bound = 0.0;
      std::vector<BoundMoat> moats;
      for (int pricing = 0; pricing < limits_.max_pricing_rounds; ++pricing) {
        std::vector<std::pair<double, std::pair<int, int>>> violated;
        bound = certified_dual_value(&violated, limits_.keep_certificate ? &moats : nullptr);
        // The scaled dual is a valid bound at every step, so a stop loses only strength.
        if (violated.empty() || stop_.should_stop()) break;
        std::sort(violated.begin(), violated.end());
        const std::size_t add = std::min<std::size_t>(violated.size(), 4 * real_ + 100);
        for (std::size_t i = 0; i < add; ++i)
          add_column(violated[i].second.first, violated[i].second.second);
        if (lp_.solve_after_columns() != detail::LinearProgram::Status::kOptimal) return false;
      }
      if (bound > out.lower_bound_m || !out.certified) {
        out.lower_bound_m = bound;
        if (limits_.keep_certificate) store_certificate(std::move(moats), out);
      }
      out.certified = true;
      out.lp_value_m = lp_.objective();
      return true;
    };
    if (!price_and_certify()) {
      out.stopped_by = BoundStop::kLpFailed;
      return out;
    }
    double lp_at_last_check = lp_.objective();
    bool priced_last = true;
    for (out.rounds = 1;; ++out.rounds) {
      // Stopped before this round's separation: count the rounds that ran.
      if (stop_.should_stop()) {
        out.stopped_by = stop_.cancelled() ? BoundStop::kCancelled : BoundStop::kTimeLimit;
        --out.rounds;
        break;
      }
      if (out.rounds > limits_.max_rounds) {
        out.stopped_by = BoundStop::kRoundLimit;
        --out.rounds;
        break;
      }
      const int added = separate();
      out.cuts += added;
      if (added == 0) {
        out.stopped_by = BoundStop::kNoViolatedCuts;
        break;
      }
      if (lp_.solve_after_rows() != detail::LinearProgram::Status::kOptimal) {
        out.stopped_by = BoundStop::kLpFailed;
        return out;
      }
      priced_last = false;
      if (out.rounds % limits_.pricing_interval == 0) {
        if (!price_and_certify()) {
          out.stopped_by = BoundStop::kLpFailed;
          return out;
        }
        priced_last = true;
        // The last rounds add little: stop when they raised the LP by too little.
        const double lp = lp_.objective();
        if (lp - lp_at_last_check < limits_.stall_fraction * std::max(lp, 1e-9)) {
          out.stopped_by = BoundStop::kStalled;
          break;
        }
        lp_at_last_check = lp;
      }
    }
    if (!priced_last && !price_and_certify()) out.stopped_by = BoundStop::kLpFailed;
    out.columns = lp_.columns();
    out.rows = lp_.rows();
    return out;
  }

 private:
  double cost(int u, int v) const {
    return metric_distance_m(metric_, positions_[u], positions_[v]);
  }

  static std::uint64_t key(int u, int v) {
    if (u > v) std::swap(u, v);
    return (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v);
  }

  void add_column(int u, int v) {
    if (u == v || !column_keys_.insert(key(u, v)).second) return;
    // Rows that contain exactly one of the two ends.
    std::vector<std::pair<int, double>> entries;
    const auto& a = rows_of_[u];
    const auto& b = rows_of_[v];
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
      if (j == b.size() || (i < a.size() && a[i] < b[j])) {
        entries.emplace_back(a[i++], 1.0);
      } else if (i == a.size() || b[j] < a[i]) {
        entries.emplace_back(b[j++], 1.0);
      } else {
        ++i;
        ++j;
      }
    }
    const double c = (u == free_end_ || v == free_end_) ? 0.0 : cost(u, v);
    const int column = lp_.add_column(c, 0.0, std::numeric_limits<double>::infinity(), entries);
    column_edge_.emplace_back(u, v);
    cols_of_[u].push_back(column);
    cols_of_[v].push_back(column);
  }

  bool add_cut(std::vector<int> members, double rhs, bool equality) {
    std::sort(members.begin(), members.end());
    if (members.empty() || static_cast<int>(members.size()) >= nodes_) return false;
    std::uint64_t h = 1469598103934665603ULL;
    for (int m : members) h = (h ^ static_cast<std::uint64_t>(m)) * 1099511628211ULL;
    if (!row_hashes_.insert(h).second) return false;
    std::vector<char>& in = scratch_;
    in.resize(nodes_, 0);
    for (int m : members) in[m] = 1;
    std::vector<std::pair<int, double>> entries;
    for (int m : members)
      for (int c : cols_of_[m]) {
        const auto [u, v] = column_edge_[c];
        if (in[u] != in[v]) entries.emplace_back(c, 1.0);
      }
    for (int m : members) in[m] = 0;
    const int row =
        lp_.add_row(rhs, equality ? rhs : std::numeric_limits<double>::infinity(), entries);
    for (int m : members) rows_of_[m].push_back(row);
    rows_.push_back({std::move(members), rhs, equality});
    return true;
  }

  void initial_columns() {
    detail::PointGrid grid(positions_);
    const int k = std::min(limits_.neighbours, real_ - 1);
    UnionFind uf(real_);
    for (int u = 0; u < real_ && k > 0; ++u)
      for (int v : grid.nearest(u, k, [](int) { return false; })) {
        add_column(u, v);
        uf.unite(u, v);
      }
    // The candidate graph must be connected (so every cut has a column across it):
    // join each of its parts but the largest to the nearest point outside it.
    for (;;) {
      std::vector<std::vector<int>> parts(real_);
      for (int v = 0; v < real_; ++v) parts[uf.find(v)].push_back(v);
      std::vector<int> roots;
      for (int r = 0; r < real_; ++r)
        if (!parts[r].empty()) roots.push_back(r);
      if (roots.size() <= 1) break;
      std::sort(roots.begin(), roots.end(),
                [&](int a, int b) { return parts[a].size() < parts[b].size(); });
      roots.pop_back();  // the largest part is reached from the others
      for (int r : roots) {
        if (uf.find(r) != r) continue;
        std::pair<double, std::pair<int, int>> best{std::numeric_limits<double>::infinity(),
                                                    {-1, -1}};
        for (int u : parts[r])
          for (int v = 0; v < real_; ++v)
            if (uf.find(v) != uf.find(u) && cost(u, v) < best.first) best = {cost(u, v), {u, v}};
        if (best.second.first >= 0) {
          add_column(best.second.first, best.second.second);
          uf.unite(best.second.first, best.second.second);
        }
      }
    }
    if (free_end_ >= 0)
      for (int v = 0; v < real_; ++v) add_column(free_end_, v);
  }

  /// The sum of `y` over the inequality rows that hold both `u` and `v`.
  double dual_shared(int u, int v, const std::vector<double>& y) const {
    double both = 0.0;
    const auto& a = rows_of_[u];
    const auto& b = rows_of_[v];
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
      if (a[i] < b[j]) {
        ++i;
      } else if (b[j] < a[i]) {
        ++j;
      } else {
        if (!rows_[a[i]].equality) both += y[a[i]];
        ++i;
        ++j;
      }
    }
    return both;
  }

  /// Dual values of the current LP made feasible for every pair of the complete graph,
  /// and their objective: a valid lower bound. Pairs with a negative reduced cost under
  /// the LP's own duals are returned in `violated` (reduced cost, pair); with `moats`,
  /// the feasible duals themselves (those of non-zero width).
  double certified_dual_value(std::vector<std::pair<double, std::pair<int, int>>>* violated,
                              std::vector<BoundMoat>* moats = nullptr) {
    if (moats) moats->clear();
    const int rows = static_cast<int>(rows_.size());
    std::vector<double> y(rows);
    for (int r = 0; r < rows; ++r) {
      y[r] = lp_.dual(r);
      if (!rows_[r].equality) y[r] = std::max(0.0, y[r]);
    }
    // pi(v): the dual of every inequality row holding v (the free end's equality row
    // only touches the free end's own pairs).
    std::vector<double> pi(real_, 0.0);
    for (int r = 0; r < rows; ++r) {
      if (rows_[r].equality) continue;
      for (int m : rows_[r].members)
        if (m < real_) pi[m] += y[r];
    }
    // pi(u) + pi(v) minus twice the rows holding both.
    auto load = [&](int u, int v) { return pi[u] + pi[v] - 2.0 * dual_shared(u, v, y); };
    // Scan every pair that could be loaded beyond its cost: cost(u, v) <= pi(u) + pi(v),
    // in x order (both metrics are at least |dx|).
    double pi_max = 0.0;
    for (double p : pi) pi_max = std::max(pi_max, p);
    const std::vector<int>& by_x = by_x_;
    double scale = 1.0;
    for (int i = 0; i < real_; ++i) {
      const int u = by_x[i];
      if (pi[u] <= 0.0 && pi_max <= 0.0) break;
      for (int j = i + 1; j < real_; ++j) {
        const int v = by_x[j];
        if (positions_[v].x() - positions_[u].x() > pi[u] + pi_max + 1e-9) break;
        const double c = cost(u, v);
        if (c > pi[u] + pi[v] + 1e-9) continue;
        const double l = load(u, v);
        if (l <= c) continue;
        if (l > 0.0) scale = std::min(scale, c / l);
        if (violated && c - l < -1e-7 && !column_keys_.count(key(u, v)))
          violated->push_back({c - l, {u, v}});
      }
    }
    // The scaled duals hold on every pair between layer points. The free end's own row
    // is free in sign: give it the largest value its (zero-cost) pairs allow.
    double value = 0.0;
    for (int r = 0; r < rows; ++r)
      if (!rows_[r].equality) value += rows_[r].rhs * scale * y[r];
    if (free_end_ >= 0) {
      double free_dual = std::numeric_limits<double>::infinity();
      for (int v = 0; v < real_; ++v) {
        double other = 0.0;  // rows separating the free end from v
        for (int r : rows_of_[v])
          if (!rows_[r].equality) other += scale * y[r];
        for (int r : rows_of_[free_end_])
          if (!rows_[r].equality) other += scale * y[r];
        other -= 2.0 * scale * dual_shared(v, free_end_, y);  // rows holding both
        free_dual = std::min(free_dual, -other);
      }
      value += free_dual;  // rhs of the free end's row is 1
      if (moats) moats->push_back({{free_end_}, 1.0, free_dual, true});
    }
    if (moats)
      for (int r = 0; r < rows; ++r)
        if (!rows_[r].equality && y[r] > 0.0)
          moats->push_back({rows_[r].members, rows_[r].rhs, scale * y[r], false});
    // A margin for the floating-point sums above.
    return std::max(0.0, value - 1e-9 * (1.0 + std::abs(value)));
  }

  void store_certificate(std::vector<BoundMoat> moats, ConnectedBound& out) const {
    ConnectedBoundCertificate& c = out.certificate.emplace();
    c.points_m.assign(positions_.begin(), positions_.begin() + real_);
    if (free_end_ >= 0) c.start = start_;
    c.moats = std::move(moats);
  }

  /// Offers `try_cut` the fundamental cuts below `rhs` of a Gomory-Hu tree of the LP
  /// support with the points grouped by `group` (group ids 0 .. groups - 1), and, with
  /// `need_odd`, holding an odd number of odd points. Groups joined by `rhs` or more
  /// are merged first: no cut between them can be violated.
  template <class TryCut>
  void tree_cuts(const std::vector<int>& group, int groups, const std::vector<double>& x,
                 double rhs, bool need_odd, TryCut&& try_cut) const {
    UnionFind merged(groups);
    for (bool changed = true; changed;) {
      changed = false;
      std::unordered_map<std::uint64_t, double> between;
      for (std::size_t c = 0; c < column_edge_.size(); ++c) {
        if (x[c] <= 1e-9) continue;
        const int a = merged.find(group[column_edge_[c].first]);
        const int b = merged.find(group[column_edge_[c].second]);
        if (a != b) between[key(a, b)] += x[c];
      }
      for (const auto& [k, value] : between)
        if (value >= rhs - 1e-9)
          changed |= merged.unite(static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu));
    }
    std::vector<int> super(groups, -1);
    int count = 0;
    for (int g = 0; g < groups; ++g) {
      const int r = merged.find(g);
      if (super[r] < 0) super[r] = count++;
      super[g] = super[r];
    }
    if (count < 2) return;
    std::vector<int> node_super(nodes_);
    std::vector<int> odd_below(count, 0);
    for (int v = 0; v < nodes_; ++v) {
      node_super[v] = super[group[v]];
      odd_below[node_super[v]] += odd_[v];
    }
    std::vector<std::pair<int, int>> edges;
    std::vector<double> capacity;
    for (std::size_t c = 0; c < column_edge_.size(); ++c) {
      const int a = node_super[column_edge_[c].first], b = node_super[column_edge_[c].second];
      if (a != b && x[c] > 1e-9) {
        edges.emplace_back(a, b);
        capacity.push_back(x[c]);
      }
    }
    const detail::CutTree tree = detail::gomory_hu_tree(count, edges, capacity);
    std::vector<std::vector<int>> children(count);
    std::vector<int> order;  // parents before children
    for (int v = 0; v < count; ++v) {
      if (tree.parent[v] >= 0)
        children[tree.parent[v]].push_back(v);
      else
        order.push_back(v);
    }
    for (std::size_t i = 0; i < order.size(); ++i)
      for (int c : children[order[i]]) order.push_back(c);
    for (auto it = order.rbegin(); it != order.rend(); ++it)
      if (tree.parent[*it] >= 0) odd_below[tree.parent[*it]] += odd_below[*it];
    int offered = 0;
    std::vector<char> chosen(count);
    for (int v = 0; v < count && offered < limits_.max_cuts_per_round; ++v) {
      if (tree.parent[v] < 0 || tree.value[v] >= rhs - 1e-6) continue;
      if (need_odd && odd_below[v] % 2 == 0) continue;
      std::fill(chosen.begin(), chosen.end(), 0);
      std::vector<int> subtree{v};
      for (std::size_t i = 0; i < subtree.size(); ++i) {
        chosen[subtree[i]] = 1;
        for (int c : children[subtree[i]]) subtree.push_back(c);
      }
      std::vector<int> members;
      for (int n = 0; n < nodes_; ++n)
        if (chosen[node_super[n]]) members.push_back(n);
      ++offered;
      try_cut(members);
    }
  }

  /// Adds violated parity and connectivity cuts; returns how many.
  int separate() {
    const int columns = lp_.columns();
    std::vector<double> x(columns);
    for (int c = 0; c < columns; ++c) x[c] = lp_.primal(c);
    int added = 0;
    std::vector<char> in(nodes_, 0);
    std::vector<int> count_in(components_, 0);
    auto try_cut = [&](const std::vector<int>& members) {
      if (members.empty() || static_cast<int>(members.size()) >= nodes_) return;
      int odd = 0;
      for (int m : members) {
        in[m] = 1;
        odd += odd_[m];
        ++count_in[component_[m]];
      }
      // A union of whole wall components needs two air moves across it; a set with an
      // odd number of odd points needs one.
      bool whole_components = true;
      for (int m : members)
        if (count_in[component_[m]] != component_size_[component_[m]]) whole_components = false;
      const double rhs = whole_components ? 2.0 : (odd % 2 == 1 ? 1.0 : 0.0);
      double crossing = 0.0;
      if (rhs > 0.0)
        for (int m : members)
          for (int c : cols_of_[m]) {
            const auto [u, v] = column_edge_[c];
            if (in[u] != in[v]) crossing += x[c];
          }
      for (int m : members) {
        in[m] = 0;
        count_in[component_[m]] = 0;
      }
      if (rhs > 0.0 && crossing < rhs - 1e-6 && add_cut(members, rhs, false)) ++added;
    };

    // Parts of the support graph, at a few thresholds: a part with an odd number of odd
    // points, or a union of whole components, that too little crosses.
    for (double threshold : {1e-9, 0.3, 0.5, 0.7, 0.99}) {
      UnionFind uf(nodes_);
      for (int c = 0; c < columns; ++c)
        if (x[c] >= threshold) uf.unite(column_edge_[c].first, column_edge_[c].second);
      std::vector<std::vector<int>> parts(nodes_);
      for (int v = 0; v < nodes_; ++v) parts[uf.find(v)].push_back(v);
      for (const auto& part : parts)
        if (part.size() > 0 && part.size() < static_cast<std::size_t>(nodes_)) try_cut(part);
      // The same with wall components kept whole.
      UnionFind whole(nodes_);
      for (int v = 0; v < nodes_; ++v) whole.unite(v, uf.find(v));
      std::vector<int> first_of(components_, -1);
      for (int v = 0; v < nodes_; ++v) {
        if (first_of[component_[v]] < 0) first_of[component_[v]] = v;
        whole.unite(v, first_of[component_[v]]);
      }
      std::vector<std::vector<int>> unions(nodes_);
      for (int v = 0; v < nodes_; ++v) unions[whole.find(v)].push_back(v);
      for (const auto& part : unions)
        if (part.size() > 0 && part.size() < static_cast<std::size_t>(nodes_)) try_cut(part);
    }

    // Exact separation from Gomory-Hu trees (Padberg and Rao): every fundamental cut
    // of the tree of the wall components' graph that is below 2, and every fundamental
    // cut of the tree of the points' support graph with an odd number of odd points
    // that is below 1.
    // Connectivity: the graph of wall components.
    if (components_ > 1) tree_cuts(component_, components_, x, 2.0, false, try_cut);
    // Parity: the points' graph, dearer, so only when nothing cheaper is left.
    if (added == 0 && nodes_ <= limits_.max_parity_tree_nodes) {
      std::vector<int> identity(nodes_);
      std::iota(identity.begin(), identity.end(), 0);
      tree_cuts(identity, nodes_, x, 1.0, true, try_cut);
    }
    return added;
  }

  Metric metric_;
  ConnectedBoundLimits limits_;
  const StopCondition& stop_;
  std::vector<Vec2> positions_;
  std::vector<int> by_x_;  // real points in ascending x
  int real_ = 0, nodes_ = 0, free_end_ = -1, start_ = -1, components_ = 0;
  std::vector<char> odd_;
  std::vector<int> component_, component_size_;
  detail::LinearProgram lp_;
  std::vector<std::pair<int, int>> column_edge_;
  std::unordered_set<std::uint64_t> column_keys_;
  std::vector<std::vector<int>> cols_of_, rows_of_;
  std::vector<CutRow> rows_;
  std::unordered_set<std::uint64_t> row_hashes_;
  std::vector<char> scratch_;
};

}  // namespace

ConnectedBound connected_airtime_bound(const floors::Layer& layer, Metric metric,
                                       const PathSpec& path, const ConnectedBoundLimits& limits,
                                       const StopCondition& stop) {
  if (layer.segments.empty()) return {};
  ConnectedBoundSolver solver(layer, metric, path, limits, stop);
  return solver.run();
}

}  // namespace ccbuild::planner
