// plan_layer end to end: the reference examples, coverage, determinism, option errors.

#include "ccbuild/planner/plan_layer.hpp"

#include <gtest/gtest.h>

#include <utility>

#include "ccbuild/floors/plan.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "layouts.hpp"
#include "test_support.hpp"

namespace ccbuild::planner {
namespace {
using testing::contains;
using testing::expect_input_error;

LayerPlan plan_example(const std::string& file, Metric metric, Algorithm algorithm) {
  const floors::FloorPlan plan = floors::load_plan(testing::data("plans/" + file));
  static floors::Layer layer;
  layer = floors::plan_as_layer(plan);
  PlanOptions o;
  o.metric = metric;
  o.algorithm = algorithm;
  o.path =
      PathSpec::open_from(plan.find_vertex(1)->position_m, Step{0, false});  // wall 1 first, 1 -> 2
  return plan_layer(layer, testing::simple_machine(), o);
}

TEST(PlanLayer, ReferenceExamplesReachTheirOptimum) {
  for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear}) {
    for (Algorithm algorithm : {Algorithm::kCcTsp, Algorithm::kExact}) {
      const LayerPlan one = plan_example("paper_example1.txt", metric, algorithm);
      EXPECT_NEAR(one.evaluation.airtime_distance_m, 25.0, 1e-9)
          << to_string(metric) << " " << to_string(algorithm);
      EXPECT_EQ(one.sequence.front(), (Step{0, false}));
      const LayerPlan two = plan_example("paper_example2.txt", metric, algorithm);
      EXPECT_NEAR(two.evaluation.airtime_distance_m, 35.0, 1e-9)
          << to_string(metric) << " " << to_string(algorithm);
    }
  }
}

TEST(PlanLayer, BaselinesOnTheReferenceExample) {
  // File order: 1, 2, 3, ... each forwards: 5 + 30.414 + ... (hand: moves between ends).
  const LayerPlan original =
      plan_example("paper_example1.txt", Metric::kEuclidean, Algorithm::kOriginal);
  for (std::size_t i = 0; i < original.sequence.size(); ++i)
    EXPECT_EQ(original.sequence[i], (Step{int(i), false}));
  const double expected = 5.0 + std::hypot(35 - 15, 0 - 30) + std::hypot(35 - 0, 30 - 50) +
                          std::hypot(35 - 0, 50 - 0) + std::hypot(0 - 35, 50 - 0) + 0.0;
  EXPECT_NEAR(original.evaluation.airtime_distance_m, expected, 1e-9);
  const LayerPlan nearest =
      plan_example("paper_example1.txt", Metric::kEuclidean, Algorithm::kNearest);
  EXPECT_GE(nearest.evaluation.airtime_distance_m, 25.0 - 1e-9);
}

TEST(PlanLayer, EveryAlgorithmDepositsEveryWallExactlyOnce) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const floors::Layer layer = testing::floor_plan_layer(6 + 3 * static_cast<int>(seed), seed);
    for (Algorithm algorithm : {Algorithm::kCcTsp, Algorithm::kNearest, Algorithm::kOriginal}) {
      for (bool closed : {true, false}) {
        PlanOptions o;
        o.algorithm = algorithm;
        o.objective = seed % 2 ? Objective::kTime : Objective::kDistance;
        if (!closed) o.path = PathSpec::open_from(layer.points[layer.segments[3].end_point]);
        const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
        EXPECT_TRUE(covers_every_segment_once(plan.sequence, layer.segments.size()));
        EXPECT_EQ(plan.evaluation.moves.size(), layer.segments.size());
        EXPECT_GE(plan.evaluation.airtime_distance_m, plan.lower_bound_m - 1e-9);
      }
    }
  }
}

TEST(PlanLayer, CcTspBeatsBothBaselinesOnFloorPlans) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const floors::Layer layer = testing::floor_plan_layer(20, seed);
    auto airtime = [&](Algorithm a) {
      PlanOptions o;
      o.algorithm = a;
      return plan_layer(layer, testing::simple_machine(), o).evaluation.airtime_distance_m;
    };
    const double cc = airtime(Algorithm::kCcTsp);
    EXPECT_LT(cc, airtime(Algorithm::kNearest));
    EXPECT_LT(cc, airtime(Algorithm::kOriginal));
  }
}

TEST(PlanLayer, SameSeedSamePlan) {
  const floors::Layer layer = testing::floor_plan_layer(40, 7);
  PlanOptions o;
  o.objective = Objective::kTime;
  o.seed = 42;
  const LayerPlan a = plan_layer(layer, testing::simple_machine(), o);
  const LayerPlan b = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_EQ(a.sequence, b.sequence);
  EXPECT_EQ(a.evaluation.airtime_s, b.evaluation.airtime_s);
}

// Past 200 walls the time objective still gets the exact-time polish (its descent): it
// takes lifts and detours out that the search's symmetric costs cannot see.
TEST(PlanLayer, LargeLayersGetTheExactTimePolish) {
  const floors::Layer layer = testing::floor_plan_layer(70, 5);
  ASSERT_GT(layer.segments.size(), 200u);
  PlanOptions o;
  o.objective = Objective::kTime;
  const LayerPlan polished = plan_layer(layer, testing::simple_machine(), o);
  o.exact_polish = false;
  const LayerPlan searched = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_TRUE(covers_every_segment_once(polished.sequence, layer.segments.size()));
  EXPECT_LT(polished.evaluation.airtime_s, searched.evaluation.airtime_s - 1.0);
  EXPECT_LE(polished.evaluation.lift_count, searched.evaluation.lift_count);
}

TEST(PlanLayer, FirstWallFixesTheStartInEitherDirection) {
  const floors::Layer layer = testing::floor_plan_layer(10, 3);
  PlanOptions o;
  o.path = PathSpec::open_from(layer.points[0], Step{4, true});
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_EQ(plan.sequence.front(), (Step{4, true}));
  EXPECT_TRUE(covers_every_segment_once(plan.sequence, layer.segments.size()));
}

TEST(PlanLayer, OptionsThatDoNotFitAreInputErrors) {
  const floors::Layer big = testing::floor_plan_layer(20, 1);
  PlanOptions exact;
  exact.algorithm = Algorithm::kExact;
  EXPECT_TRUE(contains(
      expect_input_error([&] { plan_layer(big, testing::simple_machine(), exact); }).what(),
      "exact handles layers of at most"));
  PlanOptions closed_first;
  closed_first.path.first = Step{0, false};
  EXPECT_TRUE(contains(
      expect_input_error([&] { plan_layer(big, testing::simple_machine(), closed_first); }).what(),
      "needs an open path"));
  PlanOptions off_layer;
  off_layer.path = PathSpec::open_from({0, 0}, Step{100000, false});
  EXPECT_TRUE(contains(
      expect_input_error([&] { plan_layer(big, testing::simple_machine(), off_layer); }).what(),
      "not a wall of this layer"));
  floors::Layer empty;
  EXPECT_TRUE(
      contains(expect_input_error([&] { plan_layer(empty, testing::simple_machine(), {}); }).what(),
               "no walls"));
}

TEST(PlanLayer, TimeLimitBoundsTheRun) {
  const floors::Layer layer = testing::floor_plan_layer(300, 5);
  PlanOptions o;
  o.time_limit_s = 0.2;
  o.max_kicks = 100000000;
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_TRUE(covers_every_segment_once(plan.sequence, layer.segments.size()));
  EXPECT_EQ(plan.stop, StopReason::kTimeLimit);
  EXPECT_LT(plan.solve_s, 1.0);  // generous: only catches a limit that is ignored
}

// The stopping rule (docs/planning.md): an anytime run stopped by its time limit after K
// kicks is the run of max_kicks = K, so any answer can be reproduced exactly.
TEST(PlanLayer, AnAnytimeRunIsReproducedByItsKicks) {
  // Its first descent takes ~0.05 s, far inside the limit even on a busy machine.
  const floors::Layer layer = testing::floor_plan_layer(150, 5);
  PlanOptions o;
  o.time_limit_s = 1.5;
  o.anytime = true;
  o.waypoints = false;
  const LayerPlan anytime = plan_layer(layer, testing::simple_machine(), o);
  ASSERT_EQ(anytime.stop, StopReason::kTimeLimit);  // it used the whole time
  ASSERT_GT(anytime.kicks, 0);
  PlanOptions replay = o;
  replay.anytime = false;
  replay.time_limit_s = 60.0;
  replay.max_kicks = anytime.kicks;
  const LayerPlan again = plan_layer(layer, testing::simple_machine(), replay);
  EXPECT_EQ(again.kicks, anytime.kicks);
  EXPECT_EQ(again.stop, StopReason::kConverged);
  EXPECT_EQ(again.sequence, anytime.sequence);
  // One kick fewer is another run: its kicks are its own.
  replay.max_kicks = anytime.kicks - 1;
  EXPECT_EQ(plan_layer(layer, testing::simple_machine(), replay).kicks, anytime.kicks - 1);
}

// A kick budget (like a time limit) has no stall rule, so a stalled search restarts from
// varied Euler walks and merges what is better there (docs/planning.md): on this
// 386-wall plan 30,000 kicks end 0.75% shorter than the same kicks without restarts,
// where the default budget stops in the first basin.
TEST(PlanLayer, AKickBudgetRestartsWhereTheSearchStalls) {
  const floors::Layer layer = testing::floor_plan_layer(80, 3);
  PlanOptions o;
  o.waypoints = false;
  o.bound = BoundKind::kMatching;
  const LayerPlan by_default = plan_layer(layer, testing::simple_machine(), o);
  ASSERT_EQ(by_default.stop, StopReason::kConverged);
  o.max_kicks = 30000;
  const LayerPlan budget = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_TRUE(covers_every_segment_once(budget.sequence, layer.segments.size()));
  EXPECT_EQ(budget.kicks, 30000);
  EXPECT_LT(budget.evaluation.airtime_distance_m, by_default.evaluation.airtime_distance_m - 1.0);
}

TEST(PlanLayer, TheDefaultBudgetEndsOnItsOwn) {
  const floors::Layer layer = testing::floor_plan_layer(60, 2);
  PlanOptions o;
  o.waypoints = false;
  std::vector<SearchProgress> progress;
  o.on_progress = [&](const SearchProgress& p) { progress.push_back(p); };
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  ASSERT_EQ(plan.stop, StopReason::kConverged) << "the bound proved it; pick another layout";
  ASSERT_FALSE(progress.empty());
  // It ended at least 1,000 + 20 per wall kicks after its last better tour (fewer than
  // 10,000; kicks that find no valid cut do not count as failures), and within its
  // budget; the last progress reported is the tour's cost.
  const long items = static_cast<long>(layer.segments.size());
  EXPECT_GE(plan.kicks, progress.back().kicks + 1000 + 20 * items);
  EXPECT_LT(plan.kicks, 2000 + 60 * items);
  EXPECT_NEAR(progress.back().cost, plan.evaluation.airtime_distance_m, 1e-6);
  for (std::size_t k = 1; k < progress.size(); ++k) {
    EXPECT_LT(progress[k].cost, progress[k - 1].cost);
    EXPECT_GT(progress[k].kicks, progress[k - 1].kicks);
  }
}

TEST(PlanLayer, ATourAtTheBoundWithinItsRoundingIsProvenOptimal) {
  // Each bound sits a little below its exact value by construction (LayerBound::
  // rounding_m); a tour that reaches the exact value is optimal and the search stops at
  // once. Before, these searched on to their stall budget, "converged".
  struct Case {
    int rooms;
    std::uint64_t seed;
    BoundKind kind;
  };
  for (const Case& c : {Case{8, 1, BoundKind::kConnected}, Case{4, 2, BoundKind::kMatching}}) {
    const floors::Layer layer = testing::floor_plan_layer(c.rooms, c.seed);
    const LayerBound bound = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec{}, c.kind);
    PlanOptions o;
    o.waypoints = false;
    o.bound = c.kind;
    const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
    const std::string what = to_string(c.kind);
    EXPECT_EQ(plan.stop, StopReason::kProvenOptimal) << what;
    EXPECT_EQ(plan.kicks, 0) << what << ": proven by the first descent's tour";
    // Above the certified number by more than the old 1e-9 m, within the rounding.
    const double above_m = plan.evaluation.airtime_distance_m - bound.distance_m;
    EXPECT_GT(above_m, 1e-8) << what;
    EXPECT_LE(above_m, bound.rounding_m) << what;
  }
  // The rounding is what each construction says, and no more.
  const floors::Layer layer = testing::floor_plan_layer(4, 2);
  const LayerBound matching =
      airtime_lower_bound(layer, Metric::kEuclidean, PathSpec{}, BoundKind::kMatching);
  EXPECT_DOUBLE_EQ(matching.rounding_m, 1e-5 * static_cast<double>(matching.matching.pairs.size()));
  // An open path's free end matches one terminal at no cost: nothing rounded there.
  const LayerBound open = airtime_lower_bound(
      layer, Metric::kEuclidean, PathSpec::open_from({-1.0, -1.0}), BoundKind::kMatching);
  EXPECT_DOUBLE_EQ(open.rounding_m, 1e-5 * static_cast<double>(open.matching.pairs.size() - 1));
  const LayerBound connected = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec{});
  ASSERT_EQ(connected.source(), BoundSource::kConnected);
  EXPECT_DOUBLE_EQ(connected.rounding_m, 2e-9 * (1.0 + connected.distance_m));
  // A real gap is no proof: 0.025 m between this tour and the connected bound.
  PlanOptions o;
  o.waypoints = false;
  const LayerPlan gap = plan_layer(testing::floor_plan_layer(12, 12), testing::simple_machine(), o);
  EXPECT_EQ(gap.stop, StopReason::kConverged);
  EXPECT_GT(gap.evaluation.airtime_distance_m - gap.lower_bound_m, 0.01);
}

// The layer planned under the time objective with `o`, then again as an anytime run.
std::pair<LayerPlan, LayerPlan> time_plans_without_and_with_anytime(const floors::Layer& layer,
                                                                    PlanOptions o) {
  o.waypoints = false;
  o.objective = Objective::kTime;
  LayerPlan plain = plan_layer(layer, testing::simple_machine(), o);
  o.anytime = true;
  return {std::move(plain), plan_layer(layer, testing::simple_machine(), o)};
}

TEST(PlanLayer, ExactWithATimeLimitStillProvesItsAnswer) {
  // An anytime request (plan-layer --algorithm exact --time-limit T) once let the
  // heuristic warm start search for all T seconds, so the exact search never ran and
  // the answer was "time-limit". The warm start keeps its budget; the exact search
  // proves the same answer as without the limit.
  PlanOptions o;
  o.algorithm = Algorithm::kExact;
  o.time_limit_s = 3.0;
  const auto [plain, anytime] = time_plans_without_and_with_anytime(testing::random_layer(8, 3), o);
  EXPECT_EQ(plain.stop, StopReason::kProvenOptimal);
  EXPECT_EQ(anytime.stop, StopReason::kProvenOptimal);
  EXPECT_EQ(anytime.sequence, plain.sequence);
  EXPECT_EQ(anytime.kicks, plain.kicks);
  // The warm start's polish is reported as the search's kicks are.
  EXPECT_EQ(plain.polish_kicks, 500);
  EXPECT_EQ(anytime.polish_kicks, plain.polish_kicks);
}

TEST(PlanLayer, AnAnytimeRunUnderTheTimeObjectiveSpendsItsTimeOnThePolish) {
  // The symmetric search keeps its default budget (its costs only approximate the
  // airtime); the exact-time polish then kicks until the limit. Before, the symmetric
  // search took all the time and the polish never ran: 221.4 s of airtime here against
  // 171.9 s on the default budget (now 161.6 s after 1.5 s on the 2-core machine).
  PlanOptions o;
  o.time_limit_s = 1.5;
  const auto [budget, anytime] =
      time_plans_without_and_with_anytime(testing::floor_plan_layer(20, 3), o);
  EXPECT_EQ(budget.stop, StopReason::kConverged);
  EXPECT_EQ(anytime.stop, StopReason::kTimeLimit);
  EXPECT_EQ(anytime.kicks, budget.kicks);
  EXPECT_LE(anytime.evaluation.airtime_s, budget.evaluation.airtime_s + 1e-9);
}

// Options of the polish tests: the time objective, no waypoints, and the matching bound
// (the bound plays no part in them).
PlanOptions time_objective_options() {
  PlanOptions o;
  o.waypoints = false;
  o.objective = Objective::kTime;
  o.bound = BoundKind::kMatching;
  return o;
}

TEST(PlanLayer, AnAnytimeRunOnALargeLayerKicksLocallyInThePolish) {
  // Past 200 walls the default polish is a descent without kicks; given time, its kicks
  // are followed by a descent around them only. Bounded by polish_kicks the run is
  // deterministic, and its 100 kicks find a faster tour than the descent alone (348.9
  // against 355.2 s of airtime on these 225 walls).
  const floors::Layer layer = testing::floor_plan_layer(45, 2);
  ASSERT_GT(layer.segments.size(), 200u);
  PlanOptions o = time_objective_options();
  const LayerPlan descent = plan_layer(layer, testing::simple_machine(), o);
  o.anytime = true;
  o.time_limit_s = 60.0;  // far beyond the 100 kicks: they end the run
  o.polish_kicks = 100;
  const LayerPlan kicked = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_EQ(kicked.stop, StopReason::kConverged);
  EXPECT_EQ(kicked.kicks, descent.kicks);
  EXPECT_LT(kicked.evaluation.airtime_s, descent.evaluation.airtime_s - 1.0);
  EXPECT_EQ(plan_layer(layer, testing::simple_machine(), o).sequence, kicked.sequence);
}

// Under the time objective an anytime run's extra time goes to the exact-time polish.
// The search's kicks and the polish's, given back with `anytime`, replay it without the
// clock (docs/planning.md): a polish kick the clock cuts off is dropped, not counted.
// Both kinds of polish kick: a whole window pass (103 walls) and a descent around the
// kick (225 walls).
TEST(PlanLayer, AnAnytimeRunUnderTheTimeObjectiveIsReproducedByItsKicks) {
  for (const auto& [rooms, seed] : {std::pair{20, 3}, std::pair{45, 2}}) {
    const floors::Layer layer = testing::floor_plan_layer(rooms, seed);
    const std::string what = std::to_string(layer.segments.size()) + " walls";
    PlanOptions o = time_objective_options();
    o.anytime = true;
    o.time_limit_s = 1.0;
    const LayerPlan anytime = plan_layer(layer, testing::simple_machine(), o);
    ASSERT_EQ(anytime.stop, StopReason::kTimeLimit) << what;
    ASSERT_TRUE(anytime.polish_kicks.has_value()) << what;
    ASSERT_GT(*anytime.polish_kicks, 0) << what;
    PlanOptions replay = o;
    replay.time_limit_s = 60.0;
    replay.max_kicks = anytime.kicks;
    replay.polish_kicks = anytime.polish_kicks;
    const LayerPlan again = plan_layer(layer, testing::simple_machine(), replay);
    EXPECT_EQ(again.stop, StopReason::kConverged) << what;
    EXPECT_EQ(again.kicks, anytime.kicks) << what;
    EXPECT_EQ(again.polish_kicks, anytime.polish_kicks) << what;
    EXPECT_EQ(again.sequence, anytime.sequence) << what;
    EXPECT_NEAR(again.evaluation.airtime_s, anytime.evaluation.airtime_s, 1e-9) << what;
  }
}

// polish_kicks counts the kicks after the polish's descent: 0 is the descent alone (the
// default past 200 walls), not the absence of a polish, which is exact_polish = false.
TEST(PlanLayer, NoPolishKicksIsTheDescentAlone) {
  const floors::Layer layer = testing::floor_plan_layer(20, 3);
  PlanOptions o = time_objective_options();
  const LayerPlan kicked = plan_layer(layer, testing::simple_machine(), o);
  // The default up to 200 walls is 20 kicks, fewer when its step budget runs out first.
  ASSERT_TRUE(kicked.polish_kicks.has_value());
  EXPECT_GT(*kicked.polish_kicks, 0);
  EXPECT_LE(*kicked.polish_kicks, 20);
  o.polish_kicks = 0;
  const LayerPlan descent = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_EQ(descent.polish_kicks, 0);
  o.exact_polish = false;
  const LayerPlan searched = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_FALSE(searched.polish_kicks.has_value());
  EXPECT_EQ(searched.kicks, descent.kicks);  // the same search before the polish
  EXPECT_LT(descent.evaluation.airtime_s, searched.evaluation.airtime_s - 1.0);
  EXPECT_LE(kicked.evaluation.airtime_s, descent.evaluation.airtime_s);
  // The distance objective has no polish.
  o = PlanOptions{};
  o.waypoints = false;
  EXPECT_FALSE(plan_layer(layer, testing::simple_machine(), o).polish_kicks.has_value());
}

TEST(PlanLayer, AShortTimeLimitStillLeavesThePolishTime) {
  // Under the time objective the search gets at most half of the limit, so the polish
  // that removes lifts always runs; before, a search cut short by the limit skipped it.
  // Kicks far beyond what the limit allows make the search as long as it may be (103
  // walls: 0 lifts left against 13 unpolished, 175.3 against 206.1 s of airtime).
  const floors::Layer layer = testing::floor_plan_layer(20, 3);
  PlanOptions o = time_objective_options();
  o.time_limit_s = 0.6;
  o.max_kicks = 1'000'000'000;
  const LayerPlan polished = plan_layer(layer, testing::simple_machine(), o);
  o.exact_polish = false;  // the search has the whole limit
  const LayerPlan searched = plan_layer(layer, testing::simple_machine(), o);
  EXPECT_EQ(polished.stop, StopReason::kTimeLimit);
  EXPECT_EQ(searched.stop, StopReason::kTimeLimit);
  EXPECT_LT(polished.kicks, searched.kicks);  // about half as many
  EXPECT_LT(polished.evaluation.lift_count, searched.evaluation.lift_count / 2);
  EXPECT_LT(polished.evaluation.airtime_s, searched.evaluation.airtime_s);
}

TEST(PlanLayer, NeighbourhoodNames) {
  EXPECT_EQ(parse_neighbourhood("lk"), Neighbourhood::kLinKernighan);
  EXPECT_EQ(parse_neighbourhood("2opt-oropt"), Neighbourhood::kTwoOptOrOpt);
  EXPECT_EQ(parse_neighbourhood("3opt"), std::nullopt);
  for (Neighbourhood n : {Neighbourhood::kLinKernighan, Neighbourhood::kTwoOptOrOpt})
    EXPECT_EQ(parse_neighbourhood(to_string(n)), n);
}

}  // namespace
}  // namespace ccbuild::planner

namespace ccbuild::planner {
namespace {

// Walls thicker than one bead (the masonry house: 0.45 m and 0.30 m walls, T junctions,
// a door) sliced into beads for a 0.15 m nozzle: every pattern's beads are each
// deposited once, and a tour through rings of skins is no longer than the beads' own
// length by more than the moves between rings.
TEST(PlanLayer, EveryBeadOfAThickWallIsDepositedOnce) {
  floors::FloorPlan plan = floors::load_plan(testing::data("buildings/plans/masonry.yaml"));
  for (auto pattern : {floors::WallPattern::kSkins, floors::WallPattern::kSolid,
                       floors::WallPattern::kSkinsWithTies}) {
    plan.beads = {0.15, pattern};
    const floors::Layer layer = floors::slice_plan_at(plan, 0.5, 1.0);  // the door is open
    ASSERT_GT(layer.segments.size(), plan.walls.size());
    const LayerPlan p = plan_layer(layer, testing::simple_machine(), PlanOptions{});
    EXPECT_TRUE(covers_every_segment_once(p.sequence, layer.segments.size()))
        << floors::wall_pattern_name(pattern);
    EXPECT_NEAR(p.evaluation.deposition_s * testing::simple_machine().deposition_speed_m_s,
                layer.total_length_m(), 1e-6);
  }
}

}  // namespace
}  // namespace ccbuild::planner
