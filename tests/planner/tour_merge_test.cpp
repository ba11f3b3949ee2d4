// Merging a second tour's better parts into the best one (planner/src/tour_merge.hpp),
// and the restarts of the anytime search that use it.

#include "tour_merge.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <string>

#include "layouts.hpp"
#include "test_support.hpp"
#include "wall_tours.hpp"

namespace ccbuild::planner::detail {
namespace {

/// A distance tour over every wall of a layer, closed or open from a layer point, with
/// the search's own parts.
struct Instance {
  floors::Layer layer;
  CostModel model;
  std::vector<int> segments;
  bool open;
  Vec2 start;
  TourCosts costs;

  explicit Instance(floors::Layer l, bool open_path = false)
      : layer(std::move(l)),
        model(layer, testing::simple_machine(), Metric::kEuclidean),
        segments(every_segment(layer)),
        open(open_path),
        start(layer.points[layer.segments[3].end_point]),
        costs(model, segments, Objective::kDistance, open, start, std::nullopt) {
    costs.build_neighbours(8);
  }
  static std::vector<int> every_segment(const floors::Layer& layer) {
    std::vector<int> s(layer.segments.size());
    std::iota(s.begin(), s.end(), 0);
    return s;
  }
  WallTour euler(std::mt19937_64* variation = nullptr) const {
    return tour_from_sequence(
        costs, euler_construction(model, segments, open, start, std::nullopt, variation));
  }
  /// `kicks` kicks and no stall rule; with restarts as plan_layer's anytime search makes
  /// them (from varied Euler walks), but sooner.
  SearchOutcome search(WallTour start, long kicks, std::uint64_t seed, bool restarts,
                       const StopCondition& stop = StopCondition()) const {
    SearchSettings s;
    if (restarts) {
      s.restart_kicks = 2000;
      s.restart_stall_kicks = 1000;
      s.restart_own_stall_kicks = 1000;
    }
    return search(std::move(start), kicks, seed, s, stop);
  }
  SearchOutcome search(WallTour start, long kicks, std::uint64_t seed, SearchSettings s,
                       const StopCondition& stop = StopCondition()) const {
    s.max_kicks = s.stall_kicks = kicks;
    s.seed = seed;
    if (s.restart_stall_kicks > 0)
      s.restart_tour = [this](std::mt19937_64& rng) { return euler(&rng); };
    return chained_local_search(costs, std::move(start), s, stop);
  }
};

// Merges `other` into `best` and checks the outcome: one tour through every wall, never
// longer, cheaper by exactly the gain reported. Adds what the merge did to `all`.
void check_merge(const Instance& in, WallTour best, const WallTour& other, MergeCounts& all,
                 const std::string& what) {
  const double before = best.cost(in.costs);
  std::vector<int> touched;
  MergeCounts counts;
  const double gain = merge_tours(in.costs, best, other, touched, &counts);
  ASSERT_TRUE(visits_every_item_once(best)) << what;
  EXPECT_GE(gain, 0.0) << what;
  EXPECT_NEAR(best.cost(in.costs), before - gain, 1e-6) << what;
  EXPECT_LE(counts.kept, counts.cycles) << what;
  EXPECT_EQ(gain > 0.0, counts.kept > 0) << what;
  EXPECT_EQ(touched.empty(), counts.kept == 0) << what;
  all.cycles += counts.cycles;
  all.kept += counts.kept;
  all.joins += counts.joins;
}

// Two local optima of the same layer, from differently varied first tours, as a restart
// makes them; across the layouts cycles are kept, some only after their pieces were
// joined again.
TEST(TourMerge, AMergedTourIsOneTourCheaperByExactlyItsGain) {
  MergeCounts all;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const Instance in(testing::floor_plan_layer(40, seed));
    std::mt19937_64 rng(seed);
    const WallTour best = in.search(in.euler(), 20, seed, false).tour;
    const WallTour other = in.search(in.euler(&rng), 20, seed + 100, false).tour;
    check_merge(in, best, other, all, "seed " + std::to_string(seed));
  }
  EXPECT_GT(all.kept, 0);
  EXPECT_GT(all.joins, 0);
}

// A random tour merged with a good one: many cheaper cycles, each leaving pieces, and
// joins that take air moves of the cycles still to come; and the other way round.
TEST(TourMerge, ARandomTourTakesManyCyclesFromAGoodOne) {
  MergeCounts all;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Instance in(testing::floor_plan_layer(40, seed));
    const WallTour good = in.search(in.euler(), 200, seed, false).tour;
    const WallTour bad = random_tour(in.costs.item_count(), seed);
    check_merge(in, bad, good, all, "random into good, seed " + std::to_string(seed));
    check_merge(in, good, bad, all, "good into random, seed " + std::to_string(seed));
  }
  EXPECT_GT(all.kept, 4);
  EXPECT_GT(all.joins, 4);
}

TEST(TourMerge, ATourMergedWithItselfIsUnchanged) {
  const Instance in(testing::floor_plan_layer(10, 1));
  WallTour best = in.euler();
  const WallTour same = best;
  std::vector<int> touched;
  MergeCounts counts;
  EXPECT_EQ(merge_tours(in.costs, best, same, touched, &counts), 0.0);
  EXPECT_EQ(counts.cycles, 0);
  EXPECT_TRUE(touched.empty());
  for (int p = 0; p < best.size(); ++p) EXPECT_EQ(best.entry(p), same.entry(p));
}

// Tours one reversal apart differ in one alternating cycle of two air moves, which keeps
// the tour whole: the better tour's air moves are taken, with no join; the worse tour
// has nothing to give.
TEST(TourMerge, OfToursOneReversalApartTheBetterIsTaken) {
  const Instance in(testing::floor_plan_layer(10, 2));
  // A random tour: far from any local optimum, so improving reversals abound.
  const WallTour start = random_tour(in.costs.item_count(), 2);
  int found = 0;
  for (int first = 1; first < start.size() && found < 5; ++first) {
    for (int last = first + 1; last + 1 < start.size() && found < 5; last += 3) {
      WallTour better = start;
      better.reverse(first, last);
      const double saved = start.cost(in.costs) - better.cost(in.costs);
      if (saved < 1e-6) continue;
      ++found;
      WallTour merged = start;
      std::vector<int> touched;
      MergeCounts counts;
      EXPECT_NEAR(merge_tours(in.costs, merged, better, touched, &counts), saved, 1e-9);
      EXPECT_EQ(counts.kept, 1);
      EXPECT_EQ(counts.joins, 0);
      EXPECT_EQ(air_mates(merged), air_mates(better));
      WallTour worse = better;
      EXPECT_EQ(merge_tours(in.costs, worse, start, touched, &counts), 0.0);
      EXPECT_EQ(counts.cycles, 0);
      EXPECT_EQ(air_mates(worse), air_mates(better));
    }
  }
  EXPECT_EQ(found, 5) << "the Euler walk left no improving reversal; pick another layout";
}

// What the restarts are for: a search stuck in one basin, as on the bench's 1,000-wall
// plans. On this 386-wall plan the same kicks without restarts end 0.75% longer.
TEST(Restarts, FindWhatTheSameKicksWithoutThemDoNot) {
  const Instance in(testing::floor_plan_layer(80, 3));
  const SearchOutcome plain = in.search(in.euler(), 30000, 1, false);
  const SearchOutcome restarted = in.search(in.euler(), 30000, 1, true);
  EXPECT_EQ(plain.restarts, 0);
  EXPECT_GT(restarted.restarts, 0);
  EXPECT_GT(restarted.restart_gain, 0.0);
  EXPECT_EQ(restarted.kicks, 30000);
  ASSERT_TRUE(visits_every_item_once(restarted.tour));
  EXPECT_NEAR(restarted.cost, restarted.tour.cost(in.costs), 1e-9);
  EXPECT_LT(restarted.cost, plain.cost - 0.5);
}

// An open path's restarts keep its start: the free end's item, like every other, is
// in the merged tours once, and the path read from it covers every wall once.
TEST(Restarts, KeepAnOpenPathsStart) {
  const Instance in(testing::floor_plan_layer(40, 3), true);
  const SearchOutcome restarted = in.search(in.euler(), 12000, 1, true);
  EXPECT_GT(restarted.restarts, 0);
  ASSERT_TRUE(visits_every_item_once(restarted.tour));
  EXPECT_NEAR(restarted.cost, restarted.tour.cost(in.costs), 1e-9);
  const Sequence path = sequence_from_tour(in.costs, restarted.tour);
  std::vector<int> deposited(in.segments.size(), 0);
  for (const Step& step : path) ++deposited[step.segment];
  EXPECT_EQ(deposited, std::vector<int>(in.segments.size(), 1));
}

// A run with restarts stopped by its clock after K kicks is the run of max_kicks = K,
// restarts and merges included (docs/planning.md, the stopping rule). Here the search
// restarts after every kick that finds nothing, and a restart searches until its own
// 5,000 kicks without a better tour: the clock stops it inside a restart.
TEST(Restarts, ARunStoppedByTheClockIsReproducedByItsKicks) {
  const Instance in(testing::floor_plan_layer(40, 3));
  SearchSettings s;
  s.restart_stall_kicks = 1;
  s.restart_kicks = 1'000'000'000;
  s.restart_own_stall_kicks = 5000;
  const SearchOutcome timed = in.search(in.euler(), 1'000'000'000, 7, s, StopCondition(1.0));
  ASSERT_EQ(timed.reason, StopReason::kTimeLimit);
  ASSERT_GT(timed.restarts, 0) << "no restart within 1 s: give it more time";
  const SearchOutcome replay = in.search(in.euler(), timed.kicks, 7, s);
  EXPECT_EQ(replay.kicks, timed.kicks);
  EXPECT_EQ(replay.kicks_in_restarts, timed.kicks_in_restarts);
  EXPECT_EQ(replay.restarts, timed.restarts);
  EXPECT_EQ(air_mates(replay.tour), air_mates(timed.tour));
}

}  // namespace
}  // namespace ccbuild::planner::detail
