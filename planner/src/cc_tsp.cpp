#include "cc_tsp.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "ccbuild/common/input_error.hpp"
#include "item_queue.hpp"
#include "lin_kernighan.hpp"
#include "tour_merge.hpp"

namespace ccbuild::planner::detail {

// ------------------------------------------------------------------ TourCosts ------

TourCosts::TourCosts(const CostModel& model, std::vector<int> segments, Objective objective,
                     bool open, const Vec2& start, std::optional<Vec2> start_heading)
    : model_(model),
      segments_(std::move(segments)),
      objective_(objective),
      metric_(model.metric()),
      has_depot_(open) {
  item_count_ = static_cast<int>(segments_.size()) + (has_depot_ ? 1 : 0);
  position_.resize(2 * item_count_);
  arrive_.assign(2 * item_count_, Vec2::Zero());
  const auto& layer = model_.layer();
  item_of_segment_.assign(layer.segments.size(), -1);
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    item_of_segment_[segments_[k]] = static_cast<int>(k);
    const auto& s = layer.segments[segments_[k]];
    const Vec2 a = layer.start_m(s), b = layer.end_m(s);
    position_[2 * k] = a;
    position_[2 * k + 1] = b;
    const Vec2 d = (b - a).normalized();
    arrive_[2 * k] = -d;  // arriving at the start point means travelling backwards
    arrive_[2 * k + 1] = d;
  }
  if (objective_ == Objective::kTime) {
    // About 32 slots a node, at most 2^17 (2 MiB): on the 40 x 40 rooms benchmark 17% less
    // CPU than computing each cost.
    int bits = 4;
    while (bits < 17 && (std::size_t{1} << bits) < 32 * position_.size()) ++bits;
    cache_.assign(std::size_t{1} << bits, {});
    cache_shift_ = 64 - bits;
  }
  if (has_depot_) {
    position_[2 * depot()] = start;      // the free end: position never used
    position_[2 * depot() + 1] = start;  // the start point
    if (start_heading) arrive_[2 * depot() + 1] = start_heading->normalized();
  }
}

double TourCosts::time_cost(int u, int v) const {
  const Vec2& a = position_[u];
  const Vec2& b = position_[v];
  // Leaving u along its wall's heading, entering v's wall: turn between them.
  double rotation = 0.0;
  if (!arrive_[u].isZero() && !arrive_[v].isZero())
    rotation = std::acos(std::clamp(-arrive_[u].dot(arrive_[v]), -1.0, 1.0));
  // Never priced as lifted: whether a move lifts depends on which walls are built before
  // it, which a symmetric cost cannot know. Pricing every crossing of any wall as a lift
  // made tours detour round walls not yet built (20% more airtime on 100-wall plans,
  // 27% on 1,000-wall ones; bench/README.md); the exact-time polish removes lifts instead.
  return model_.move_time_s(a, b, rotation, false);
}

void TourCosts::build_neighbours(int k) {
  const int nodes = 2 * item_count_;
  neighbours_.assign(nodes, {});
  // Candidates by straight-line distance, then ordered by the real cost.
  std::vector<Vec2> points(position_.begin(), position_.end());
  PointGrid grid(points);
  const int wanted = std::min(nodes - 2, objective_ == Objective::kTime ? k + 4 : k);
  for (int u = 0; u < nodes; ++u) {
    if (is_free(u) || wanted <= 0) continue;
    auto near = grid.nearest(u, wanted, [&](int v) { return v / 2 == u / 2 || is_free(v); });
    std::stable_sort(near.begin(), near.end(),
                     [&](int a, int b) { return cost(u, a) < cost(u, b); });
    if (static_cast<int>(near.size()) > k) near.resize(k);
    if (has_depot_ && u / 2 != depot()) near.insert(near.begin(), 2 * depot());
    neighbours_[u] = std::move(near);
  }
}

// ------------------------------------------------------------------- WallTour ------

WallTour::WallTour(std::vector<int> order, std::vector<char> reversed)
    : node_at_(std::move(order)) {
  where_.assign(node_at_.size(), -1);
  for (int p = 0; p < size(); ++p) {
    const int item = node_at_[p];
    where_[item] = p;
    node_at_[p] = 2 * item + (reversed[item] ? 1 : 0);
  }
}

void WallTour::write(int position, int node) {
  if (journaling_) log_.emplace_back(position, node_at_[position]);
  node_at_[position] = node;
  where_[node >> 1] = position;
}

void WallTour::begin_journal() {
  journaling_ = true;
  log_.clear();
}

void WallTour::commit_journal() {
  journaling_ = false;
  log_.clear();
}

void WallTour::undo_journal() {
  for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
    if (it->first < 0) {
      flip(-1 - it->first, it->second);  // a flip is its own inverse
    } else {
      node_at_[it->first] = it->second;
      where_[it->second >> 1] = it->first;
    }
  }
  commit_journal();
}

void WallTour::reverse(int first, int last) {
  const int n = size();
  int length = (last - first + n) % n + 1;
  if (2 * length > n) {  // the complement is shorter (and empty for the whole tour)
    first = next(last);
    length = n - length;
  }
  if (length == 0) return;
  if (journaling_) log_.emplace_back(-1 - first, length);
  flip(first, length);
}

void WallTour::flip(int first, int length) {
  const int n = size();
  // Swap from both ends, each node turned round (x ^ 1: the item's other end first).
  int i = first, j = (first + length - 1) % n;
  for (int k = 0; k < length / 2; ++k) {
    const int a = node_at_[i], b = node_at_[j];
    node_at_[i] = b ^ 1;
    where_[b >> 1] = i;
    node_at_[j] = a ^ 1;
    where_[a >> 1] = j;
    i = i + 1 == n ? 0 : i + 1;
    j = j == 0 ? n - 1 : j - 1;
  }
  if (length % 2 == 1) node_at_[i] ^= 1;
}

void WallTour::move_block(int first, int length, int after, bool reversed) {
  const int n = size();
  const int last = (first + length - 1) % n;
  const int forward = (after - last + n) % n;  // items between block and insertion point, going on
  const int backward = (first - 1 - after + 2 * n) % n;  // ... going back
  scratch_.clear();
  auto block = [&] {
    for (int k = 0; k < length; ++k) {
      const int node = node_at_[(first + (reversed ? length - 1 - k : k)) % n];
      scratch_.push_back(reversed ? node ^ 1 : node);
    }
  };
  int write_from;
  if (forward <= backward) {
    // [first .. after] becomes (last+1 .. after) + block
    for (int k = 1; k <= forward; ++k) scratch_.push_back(node_at_[(last + k) % n]);
    block();
    write_from = first;
  } else {
    // [after+1 .. last] becomes block + (after+1 .. first-1)
    block();
    for (int k = 1; k <= backward; ++k) scratch_.push_back(node_at_[(after + k) % n]);
    write_from = (after + 1) % n;
  }
  for (std::size_t k = 0; k < scratch_.size(); ++k)
    write((write_from + static_cast<int>(k)) % n, scratch_[k]);
}

double WallTour::cost(const TourCosts& costs) const {
  double total = 0.0;
  for (int p = 0; p < size(); ++p) total += costs.cost(exit(p), entry(next(p)));
  return total;
}

// ---------------------------------------------------------------- local search -----

namespace {

constexpr double kEps = 1e-9;

class LocalSearch {
 public:
  LocalSearch(const TourCosts& costs, WallTour& tour)
      : costs_(costs), tour_(tour), queue_(tour.size()) {}

  void push(int item) { queue_.push(item); }
  void push_position(int p) { push(tour_.item_at(p)); }
  /// Forgets what a run cut short left queued.
  void drop_queue() { queue_.clear(); }

  /// Runs until no queued item improves; returns the total gain.
  double run(const StopCondition& stop) {
    double gain = 0.0;
    long steps = 0;
    while (!queue_.empty()) {
      if ((++steps & 255) == 0 && stop.should_stop()) break;
      const int item = queue_.pop();
      double g = 0.0;
      if (improve(item, g)) {
        gain += g;
        push(item);
      }
    }
    return gain;
  }

 private:
  double c(int u, int v) const { return costs_.cost(u, v); }

  bool improve(int item, double& gain) {
    for (int side = 0; side < 2; ++side) {
      if (two_opt(2 * item + side, gain)) return true;
    }
    return or_opt(item, gain);
  }

  void touch(std::initializer_list<int> positions) {
    for (int p : positions) push_position(p);
  }

  bool two_opt(int a, double& gain) {
    const int pa = tour_.position_of(a / 2);
    if (tour_.size() < 3) return false;
    if (a == tour_.exit(pa)) {
      const int pb = tour_.next(pa);
      const int b = tour_.entry(pb);
      const double ab = c(a, b);
      for (int cand : costs_.neighbours(a)) {
        if (ab - c(a, cand) <= kEps) break;
        const int pc = tour_.position_of(cand / 2);
        if (cand != tour_.exit(pc) || pc == pa) continue;
        const int pd = tour_.next(pc);
        const int d = tour_.entry(pd);
        const double delta = ab + c(cand, d) - c(a, cand) - c(b, d);
        if (delta > kEps) {
          tour_.reverse(pb, pc);
          gain = delta;
          touch({tour_.position_of(a / 2), tour_.position_of(b / 2), tour_.position_of(cand / 2),
                 tour_.position_of(d / 2)});
          return true;
        }
      }
    } else {
      const int pb = tour_.prev(pa);
      const int b = tour_.exit(pb);
      const double ab = c(a, b);
      for (int cand : costs_.neighbours(a)) {
        if (ab - c(a, cand) <= kEps) break;
        const int pc = tour_.position_of(cand / 2);
        if (cand != tour_.entry(pc) || pc == pa) continue;
        const int pd = tour_.prev(pc);
        const int d = tour_.exit(pd);
        const double delta = ab + c(d, cand) - c(a, cand) - c(b, d);
        if (delta > kEps) {
          tour_.reverse(pa, pd);
          gain = delta;
          touch({tour_.position_of(a / 2), tour_.position_of(b / 2), tour_.position_of(cand / 2),
                 tour_.position_of(d / 2)});
          return true;
        }
      }
    }
    return false;
  }

  bool or_opt(int item, double& gain) {
    const int n = tour_.size();
    const int pi = tour_.position_of(item);
    for (int length = 1; length <= 3; ++length) {
      if (length + 2 > n) break;
      for (int variant = 0; variant < (length == 1 ? 1 : 2); ++variant) {
        const int s = variant == 0 ? pi : (pi - length + 1 + n) % n;
        const int e = (s + length - 1) % n;
        const int p = tour_.prev(s), q = tour_.next(e);
        const int xp = tour_.exit(p), es = tour_.entry(s), xe = tour_.exit(e), eq = tour_.entry(q);
        const double removal = c(xp, es) + c(xe, eq) - c(xp, eq);
        if (removal <= kEps) continue;
        auto in_block = [&](int pos) { return (pos - s + n) % n < length; };
        for (int x : {es, xe}) {
          for (int cand : costs_.neighbours(x)) {
            if (c(x, cand) >= removal - kEps) break;
            const int pc = tour_.position_of(cand / 2);
            if (in_block(pc)) continue;
            const bool cand_exit = cand == tour_.exit(pc);
            int after;
            double added;
            bool reversed;
            if (x == es && cand_exit) {  // c, block, next(c)
              if (pc == p) continue;
              after = pc;
              const int n1 = tour_.entry(tour_.next(pc));
              added = c(cand, es) + c(xe, n1) - c(cand, n1);
              reversed = false;
            } else if (x == es) {  // prev(c), reversed block, c
              if (pc == q) continue;
              after = tour_.prev(pc);
              const int xk = tour_.exit(after);
              added = c(xk, xe) + c(es, cand) - c(xk, cand);
              reversed = true;
            } else if (!cand_exit) {  // prev(c), block, c
              if (pc == q) continue;
              after = tour_.prev(pc);
              const int xk = tour_.exit(after);
              added = c(xk, es) + c(xe, cand) - c(xk, cand);
              reversed = false;
            } else {  // c, reversed block, next(c)
              if (pc == p) continue;
              after = pc;
              const int n1 = tour_.entry(tour_.next(pc));
              added = c(cand, xe) + c(es, n1) - c(cand, n1);
              reversed = true;
            }
            const double delta = removal - added;
            if (delta > kEps) {
              const int after_item = tour_.item_at(after),
                        next_item = tour_.item_at(tour_.next(after));
              const int p_item = tour_.item_at(p), q_item = tour_.item_at(q);
              const int s_item = tour_.item_at(s), e_item = tour_.item_at(e);
              tour_.move_block(s, length, after, reversed);
              gain = delta;
              for (int it : {after_item, next_item, p_item, q_item, s_item, e_item}) push(it);
              return true;
            }
          }
        }
      }
    }
    return false;
  }

  const TourCosts& costs_;
  WallTour& tour_;
  ItemQueue queue_;
};

}  // namespace

namespace {

// Cost change of moving block [first, first+length) to just after `after`.
double block_move_delta(const TourCosts& costs, const WallTour& t, int first, int length, int after,
                        bool reversed) {
  const int n = t.size();
  const int last = (first + length - 1) % n;
  const int p = t.prev(first), q = t.next(last);
  const int xp = t.exit(p), es = t.entry(first), xe = t.exit(last), eq = t.entry(q);
  const double removal = costs.cost(xp, es) + costs.cost(xe, eq) - costs.cost(xp, eq);
  const int xa = t.exit(after), n1 = t.entry(t.next(after));
  const double added = reversed ? costs.cost(xa, xe) + costs.cost(es, n1) - costs.cost(xa, n1)
                                : costs.cost(xa, es) + costs.cost(xe, n1) - costs.cost(xa, n1);
  return added - removal;
}

// Cost change of reversing positions first..last.
double reversal_delta(const TourCosts& costs, const WallTour& t, int first, int last) {
  const int p = t.prev(first), q = t.next(last);
  const int xp = t.exit(p), ef = t.entry(first), xl = t.exit(last), eq = t.entry(q);
  return costs.cost(xp, xl) + costs.cost(ef, eq) - costs.cost(xp, ef) - costs.cost(xl, eq);
}

}  // namespace

SearchOutcome chained_local_search(const TourCosts& costs, WallTour tour,
                                   const SearchSettings& settings, const StopCondition& stop) {
  SearchOutcome out;
  const int n = tour.size();
  std::mt19937_64 rng(settings.seed);
  const bool lk = settings.neighbourhood == Neighbourhood::kLinKernighan;
  // Local search from the given items; returns the gain. A kick's repair is short and
  // never cut off by the clock (the clock is read between kicks), so a run stopped by
  // its time limit after K kicks is the run of max_kicks = K.
  const StopCondition never;
  // Both searches work on `tour` throughout (a rejected kick is undone in place).
  LocalSearch cheap(costs, tour);
  LinKernighan deep(costs, tour, settings.lk_depth);
  auto descend = [&](const std::vector<int>& items, const StopCondition& until) {
    double gain = 0.0;
    if (!lk || settings.two_opt_before_lk) {
      cheap.drop_queue();
      for (int item : items) cheap.push(item);
      gain += cheap.run(until);
    }
    if (lk) {
      deep.drop_queue();
      for (int item : items) deep.push(item);
      gain += deep.run(until);
    }
    return gain;
  };
  double current = tour.cost(costs);
  {
    std::vector<int> items(n);
    std::iota(items.begin(), items.end(), 0);
    std::shuffle(items.begin(), items.end(), rng);
    current -= descend(items, stop);
  }
  out.reason = StopReason::kConverged;
  double best = current;
  if (settings.on_better) settings.on_better(0, best);
  long since_improvement = 0;
  const int max_block = std::max(1, std::min(50, n / 4));
  std::vector<int> kicked;
  // A restart (SearchSettings::restart_stall_kicks) of at most `kicks` kicks: its own
  // search, whose better parts are then merged into the best tour. Returns its outcome.
  auto restart = [&](long kicks) {
    CCBUILD_CHECK(static_cast<bool>(settings.restart_tour), "restarts have a first tour");
    SearchSettings own = settings;
    own.restart_stall_kicks = 0;
    own.max_kicks = std::min(settings.restart_kicks, kicks);
    own.stall_kicks = settings.restart_own_stall_kicks;
    own.on_better = nullptr;
    own.seed = rng();
    SearchOutcome other = chained_local_search(costs, settings.restart_tour(rng), own, stop);
    // Cut off in its first descent: that may be unfinished, so nothing is merged.
    if (cut_short(other.reason) && other.kicks == 0) return other;
    ++out.restarts;
    kicked.clear();
    double gain = 0.0;
    if (other.cost < best - 1e-9) {
      gain = best - other.cost;
      tour = other.tour;
    } else {
      gain = merge_tours(costs, tour, other.tour, kicked);
    }
    if (gain > 0.0) {
      current = best - gain;
      current -= descend(kicked, never);
      out.restart_gain += best - current;
      best = current;
      if (settings.on_better) settings.on_better(out.kicks + 1 + other.kicks, best);
    }
    return other;
  };
  for (out.kicks = 0; n >= 5 && out.kicks < settings.max_kicks; ++out.kicks) {
    if (settings.target_cost && best <= *settings.target_cost + 1e-9) {
      out.reason = StopReason::kProvenOptimal;
      break;
    }
    if ((out.kicks & 15) == 0 && stop.should_stop()) {
      out.reason = stop.reason();
      break;
    }
    if (since_improvement >= settings.stall_kicks) break;
    if (settings.restart_stall_kicks > 0 && since_improvement >= settings.restart_stall_kicks) {
      since_improvement = 0;
      // Counted as one kick plus the restart's own, so that a run stopped by the clock
      // after K kicks is still the run of max_kicks = K.
      const long left = settings.max_kicks - out.kicks - 1;
      if (left <= 0) continue;  // the last kick: a restart would have none of its own
      const SearchOutcome other = restart(left);
      out.kicks += other.kicks;
      out.kicks_in_restarts += other.kicks;
      if (cut_short(other.reason)) {
        out.kicks += 1;
        out.reason = other.reason;
        break;
      }
      continue;
    }
    // The tour is the best so far; a kick that makes it longer is undone from the
    // journal of what it changed (not by copying the whole tour back).
    tour.begin_journal();
    kicked.clear();
    if (lk && (rng() & 1)) {
      // A double bridge between parts of the tour that lie close together in the plan
      // (a room visited twice, say), however far apart in the tour: three cuts after
      // items reached by short walks over the candidate lists.
      int cut[3] = {static_cast<int>(rng() % n), -1, -1};
      bool walked = true;
      for (int k = 1; k < 3 && walked; ++k) {
        const int node = 2 * tour.item_at(cut[k - 1]) + static_cast<int>(rng() % 2);
        const auto& near = costs.neighbours(node);  // empty at an open path's free end
        walked = !near.empty();
        if (walked) cut[k] = tour.position_of(near[rng() % near.size()] / 2);
      }
      if (!walked) continue;
      std::sort(cut, cut + 3);
      if (cut[0] == cut[1] || cut[1] == cut[2]) continue;
      const bool reversed = (rng() & 1) != 0;
      for (int c : cut)
        for (int k = 0; k < 2; ++k) kicked.push_back(tour.item_at((c + k) % n));
      current += block_move_delta(costs, tour, cut[0] + 1, cut[1] - cut[0], cut[2], reversed);
      tour.move_block(cut[0] + 1, cut[1] - cut[0], cut[2], reversed);
    } else {
      // A local double bridge: swap two adjacent short blocks B and C, reversing either at
      // random, then repair locally.
      const int l1 = 1 + static_cast<int>(rng() % max_block);
      const int l2 = 1 + static_cast<int>(rng() % max_block);
      const int s = static_cast<int>(rng() % n);
      const unsigned flips = static_cast<unsigned>(rng() % 4);
      if (l1 + l2 + 2 >= n) continue;
      const int b_first = (s + 1) % n, c_last = (s + l1 + l2) % n;
      current += block_move_delta(costs, tour, b_first, l1, c_last, (flips & 1) != 0);
      tour.move_block(b_first, l1, c_last, (flips & 1) != 0);
      const int s_item = tour.item_at(s);
      if (flips & 2) {
        const int cf = tour.next(tour.position_of(s_item));
        const int cl = (tour.position_of(s_item) + l2) % n;
        current += reversal_delta(costs, tour, cf, cl);
        tour.reverse(cf, cl);
      }
      const int ps = tour.position_of(s_item);
      for (int k = 0; k <= l1 + l2 + 1; ++k) {
        if (k <= 1 || k >= l1 + l2 || k == l2 || k == l2 + 1)
          kicked.push_back(tour.item_at((ps + k) % n));
      }
    }
    current -= descend(kicked, never);
    if (current < best - 1e-9) {
      best = current;
      tour.commit_journal();
      since_improvement = 0;
      if (settings.on_better) settings.on_better(out.kicks + 1, best);
    } else if (current <= best + 1e-12) {
      best = std::min(best, current);
      tour.commit_journal();  // sideways: keep wandering along plateaus of equal cost
      ++since_improvement;
    } else {
      tour.undo_journal();
      current = best;
      ++since_improvement;
    }
  }
  tour.commit_journal();
  out.tour = tour;
  out.cost = tour.cost(costs);  // fresh sum: no drift from the running total
  if (settings.target_cost && out.cost <= *settings.target_cost + 1e-9)
    out.reason = StopReason::kProvenOptimal;
  return out;
}

// ------------------------------------------------------------ tours and sequences ---

WallTour tour_from_sequence(const TourCosts& costs, const Sequence& sequence) {
  std::vector<int> order;
  std::vector<char> reversed(costs.item_count(), 0);
  order.reserve(costs.item_count());
  if (costs.has_depot()) order.push_back(costs.depot());
  for (const Step& step : sequence) {
    const int item = costs.item_of_segment(step.segment);
    CCBUILD_CHECK(item >= 0, "sequence step belongs to this tour");
    order.push_back(item);
    reversed[item] = step.reversed ? 1 : 0;
  }
  CCBUILD_CHECK(static_cast<int>(order.size()) == costs.item_count(),
                "sequence covers every item once");
  return WallTour(std::move(order), std::move(reversed));
}

Sequence sequence_from_tour(const TourCosts& costs, const WallTour& tour) {
  Sequence out;
  const int n = tour.size();
  if (!costs.has_depot()) {
    for (int p = 0; p < n; ++p)
      out.push_back({costs.segment_of(tour.item_at(p)), tour.reversed(tour.item_at(p))});
    return out;
  }
  const int pd = tour.position_of(costs.depot());
  // Unreversed, the depot leaves from its start node: read on; else read backwards.
  const bool forward = !tour.reversed(costs.depot());
  for (int k = 1; k < n; ++k) {
    const int p = forward ? (pd + k) % n : (pd - k + n) % n;
    const int item = tour.item_at(p);
    out.push_back({costs.segment_of(item), forward ? tour.reversed(item) : !tour.reversed(item)});
  }
  return out;
}

}  // namespace ccbuild::planner::detail
