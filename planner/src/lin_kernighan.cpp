#include "lin_kernighan.hpp"

#include <algorithm>
#include <limits>

namespace ccbuild::planner::detail {

namespace {
constexpr double kEps = 1e-9;
std::pair<int, int> edge(int u, int v) {
  return u < v ? std::pair{u, v} : std::pair{v, u};
}
}  // namespace

LinKernighan::LinKernighan(const TourCosts& costs, WallTour& tour, int max_depth,
                           int short_flip_items)
    : costs_(costs),
      tour_(tour),
      view_(tour),
      max_depth_(max_depth),
      short_flip_items_(short_flip_items),
      queue_(tour.size()) {}

double LinKernighan::run(const StopCondition& stop) {
  double total = 0.0;
  long steps = 0;
  while (!queue_.empty()) {
    if ((++steps & 63) == 0 && stop.should_stop()) break;
    const int item = queue_.pop();
    for (int side = 0; side < 2; ++side) {
      double gain = 0.0;
      if (improve_from(2 * item + side, gain)) {
        total += gain;
        for (int node : touched_) queue_.push(node / 2);
        break;  // the item itself is queued again among the touched
      }
    }
  }
  return total;
}

bool LinKernighan::between(bool forwards, int ia, int ib, int ic) const {
  const int n = 2 * view_.size();
  if (forwards) return (ib - ia + n) % n <= (ic - ia + n) % n;
  return (ia - ib + n) % n <= (ia - ic + n) % n;
}

std::pair<int, int> LinKernighan::flip_range(int a, int b, int d) const {
  // Walking a, b, ..., d, c one way round; b .. d are whole items (b enters its item, d
  // leaves its own), so reversing their positions keeps every fixed edge.
  int first = view_.place(b / 2).position, last = view_.place(d / 2).position;
  if (suc(spot(a)) != b) std::swap(first, last);
  return {first, last};
}

void LinKernighan::make_2opt(int a, int b, int c, int d) {
  const auto [first, last] = flip_range(a, b, d);
  const int n = view_.size();
  const int length = (last - first + n) % n + 1;
  // A short flip is made on the WallTour at once (and undone there if the chain fails);
  // from the first long one on, the chain's flips go to the view.
  if (view_.runs() == 1 && std::min(length, n - length) <= short_flip_items_) {
    tour_.reverse(first, last);
    tour_flips_.push_back({a, b, c, d});
  } else {
    view_.reverse(first, last);
    view_flips_.push_back({a, b, c, d});
  }
}

void LinKernighan::flip_on_tour(int a, int b, int d) {
  // With the view reset, its positions are the WallTour's.
  const auto [first, last] = flip_range(a, b, d);
  tour_.reverse(first, last);
}

void LinKernighan::undo_chain() {
  view_.reset();
  view_flips_.clear();
  // The inverse of the flip for (a, b, c, d) is the flip for (c, b, a, d).
  for (auto f = tour_flips_.rbegin(); f != tour_flips_.rend(); ++f) flip_on_tour(f->c, f->b, f->d);
  tour_flips_.clear();
}

void LinKernighan::commit_chain() {
  view_.reset();
  for (const Flip& f : view_flips_) flip_on_tour(f.a, f.b, f.d);
  view_flips_.clear();
  tour_flips_.clear();
}

bool LinKernighan::was_added(int u, int v) const {
  return std::find(added_.begin(), added_.end(), edge(u, v)) != added_.end();
}

bool LinKernighan::was_removed(int u, int v) const {
  return std::find(removed_.begin(), removed_.end(), edge(u, v)) != removed_.end();
}

bool LinKernighan::improve_from(int t1, double& gain) {
  if (tour_.size() < 3) return false;
  int t2 = free_neighbour(spot(t1));
  added_.clear();
  removed_.assign(1, edge(t1, t2));
  touched_.assign({t1, t2});
  double open_gain = c(t1, t2);
  for (int depth = 0; depth < max_depth_; ++depth) {
    const Step step = best_step(t1, t2, open_gain, depth + 1 == max_depth_);
    if (step.improved) {
      commit_chain();
      gain = step.gain;
      return true;
    }
    if (!step.found) break;
    t2 = step.next_t2;
    open_gain = step.gain;
  }
  undo_chain();
  return false;
}

LinKernighan::Step LinKernighan::best_step(int t1, int t2, double open_gain, bool last) {
  // Orientation: walking "forwards" means from t1 to t2. S and P follow it.
  // Each node's place in the view is looked up once (a lookup walks the chain's runs).
  const bool forwards = suc(spot(t1)) == t2;
  auto S = [&](const Spot& x) { return forwards ? suc(x) : pred(x); };
  auto P = [&](const Spot& x) { return forwards ? pred(x) : suc(x); };
  const int i2 = index(spot(t2));
  Step out;
  double best_open = kEps;
  int best[4] = {-1, -1, -1, -1};  // t3, t4, t5, t6 of the best open step (t5 < 0: 2-opt)

  auto finish = [&](int t3, int t4, int t5, int t6) {
    if (t5 < 0) {
      make_2opt(t1, t2, t3, t4);
    } else if (S(spot(t5)) == t6) {
      // t1 t2 A t5 t6 B t3 t4 C  ->  t1 t6 B t3 t2 A t5 t4 C
      make_2opt(t1, t2, t6, t5);
      make_2opt(t1, t5, t4, t3);
      make_2opt(t1, t3, t2, t6);
    } else {
      // t1 t2 A t6 t5 B t3 t4 C  ->  t1 t6 A' t2 t3 B' t5 t4 C
      make_2opt(t1, t2, t5, t6);
      make_2opt(t2, t5, t4, t3);
    }
    added_.push_back(edge(t2, t3));
    removed_.push_back(edge(t3, t4));
    touched_.insert(touched_.end(), {t3, t4});
    if (t5 >= 0) {
      added_.push_back(edge(t4, t5));
      removed_.push_back(edge(t5, t6));
      touched_.insert(touched_.end(), {t5, t6});
    }
  };

  for (int t3 : costs_.neighbours(t2)) {
    const double g1 = open_gain - c(t2, t3);
    if (g1 <= kEps) break;  // candidates come cheapest first
    if (t3 / 2 == t2 / 2 || t3 == t1 || was_removed(t2, t3)) continue;
    const Spot s3 = spot(t3);
    for (int kind = 0; kind < 2; ++kind) {
      const int t4 = kind == 0 ? P(s3) : S(s3);
      if (t4 / 2 == t3 / 2 || was_added(t3, t4)) continue;  // fixed or new edge
      const double g2 = g1 + c(t3, t4);
      if (kind == 0) {
        // t1 t2 .. t4 t3: closing with (t4, t1) is a 2-opt move.
        const double closed = g2 - c(t4, t1);
        if (closed > kEps) {
          finish(t3, t4, -1, -1);
          out.improved = true;
          out.gain = closed;
          return out;
        }
        if (g2 > best_open && !was_removed(t4, t1)) {
          best_open = g2;
          best[0] = t3, best[1] = t4, best[2] = -1, best[3] = -1;
        }
        continue;
      }
      // t1 t2 .. t3 t4: (t2, t3) closes t2 .. t3 into a loop; break it at (t5, t6) and
      // join it in between t4 and t1.
      for (int t5 : costs_.neighbours(t4)) {
        const double g3 = g2 - c(t4, t5);
        if (g3 <= kEps) break;
        if (t5 == t2 || t5 == t3 || t5 / 2 == t4 / 2 || was_removed(t4, t5)) continue;
        const Spot s5 = spot(t5);
        if (!between(forwards, i2, index(s5), index(s3))) continue;
        const int t6 = free_neighbour(s5);
        if (was_added(t5, t6)) continue;
        const double g4 = g3 + c(t5, t6);
        const double closed = g4 - c(t6, t1);
        if (closed > kEps) {
          finish(t3, t4, t5, t6);
          out.improved = true;
          out.gain = closed;
          return out;
        }
        if (g4 > best_open && !was_removed(t6, t1)) {
          best_open = g4;
          best[0] = t3, best[1] = t4, best[2] = t5, best[3] = t6;
        }
      }
    }
  }
  // The last step only closes: an open one would only be undone.
  if (last || best[0] < 0) return out;
  finish(best[0], best[1], best[2], best[3]);
  out.found = true;
  out.next_t2 = best[2] < 0 ? best[1] : best[3];
  out.gain = best_open;
  return out;
}

}  // namespace ccbuild::planner::detail
