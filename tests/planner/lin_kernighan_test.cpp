// The Lin–Kernighan search itself (planner/src/lin_kernighan.hpp): exact gains, fixed
// edges kept, and no improving candidate move left behind.

#include "lin_kernighan.hpp"

#include "flipped_tour.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "layouts.hpp"
#include "test_support.hpp"
#include "wall_tours.hpp"

namespace ccbuild::planner::detail {
namespace {

/// The best gain of any 2-opt move between two free edges whose new edge (t2, t3) has t3
/// among t2's candidates: LK's first level must have found every one of them.
double best_candidate_two_opt(const TourCosts& costs, const WallTour& tour) {
  double best = 0.0;
  const int n = tour.size();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      // Free edges (a, b) after position i and (c, d) after j; reversing i+1 .. j joins
      // (a, c) and (b, d).
      const int a = tour.exit(i), b = tour.entry(tour.next(i));
      const int c = tour.exit(j), d = tour.entry(tour.next(j));
      const auto& nb = costs.neighbours(b);
      const auto& na = costs.neighbours(a);
      const bool candidate = std::find(nb.begin(), nb.end(), d) != nb.end() ||
                             std::find(na.begin(), na.end(), c) != na.end();
      if (!candidate) continue;
      best =
          std::max(best, costs.cost(a, b) + costs.cost(c, d) - costs.cost(a, c) - costs.cost(b, d));
    }
  }
  return best;
}

TEST(LinKernighan, GainsAreExactAndNoCandidateTwoOptIsLeft) {
  const machine::MachineModel machine = testing::simple_machine();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const floors::Layer layer =
        seed % 2 ? testing::random_layer(30, seed) : testing::floor_plan_layer(8 + int(seed), seed);
    const CostModel model(layer, machine, Metric::kEuclidean);
    std::vector<int> segments(layer.segments.size());
    std::iota(segments.begin(), segments.end(), 0);
    TourCosts costs(model, segments, Objective::kDistance, false, Vec2::Zero(), std::nullopt);
    costs.build_neighbours(8);
    WallTour tour = random_tour(costs.item_count(), seed);
    const double before = tour.cost(costs);
    LinKernighan search(costs, tour, 10);
    for (int item = 0; item < tour.size(); ++item) search.push(item);
    const double gain = search.run(StopCondition());
    EXPECT_TRUE(visits_every_item_once(tour)) << seed;
    EXPECT_NEAR(before - gain, tour.cost(costs), 1e-6) << seed;
    EXPECT_GT(gain, 0.0) << seed;
    EXPECT_LE(best_candidate_two_opt(costs, tour), 1e-9) << seed;
  }
}

/// The entry node at each position of a walk.
std::vector<int> entries_of(const WallTour& tour) {
  std::vector<int> entries(tour.size());
  for (int p = 0; p < tour.size(); ++p) entries[p] = tour.entry(p);
  return entries;
}

/// A walk's air moves (by its entry node at each position) as unordered node pairs: the
/// same for a tour walked either way.
std::vector<std::pair<int, int>> air_moves(const std::vector<int>& entries) {
  std::vector<std::pair<int, int>> out;
  const int n = static_cast<int>(entries.size());
  for (int p = 0; p < n; ++p) {
    const int a = entries[p] ^ 1, b = entries[(p + 1) % n];
    out.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(out.begin(), out.end());
  return out;
}
std::vector<std::pair<int, int>> air_moves(const WallTour& tour) {
  return air_moves(entries_of(tour));
}

/// The list model of a reversal: the `length` positions from `first` (cyclic) in the
/// other order, each item turned round.
std::vector<int> reversed_walk(const std::vector<int>& entries, int first, int length) {
  const int n = static_cast<int>(entries.size());
  std::vector<int> out = entries;
  for (int k = 0; k < length; ++k) out[(first + k) % n] = entries[(first + length - 1 - k) % n] ^ 1;
  return out;
}

// A reversal, whichever side it flips (the range or its shorter complement, the whole tour
// included), gives the tour a plain list model gives: the range's items in the other
// order, each turned round.
TEST(WallTour, ReversalMatchesAListModel) {
  std::mt19937_64 rng(3);
  for (int items : {2, 3, 4, 5, 8, 13}) {
    WallTour tour = random_tour(items, static_cast<std::uint64_t>(items));
    for (int round = 0; round < 300; ++round) {
      const int first = static_cast<int>(rng() % items);
      const int length = 1 + static_cast<int>(rng() % items);  // the whole tour too
      const std::vector<int> flipped = reversed_walk(entries_of(tour), first, length);
      const WallTour list(
          [&] {
            std::vector<int> order;
            for (int node : flipped) order.push_back(node / 2);
            return order;
          }(),
          [&] {
            std::vector<char> reversed(items);
            for (int node : flipped) reversed[node / 2] = static_cast<char>(node % 2);
            return reversed;
          }());
      tour.reverse(first, (first + length - 1) % items);
      ASSERT_TRUE(visits_every_item_once(tour)) << items << " " << round;
      ASSERT_EQ(air_moves(tour), air_moves(list)) << items << " " << round;
    }
  }
}

// The view a chain's long flips go to gives the tour a list model gives, whichever side
// it reverses (a range that wraps, a single item, the whole tour), and finds each item
// where it puts it; it never touches the tour under it, and a reset returns to it.
TEST(FlippedTour, ReversalsMatchAListModel) {
  std::mt19937_64 rng(7);
  for (int items : {2, 3, 4, 5, 8, 13, 40}) {
    const WallTour tour = random_tour(items, static_cast<std::uint64_t>(items) + 100);
    const std::vector<int> base = entries_of(tour);
    FlippedTour view(tour);
    for (int round = 0; round < 200; ++round) {
      if (round % 12 == 0) view.reset();
      // The model reverses the view's walk as it is now, position for position.
      std::vector<int> before(items);
      for (int p = 0; p < items; ++p) before[p] = view.entry(p);
      const int first = static_cast<int>(rng() % items);
      const int length = 1 + static_cast<int>(rng() % items);
      const std::vector<int> model = reversed_walk(before, first, length);
      view.reverse(first, (first + length - 1) % items);
      std::vector<int> walked(items);
      for (int p = 0; p < items; ++p) {
        walked[p] = view.entry(p);
        const FlippedTour::Place at = view.place(walked[p] / 2);
        ASSERT_EQ(at.position, p) << items << " " << round;
        ASSERT_EQ(at.entry, walked[p]) << items << " " << round;
      }
      ASSERT_EQ(air_moves(walked), air_moves(model)) << items << " " << round;
      ASSERT_LE(view.runs(), 1 + 2 * (round % 12 + 1)) << items << " " << round;
    }
    for (int p = 0; p < items; ++p) ASSERT_EQ(tour.entry(p), base[p]) << items;
    view.reset();
    for (int p = 0; p < items; ++p) ASSERT_EQ(view.entry(p), base[p]) << items;
  }
}

// Where a chain's flips are made is only speed: every flip in the view, every flip on
// the tour, or the first few on the tour and the rest in the view, the search makes the
// same moves and ends in the same tour, position for position, with the same gain.
TEST(LinKernighan, ChainsInTheViewEndInTheSameTour) {
  const machine::MachineModel machine = testing::simple_machine();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const floors::Layer layer = seed % 2 ? testing::random_layer(60, seed)
                                         : testing::floor_plan_layer(12 + int(seed), seed);
    const CostModel model(layer, machine, Metric::kEuclidean);
    std::vector<int> segments(layer.segments.size());
    std::iota(segments.begin(), segments.end(), 0);
    TourCosts costs(model, segments, Objective::kDistance, false, Vec2::Zero(), std::nullopt);
    costs.build_neighbours(8);
    std::vector<std::vector<int>> ends;
    std::vector<double> gains;
    for (int short_flip_items : {1'000'000, 0, 3}) {
      WallTour tour = random_tour(costs.item_count(), seed);
      LinKernighan search(costs, tour, 10, short_flip_items);
      for (int item = 0; item < tour.size(); ++item) search.push(item);
      // Milliseconds when right; the limit only ends a search that a wrong tour keeps
      // "improving" (the ends then differ).
      gains.push_back(search.run(StopCondition(5.0)));
      ASSERT_TRUE(visits_every_item_once(tour)) << seed << " " << short_flip_items;
      ends.push_back(entries_of(tour));
    }
    EXPECT_GT(gains[0], 0.0) << seed;
    for (std::size_t k = 1; k < ends.size(); ++k) {
      EXPECT_EQ(ends[k], ends[0]) << seed << " " << k;
      EXPECT_EQ(gains[k], gains[0]) << seed << " " << k;
    }
  }
}

// The journal that undoes a rejected kick returns exactly to the tour before it, after
// any mix of reversals and block moves (both directions, reversed or not).
TEST(WallTourJournal, UndoReturnsToTheTourBefore) {
  std::mt19937_64 rng(5);
  WallTour tour = random_tour(37, 9);
  for (int round = 0; round < 200; ++round) {
    const WallTour before = tour;
    tour.begin_journal();
    const int changes = 1 + static_cast<int>(rng() % 6);
    for (int k = 0; k < changes; ++k) {
      const int n = tour.size();
      if (rng() % 2) {
        tour.reverse(static_cast<int>(rng() % n), static_cast<int>(rng() % n));
      } else {
        const int length = 1 + static_cast<int>(rng() % 10);
        const int first = static_cast<int>(rng() % n);
        const int after = (first + length + static_cast<int>(rng() % (n - length - 1))) % n;
        tour.move_block(first, length, after, rng() % 2 != 0);
      }
    }
    const bool keep = rng() % 3 == 0;
    if (keep) {
      tour.commit_journal();
      continue;
    }
    tour.undo_journal();
    for (int p = 0; p < tour.size(); ++p) {
      ASSERT_EQ(tour.item_at(p), before.item_at(p)) << round;
      ASSERT_EQ(tour.position_of(tour.item_at(p)), p) << round;
      ASSERT_EQ(tour.reversed(tour.item_at(p)), before.reversed(before.item_at(p))) << round;
    }
  }
}

// LK reaches what 2-opt and Or-opt cannot: from their local optimum (the 2-opt/Or-opt
// search without kicks) it still finds gains, exactly accounted for.
TEST(LinKernighan, ImprovesOnTwoOptAndOrOptLocalOptima) {
  const machine::MachineModel machine = testing::simple_machine();
  double total_gain = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const floors::Layer layer = testing::random_layer(40, seed);
    const CostModel model(layer, machine, Metric::kEuclidean);
    std::vector<int> segments(layer.segments.size());
    std::iota(segments.begin(), segments.end(), 0);
    TourCosts costs(model, segments, Objective::kDistance, false, Vec2::Zero(), std::nullopt);
    costs.build_neighbours(8);
    SearchSettings settings;
    settings.neighbourhood = Neighbourhood::kTwoOptOrOpt;
    settings.max_kicks = 0;
    settings.seed = seed;
    SearchOutcome local = chained_local_search(costs, random_tour(costs.item_count(), seed),
                                               settings, StopCondition());
    LinKernighan search(costs, local.tour, 10);
    for (int item = 0; item < local.tour.size(); ++item) search.push(item);
    const double gain = search.run(StopCondition());
    EXPECT_TRUE(visits_every_item_once(local.tour)) << seed;
    EXPECT_NEAR(local.cost - gain, local.tour.cost(costs), 1e-6) << seed;
    total_gain += gain;
  }
  EXPECT_GT(total_gain, 1e-3);
}

/// A 6-room layer's search costs in time, built as the search builds them.
class TimeCosts : public ::testing::Test {
 protected:
  TimeCosts() { std::iota(segments.begin(), segments.end(), 0); }
  TourCosts costs() const {
    return TourCosts(model, segments, Objective::kTime, false, Vec2::Zero(), std::nullopt);
  }
  const machine::MachineModel machine = testing::simple_machine();
  const floors::Layer layer = testing::floor_plan_layer(6, 2);
  const CostModel model{layer, machine, Metric::kEuclidean};
  std::vector<int> segments = std::vector<int>(layer.segments.size());
};

// The search's time costs never price a move as lifted, even one across a wall: whether
// it lifts depends on what is built before it (the exact-time polish's business). At
// most a half turn, so each cost stays under an unlifted move with a half turn, which a
// lift (5 s on this machine, against a 3.14 s half turn) would exceed.
TEST_F(TimeCosts, PriceNoLift) {
  const TourCosts costs = this->costs();
  int crossing = 0;
  for (int u = 0; u < 2 * static_cast<int>(segments.size()); ++u) {
    for (int v = 0; v < 2 * static_cast<int>(segments.size()); ++v) {
      const Vec2 &a = costs.position(u), &b = costs.position(v);
      if (u / 2 == v / 2 || model.distance_m(a, b) < 1e-6 || model.crossed_segments(a, b).empty())
        continue;
      ++crossing;
      EXPECT_LE(costs.cost(u, v), model.move_time_s(a, b, M_PI, false) + 1e-9) << u << " " << v;
      EXPECT_GE(costs.cost(u, v), model.move_time_s(a, b, 0.0, false) - 1e-9) << u << " " << v;
    }
  }
  EXPECT_GT(crossing, 100);
}

// Time costs are remembered in a table of about 32 slots a node, so that most pairs share
// a slot with others: read in any order, each is the cost of its own pair, and the same
// both ways.
TEST_F(TimeCosts, RememberedAreEachPairsOwn) {
  const int nodes = 2 * static_cast<int>(segments.size());
  ASSERT_GT(nodes, 64);  // more pairs than slots
  const TourCosts in_order = costs(), shuffled = costs();
  std::vector<std::pair<int, int>> pairs;
  for (int u = 0; u < nodes; ++u)
    for (int v = 0; v < nodes; ++v)
      if (u != v) pairs.emplace_back(u, v);
  std::vector<double> first(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k)
    first[k] = in_order.cost(pairs[k].first, pairs[k].second);
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(7));
  for (int pass = 0; pass < 2; ++pass)
    for (const std::size_t k : order) {
      const auto [u, v] = pairs[k];
      ASSERT_EQ(shuffled.cost(u, v), first[k]) << u << " " << v << " pass " << pass;
      ASSERT_EQ(in_order.cost(v, u), first[k]) << u << " " << v << " pass " << pass;
      const Vec2 &a = in_order.position(u), &b = in_order.position(v);
      ASSERT_GE(first[k], model.move_time_s(a, b, 0.0, false) - 1e-9) << u << " " << v;
      ASSERT_LE(first[k], model.move_time_s(a, b, M_PI, false) + 1e-9) << u << " " << v;
    }
}

}  // namespace
}  // namespace ccbuild::planner::detail
