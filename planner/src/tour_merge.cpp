#include "tour_merge.hpp"

#include <algorithm>
#include <limits>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::planner::detail {
namespace {

constexpr double kEps = 1e-9;

/// Joins the pieces (cycles of walls and air moves) that `mates` make into one by the
/// cheapest 2-exchanges, smallest piece first. Returns what joining cost, or infinity as
/// soon as it reaches `budget` (mates then half joined: discard them). Appends the items
/// whose air moves changed to `moved`.
double join_pieces(const TourCosts& costs, std::vector<int>& mates, double budget,
                   std::vector<int>& moved, int& joins) {
  const int nodes = static_cast<int>(mates.size());
  std::vector<int> piece(nodes, -1);
  std::vector<std::vector<int>> members;
  for (int s = 0; s < nodes; s += 2) {
    if (piece[s] >= 0) continue;
    const int id = static_cast<int>(members.size());
    members.emplace_back();
    int entry = s;
    do {
      piece[entry] = piece[entry ^ 1] = id;
      members[id].push_back(entry);
      members[id].push_back(entry ^ 1);
      entry = mates[entry ^ 1];
    } while (entry != s && piece[entry] < 0);
  }
  const double kNone = std::numeric_limits<double>::infinity();
  double spent = 0.0;
  for (int left = static_cast<int>(members.size()); left > 1; --left) {
    int small = -1;
    for (int id = 0; id < static_cast<int>(members.size()); ++id)
      if (!members[id].empty() && (small < 0 || members[id].size() < members[small].size()))
        small = id;
    // Remove air moves (a, a') of the small piece and (b, b') of another; add (a, b) and
    // (a', b'), or (a, b') and (a', b): either way one piece.
    double best = kNone;
    int best_a = -1, best_b = -1;
    bool crossed = false;
    auto consider = [&](int a, int b) {
      if (piece[b] == small) return;
      const int a2 = mates[a], b2 = mates[b];
      const double removed = costs.cost(a, a2) + costs.cost(b, b2);
      const double straight = costs.cost(a, b) + costs.cost(a2, b2) - removed;
      const double cross = costs.cost(a, b2) + costs.cost(a2, b) - removed;
      if (straight < best) best = straight, best_a = a, best_b = b, crossed = false;
      if (cross < best) best = cross, best_a = a, best_b = b, crossed = true;
    };
    for (int a : members[small])
      for (int b : costs.neighbours(a)) consider(a, b);
    if (best_a < 0)  // no candidate leaves the piece: every end (rare, small pieces)
      for (int a : members[small])
        for (int b = 0; b < nodes; ++b) consider(a, b);
    spent += best;
    if (spent >= budget) return kNone;
    const int a = best_a, a2 = mates[a];
    const int b = crossed ? mates[best_b] : best_b, b2 = mates[b];
    mates[a] = b, mates[b] = a, mates[a2] = b2, mates[b2] = a2;
    for (int end : {a, a2, b, b2}) moved.push_back(end / 2);
    ++joins;
    const int into = piece[best_b];
    for (int end : members[small]) piece[end] = into;
    members[into].insert(members[into].end(), members[small].begin(), members[small].end());
    members[small].clear();
  }
  return spent;
}

}  // namespace

std::vector<int> air_mates(const WallTour& tour) {
  std::vector<int> mates(2 * tour.size());
  for (int p = 0; p < tour.size(); ++p) {
    const int exit = tour.exit(p), entry = tour.entry(tour.next(p));
    mates[exit] = entry;
    mates[entry] = exit;
  }
  return mates;
}

WallTour tour_of_mates(const std::vector<int>& mates) {
  const int items = static_cast<int>(mates.size()) / 2;
  std::vector<int> order;
  order.reserve(items);
  std::vector<char> reversed(items, 0);
  int entry = 0;
  do {
    CCBUILD_CHECK(static_cast<int>(order.size()) < items, "air moves make one tour");
    order.push_back(entry / 2);
    reversed[entry / 2] = static_cast<char>(entry & 1);
    entry = mates[entry ^ 1];
  } while (entry != 0);
  CCBUILD_CHECK(static_cast<int>(order.size()) == items, "air moves make one tour");
  return WallTour(std::move(order), std::move(reversed));
}

double merge_tours(const TourCosts& costs, WallTour& best, const WallTour& other,
                   std::vector<int>& touched, MergeCounts* counts) {
  MergeCounts counted;
  std::vector<int> mates = air_mates(best);
  const std::vector<int> theirs = air_mates(other);
  const int nodes = static_cast<int>(mates.size());
  // Alternating cycles: ends x0, y0, x1, y1, ... with (x_i, y_i) air moves of `best` and
  // (y_i, x_i+1) of `other`.
  struct Cycle {
    double gain = 0.0;
    std::vector<int> ends;
  };
  std::vector<Cycle> cycles;
  std::vector<char> seen(nodes, 0);
  for (int u = 0; u < nodes; ++u) {
    if (seen[u] || mates[u] == theirs[u]) continue;
    Cycle cycle;
    int x = u;
    do {
      const int y = mates[x];
      seen[x] = seen[y] = 1;
      cycle.ends.push_back(x);
      cycle.ends.push_back(y);
      cycle.gain += costs.cost(x, y) - costs.cost(y, theirs[y]);
      x = theirs[y];
    } while (x != u);
    if (cycle.gain > kEps) cycles.push_back(std::move(cycle));
  }
  std::stable_sort(cycles.begin(), cycles.end(),
                   [](const Cycle& a, const Cycle& b) { return a.gain > b.gain; });
  double total = 0.0;
  std::vector<int> trial, moved;
  for (const Cycle& cycle : cycles) {
    // An earlier cycle's joining may have taken one of this cycle's air moves.
    bool intact = true;
    for (std::size_t i = 0; i < cycle.ends.size() && intact; i += 2)
      intact = mates[cycle.ends[i]] == cycle.ends[i + 1];
    if (!intact) continue;
    trial = mates;
    moved.clear();
    for (std::size_t i = 1; i < cycle.ends.size(); i += 2) {
      const int y = cycle.ends[i], z = theirs[y];
      trial[y] = z;
      trial[z] = y;
      moved.push_back(y / 2);
      moved.push_back(z / 2);
    }
    int joins = 0;
    const double joining = join_pieces(costs, trial, cycle.gain - kEps, moved, joins);
    if (cycle.gain - joining <= kEps) continue;
    mates.swap(trial);
    total += cycle.gain - joining;
    ++counted.kept;
    counted.joins += joins;
    touched.insert(touched.end(), moved.begin(), moved.end());
  }
  counted.cycles = static_cast<int>(cycles.size());
  if (counts) *counts = counted;
  if (total > 0.0) best = tour_of_mates(mates);
  return total;
}

}  // namespace ccbuild::planner::detail
