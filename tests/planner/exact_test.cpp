// The exact solver as a referee: the heuristic must match it on small layouts, for both
// metrics and both objectives, and the lower bound must never exceed it.

#include <gtest/gtest.h>

#include "ccbuild/planner/plan_layer.hpp"
#include "layouts.hpp"

namespace ccbuild::planner {
namespace {

struct Case {
  std::string name;
  floors::Layer layer;
};

std::vector<Case> small_layouts() {
  std::vector<Case> cases;
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    cases.push_back({"random" + std::to_string(seed),
                     testing::random_layer(6 + 2 * static_cast<int>(seed % 4), seed)});
  for (std::uint64_t seed = 1; seed <= 40 && cases.size() < 8; ++seed) {
    floors::Layer layer = testing::floor_plan_layer(2 + static_cast<int>(seed % 2), seed);
    if (layer.segments.size() >= 6 && layer.segments.size() <= 12)
      cases.push_back({"plan" + std::to_string(seed), std::move(layer)});
  }
  return cases;
}

double objective_value(const LayerPlan& p) {
  return p.objective == Objective::kDistance ? p.evaluation.airtime_distance_m
                                             : p.evaluation.airtime_s;
}

class HeuristicVersusExact : public ::testing::TestWithParam<std::tuple<Metric, Objective, bool>> {
};

TEST_P(HeuristicVersusExact, SameOptimumOnSmallLayouts) {
  const auto [metric, objective, closed] = GetParam();
  for (const Case& c : small_layouts()) {
    ASSERT_LE(c.layer.segments.size(), 12u);
    PlanOptions o;
    o.metric = metric;
    o.objective = objective;
    if (!closed) o.path = PathSpec::open_from(c.layer.points[0]);
    o.algorithm = Algorithm::kExact;
    const LayerPlan exact = plan_layer(c.layer, testing::simple_machine(), o);
    ASSERT_EQ(exact.stop, StopReason::kProvenOptimal);
    o.algorithm = Algorithm::kCcTsp;
    const LayerPlan heuristic = plan_layer(c.layer, testing::simple_machine(), o);
    EXPECT_NEAR(objective_value(heuristic), objective_value(exact), 1e-6)
        << c.name << " (" << c.layer.segments.size() << " walls)";
    EXPECT_LE(exact.lower_bound_m, exact.evaluation.airtime_distance_m + 1e-9) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllVariants, HeuristicVersusExact,
    ::testing::Combine(::testing::Values(Metric::kEuclidean, Metric::kRectilinear),
                       ::testing::Values(Objective::kDistance, Objective::kTime),
                       ::testing::Values(true, false)),
    [](const auto& info) {
      return to_string(std::get<0>(info.param)) + "_" + to_string(std::get<1>(info.param)) +
             (std::get<2>(info.param) ? "_closed" : "_open");
    });

TEST(Exact, AgreesWithItsOwnEvaluation) {
  // The DP's internal arithmetic and CostModel::evaluate must agree: a plan the DP calls
  // optimal cannot be beaten by any rotation of itself (closed) under evaluate().
  const floors::Layer layer = testing::random_layer(8, 11);
  PlanOptions o;
  o.algorithm = Algorithm::kExact;
  o.objective = Objective::kTime;
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  const CostModel model(layer, testing::simple_machine(), Metric::kEuclidean);
  for (std::size_t r = 0; r < plan.sequence.size(); ++r) {
    Sequence rotated(plan.sequence.begin() + r, plan.sequence.end());
    rotated.insert(rotated.end(), plan.sequence.begin(), plan.sequence.begin() + r);
    EXPECT_GE(model.evaluate(rotated, PathSpec::closed_tour()).airtime_s,
              plan.evaluation.airtime_s - 1e-9);
  }
}

}  // namespace
}  // namespace ccbuild::planner
