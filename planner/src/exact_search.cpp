// Local search under the exact time evaluation. The chained search optimises symmetric
// approximate costs; lifts (which depend on what is already built) and the stopper
// (which depends on how far the nozzle has wound) are only seen here. Candidates are
// evaluated from the first position they change, reusing the nozzle states before it.

#include <algorithm>
#include <cmath>
#include <optional>

#include "ccbuild/common/input_error.hpp"
#include "search_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

class IncrementalTime {
 public:
  IncrementalTime(const CostModel& model, const PathSpec& path)
      : model_(model), path_(path), position_(model.layer().segments.size(), -1) {}

  /// Makes `sequence` current; returns its airtime, s.
  double reset(const Sequence& sequence) {
    current_ = sequence;
    std::fill(position_.begin(), position_.end(), -1);
    for (std::size_t k = 0; k < current_.size(); ++k)
      position_[current_[k].segment] = static_cast<int>(k);
    scratch_ = position_;
    state_.assign(current_.size() + 1, {});
    time_.assign(current_.size() + 1, 0.0);
    cost_ = run(current_, 0, position_, true);
    return cost_;
  }

  /// Airtime of `candidate`, which equals the current sequence outside [from, last).
  double evaluate(const Sequence& candidate, std::size_t from, std::size_t last) {
    // Where the candidate last differs: past it, the same segments are built and the
    // same steps follow, so once the nozzle's state matches the current sequence's the
    // rest of the time is the current's (only the winding of the heading can differ).
    while (last > from && candidate[last - 1].segment == current_[last - 1].segment &&
           candidate[last - 1].reversed == current_[last - 1].reversed)
      --last;
    if (last == from) return cost_;
    for (std::size_t k = from; k < last; ++k) scratch_[candidate[k].segment] = static_cast<int>(k);
    const bool same_front = candidate.front().segment == current_.front().segment &&
                            candidate.front().reversed == current_.front().reversed;
    const double cost = run(candidate, from, scratch_, false, same_front ? last : kNoShortcut);
    for (std::size_t k = from; k < last; ++k)
      scratch_[current_[k].segment] = position_[current_[k].segment];
    return cost;
  }

  /// Makes `candidate` current; it equals the current sequence outside [from, last).
  void accept(const Sequence& candidate, std::size_t from, std::size_t last) {
    std::copy(candidate.begin() + from, candidate.begin() + last, current_.begin() + from);
    for (std::size_t k = from; k < last; ++k) {
      position_[current_[k].segment] = static_cast<int>(k);
      scratch_[current_[k].segment] = static_cast<int>(k);
    }
    cost_ = run(current_, from, position_, true);
  }

  double cost() const { return cost_; }
  const Sequence& current() const { return current_; }
  long steps() const { return steps_; }

 private:
  static constexpr std::size_t kNoShortcut = static_cast<std::size_t>(-1);

  /// The nozzle is in the same state as the current sequence's before step k.
  bool converged(const PathState& state, std::size_t k) const {
    const PathState& s = state_[k];
    return state.point == s.point && state.steps == s.steps && state.position_m == s.position_m &&
           std::abs(state.heading_rad - s.heading_rad) <= 1e-12 &&
           state.initial_heading_rad == s.initial_heading_rad;
  }

  /// Airtime of `sequence` from `from` on (the states before it are the current's). With
  /// `shortcut_after` set (not when storing), stops at the first step at or past it where
  /// the state has converged to the current sequence's, adding the current's rest.
  double run(const Sequence& sequence, std::size_t from, const std::vector<int>& position,
             bool store, std::size_t shortcut_after = kNoShortcut) {
    PathState state = from == 0 ? model_.begin(path_) : state_[from];
    double time = time_[from];
    for (std::size_t k = from; k < sequence.size(); ++k) {
      if (k >= shortcut_after && k > from && converged(state, k)) {
        steps_ += static_cast<long>(k - from);
        return time + (cost_ - time_[k]);
      }
      if (store) {
        state_[k] = state;
        time_[k] = time;
      }
      const int here = static_cast<int>(k);
      const Move m = model_.advance(state, sequence[k], path_,
                                    [&](int s) { return position[s] >= 0 && position[s] < here; });
      if (k > 0 || !path_.closed) time += m.time_s;
    }
    steps_ += static_cast<long>(sequence.size() - from) + 1;
    if (store) {
      state_[sequence.size()] = state;
      time_[sequence.size()] = time;
    }
    if (path_.closed && !sequence.empty())
      time += model_.close(state, sequence.front(), [&](int s) { return position[s] >= 0; }).time_s;
    return time;
  }

  const CostModel& model_;
  const PathSpec& path_;
  Sequence current_;
  std::vector<int> position_;
  std::vector<int> scratch_;
  std::vector<PathState> state_;
  std::vector<double> time_;
  double cost_ = 0.0;
  long steps_ = 0;
};

/// Reverses s[i, j] in place, each step turned round.
void reverse_block(Sequence& s, std::size_t i, std::size_t j) {
  std::reverse(s.begin() + i, s.begin() + j + 1);
  for (std::size_t k = i; k <= j; ++k) s[k].reversed = !s[k].reversed;
}

/// Moves s[i, i+length) in place so that it starts at `to`, reversed or not; the steps
/// between shift over. Changes s[min(i, to), max(i, to) + length) only.
void move_block(Sequence& s, std::size_t i, std::size_t length, std::size_t to, bool reversed) {
  if (to < i)
    std::rotate(s.begin() + to, s.begin() + i, s.begin() + i + length);
  else if (to > i)
    std::rotate(s.begin() + i, s.begin() + i + length, s.begin() + to + length);
  if (reversed) reverse_block(s, to, to + length - 1);
}

Sequence reversed_block(Sequence s, std::size_t i, std::size_t j) {
  reverse_block(s, i, j);
  return s;
}

Sequence moved_block(Sequence s, std::size_t i, std::size_t length, std::size_t to, bool reversed) {
  move_block(s, i, length, to, reversed);
  return s;
}

}  // namespace

ExactPolishOutcome improve_exact_time(const CostModel& model, Sequence sequence,
                                      const PathSpec& path, std::size_t fixed_prefix,
                                      const ExactPolishSettings& settings, std::mt19937_64& rng,
                                      const StopCondition& stop) {
  const std::size_t n = sequence.size();
  if (n < 2) return {std::move(sequence), 0};
  IncrementalTime eval(model, path);
  eval.reset(sequence);
  const std::size_t window = std::max<std::size_t>(1, std::min(n, settings.window));
  auto out_of_budget = [&] {
    return eval.steps() >= settings.max_step_evaluations || stop.should_stop();
  };
  // Candidates are made in `work`, a copy of the current sequence, over the range they
  // change, and undone there when refused: no copy of the whole sequence per candidate.
  Sequence work = eval.current();
  auto try_work = [&](std::size_t from, std::size_t last) {
    if (eval.evaluate(work, from, last) < eval.cost() - 1e-9) {
      eval.accept(work, from, last);
      return true;
    }
    std::copy(eval.current().begin() + from, eval.current().begin() + last, work.begin() + from);
    return false;
  };
  // Where a closed tour starts, and its direction, change its lifts and its unwinding.
  auto try_rotations = [&] {
    if (!path.closed) return false;
    for (std::size_t r = 1; r < n; ++r) {
      const Sequence& cur = eval.current();
      std::rotate_copy(cur.begin(), cur.begin() + r, cur.end(), work.begin());
      if (try_work(0, n)) return true;
    }
    reverse_block(work, 0, n - 1);
    return try_work(0, n);
  };
  // The first position a move from position i may reach back to.
  auto window_start = [&](std::size_t i) {
    return std::max(fixed_prefix, i > window ? i - window : 0);
  };
  // 2-opt and Or-opt moves that change the sequence from position i on.
  auto try_at = [&](std::size_t i) {
    for (std::size_t j = i; j < std::min(n, i + window); ++j) {
      reverse_block(work, i, j);
      if (try_work(i, j + 1)) return true;
    }
    for (std::size_t length = 1; length <= 3 && i + length <= n; ++length) {
      const std::size_t lo = window_start(i);
      const std::size_t hi = std::min(n - length, i + window);
      for (std::size_t to = lo; to <= hi; ++to) {
        if (to == i) continue;
        for (bool reversed : {false, true}) {
          move_block(work, i, length, to, reversed);
          if (try_work(std::min(i, to), std::max(i, to) + length)) return true;
        }
      }
    }
    return false;
  };
  // First improvement, scanning positions round and round until a whole round is quiet.
  auto descend = [&] {
    const std::size_t movable = n - fixed_prefix;
    bool again = true;
    while (again && !out_of_budget()) {
      again = try_rotations();
      std::size_t i = fixed_prefix, quiet = 0;
      while (quiet < movable && !out_of_budget()) {
        if (try_at(i)) {
          quiet = 0;
          again = true;
        } else {
          ++quiet;
        }
        i = i + 1 < n ? i + 1 : fixed_prefix;
      }
      again = again && path.closed;  // a changed closed tour may now start better elsewhere
    }
  };

  // The same around [lo, hi) only: its positions are tried until a pass there finds
  // nothing; an improvement widens the range by the window, as far as its moves reach.
  auto descend_around = [&](std::size_t lo, std::size_t hi) {
    for (bool again = true; again && !out_of_budget();) {
      again = false;
      for (std::size_t i = lo; i < hi && !out_of_budget(); ++i) {
        if (!try_at(i)) continue;
        again = true;
        lo = std::min(lo, window_start(i));
        hi = std::max(hi, std::min(n, i + window + 1));
      }
    }
  };

  descend();
  Sequence best = eval.current();
  double best_cost = eval.cost();
  if (settings.on_better) settings.on_better(0, best_cost);
  const std::size_t movable = n - fixed_prefix;
  // A double bridge on the movable part: two adjacent blocks [start, start + first) and
  // the `second` steps after it, to be swapped; none when they do not fit.
  struct Bridge {
    std::size_t start, first, second;
  };
  auto pick_bridge = [&]() -> std::optional<Bridge> {
    const std::size_t cap = std::max<std::size_t>(1, std::min<std::size_t>(movable / 3, 8));
    const std::size_t first = 1 + rng() % cap, second = 1 + rng() % cap;
    if (first + second > movable) return std::nullopt;
    return Bridge{fixed_prefix + rng() % (movable - first - second + 1), first, second};
  };
  // Keeps the current sequence when no slower than the best (equal too: walk along
  // plateaus); says whether it was kept.
  auto keep_if_no_slower = [&](long kicks) {
    if (eval.cost() > best_cost + 1e-9) return false;
    const bool faster = eval.cost() < best_cost - 1e-9;
    best = eval.current();
    best_cost = std::min(best_cost, eval.cost());
    if (faster && settings.on_better) settings.on_better(kicks, best_cost);
    return true;
  };
  long kick = 0;
  for (; kick < settings.max_kicks && movable >= 4 && !out_of_budget(); ++kick) {
    if (settings.local_kicks) {
      // The bridge taken whatever it costs, then a descent around it alone; back to the
      // best sequence when that ends slower.
      const auto bridge = pick_bridge();
      if (!bridge) continue;
      const auto [start, first, second] = *bridge;
      move_block(work, start, first, start + second, rng() % 2 == 0);
      eval.accept(work, start, start + first + second);
      descend_around(window_start(start), std::min(n, start + first + second + window));
      if (stop.should_stop()) break;  // its descent may be unfinished: dropped
      if (!keep_if_no_slower(kick + 1)) {
        eval.reset(best);
        work = best;
      }
      continue;
    }
    if (kick % 2 == 0) {
      const auto bridge = pick_bridge();
      if (!bridge) continue;
      const auto [start, first, second] = *bridge;
      eval.reset(moved_block(best, start, first, start + second, rng() % 2 == 0));
    } else {
      // Reverse a block of any length: reaches orders that small swaps cannot.
      const std::size_t i = fixed_prefix + rng() % movable;
      const std::size_t j = fixed_prefix + rng() % movable;
      eval.reset(reversed_block(best, std::min(i, j), std::max(i, j)));
    }
    work = eval.current();
    descend();
    if (stop.should_stop()) break;  // as above
    keep_if_no_slower(kick + 1);
  }
  return {std::move(best), kick};
}

}  // namespace ccbuild::planner::detail
