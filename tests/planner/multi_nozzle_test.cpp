// Multi-nozzle planning: each method where it must succeed and where it must fail, every
// returned plan re-checked exactly, the guarantee of auto, stages, bad parameters.

#include "ccbuild/planner/multi_nozzle.hpp"

#include <gtest/gtest.h>

#include "layouts.hpp"
#include "test_support.hpp"

namespace ccbuild::planner {
namespace {
using testing::contains;
using testing::expect_input_error;

// Two square rooms 20 m apart along x: nothing near the border between them.
floors::Layer two_far_rooms() {
  return testing::layer_from_walls({{0, 0, 4, 0},
                                    {4, 0, 4, 4},
                                    {4, 4, 0, 4},
                                    {0, 4, 0, 0},
                                    {24, 0, 28, 0},
                                    {28, 0, 28, 4},
                                    {28, 4, 24, 4},
                                    {24, 4, 24, 0}});
}

// A 4 m square room with a partition: too short along x for two gantries 3.5 m apart to
// both work in it at the same time.
floors::Layer narrow_room() {
  return testing::layer_from_walls(
      {{0, 0, 4, 0}, {4, 0, 4, 4}, {4, 4, 0, 4}, {0, 4, 0, 0}, {2, 0, 2, 4}});
}

MultiNozzleOptions options(MultiMethod method, double width, int nozzles = 2) {
  MultiNozzleOptions o;
  o.nozzles = nozzles;
  o.gantry_width_m = width;
  o.method = method;
  o.planning.max_kicks = 200;
  return o;
}

// Independent re-check of a returned plan: every adjacent pair exactly, every wall built.
void expect_sound(const floors::Layer& layer, const MultiNozzlePlan& plan,
                  const MultiNozzleOptions& o) {
  ASSERT_TRUE(plan.collision_free) << plan.failure;
  double built = 0.0;
  for (const auto& stage : plan.stages) {
    for (std::size_t k = 0; k + 1 < stage.nozzles.size(); ++k) {
      EXPECT_FALSE(first_conflict(stage.nozzles[k].timeline, stage.nozzles[k + 1].timeline,
                                  o.rail_axis, o.gantry_width_m))
          << "stage from " << stage.from_m << ", nozzles " << k + 1 << " and " << k + 2;
      EXPECT_GE(min_gap_m(stage.nozzles[k].timeline, stage.nozzles[k + 1].timeline, o.rail_axis),
                o.gantry_width_m - 1e-9);
    }
    for (const auto& n : stage.nozzles) {
      EXPECT_TRUE(covers_every_segment_once(n.sequence, n.layer.segments.size()));
      built += n.layer.total_length_m();
      EXPECT_GE(n.finish_s, n.busy_s - 1e-9);
    }
  }
  EXPECT_NEAR(built, layer.total_length_m(), 1e-6);
}

TEST(MultiNozzle, EveryMethodSucceedsWhereTheSectionsAreFarApart) {
  const auto layer = two_far_rooms();
  for (MultiMethod m : {MultiMethod::kPathCycling, MultiMethod::kGlobalPathCycling,
                        MultiMethod::kBufferZonePathCycling, MultiMethod::kAuxBufferZone,
                        MultiMethod::kDelay, MultiMethod::kAuto}) {
    const auto o = options(m, 1.0);
    const MultiNozzlePlan plan = plan_layer_multi(layer, machine::MachineModel::defaults(), o);
    SCOPED_TRACE(to_string(m));
    expect_sound(layer, plan, o);
    // Two equal rooms built at once: about half the single-nozzle time.
    EXPECT_LT(plan.layer_time_s, 0.75 * plan.single_nozzle_time_s);
  }
}

TEST(MultiNozzle, SectionMethodsFailWhenTheLayoutIsTooShortForTheGantries) {
  const auto layer = narrow_room();
  for (MultiMethod m : {MultiMethod::kPathCycling, MultiMethod::kGlobalPathCycling,
                        MultiMethod::kBufferZonePathCycling, MultiMethod::kAuxBufferZone}) {
    const MultiNozzlePlan plan =
        plan_layer_multi(layer, machine::MachineModel::defaults(), options(m, 3.5));
    EXPECT_FALSE(plan.collision_free) << to_string(m);
    ASSERT_EQ(plan.stages.size(), 1u);
    ASSERT_EQ(plan.stages[0].attempts.size(), 1u);
    EXPECT_TRUE(contains(plan.stages[0].attempts[0], to_string(m) + ": "))
        << plan.stages[0].attempts[0];
  }
}

TEST(MultiNozzle, DelaySucceedsWhereTheOthersFailAndAutoFallsBackToIt) {
  const auto layer = narrow_room();
  for (MultiMethod m : {MultiMethod::kDelay, MultiMethod::kAuto}) {
    const auto o = options(m, 3.5);
    const MultiNozzlePlan plan = plan_layer_multi(layer, machine::MachineModel::defaults(), o);
    SCOPED_TRACE(to_string(m));
    expect_sound(layer, plan, o);
    EXPECT_EQ(plan.stages[0].method, MultiMethod::kDelay);
  }
  const MultiNozzlePlan automatic =
      plan_layer_multi(layer, machine::MachineModel::defaults(), options(MultiMethod::kAuto, 3.5));
  EXPECT_EQ(automatic.stages[0].attempts.size(), 4u);  // the papers' three, then ours
}

TEST(MultiNozzle, DelayFailsWhenNoTurnsAndNoParkingArePossible) {
  auto machine = machine::MachineModel::defaults();
  machine.x = {0.0, 5.0, 0.5};  // rails barely longer than the room: nowhere to park
  const MultiNozzlePlan plan =
      plan_layer_multi(narrow_room(), machine, options(MultiMethod::kDelay, 3.5));
  EXPECT_FALSE(plan.collision_free);
  EXPECT_TRUE(contains(plan.stages[0].attempts[0], "no room to park"));
}

TEST(MultiNozzle, DelayWaitsWhenPathsWouldMeet) {
  // One wall on each side of x = 5, both deposited towards the border: each tour has a
  // single wall, so there is nothing to cycle and path cycling must fail; one nozzle
  // holding until the other has gone back is enough.
  const auto layer = testing::layer_from_walls({{0, 0, 4.9, 0}, {10, 1, 5.1, 1}});
  const MultiNozzlePlan cycling = plan_layer_multi(layer, machine::MachineModel::defaults(),
                                                   options(MultiMethod::kPathCycling, 2.0));
  EXPECT_FALSE(cycling.collision_free);
  const auto o = options(MultiMethod::kDelay, 2.0);
  const MultiNozzlePlan plan = plan_layer_multi(layer, machine::MachineModel::defaults(), o);
  expect_sound(layer, plan, o);
  double waited = 0.0;
  for (const auto& n : plan.stages[0].nozzles) waited += n.wait_s;
  EXPECT_GT(waited, 0.0);
  EXPECT_TRUE(contains(plan.stages[0].method_detail, "waits")) << plan.stages[0].method_detail;
  // Still faster than one nozzle doing both walls.
  EXPECT_LT(plan.layer_time_s, plan.single_nozzle_time_s);
}

TEST(MultiNozzle, EveryReturnedPlanPassesTheExactCheck) {
  int plans = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const floors::Layer layer = testing::floor_plan_layer(6 + 4 * static_cast<int>(seed), seed);
    for (int nozzles : {2, 3}) {
      for (double width : {0.8, 2.4}) {
        for (MultiMethod m : {MultiMethod::kPathCycling, MultiMethod::kGlobalPathCycling,
                              MultiMethod::kBufferZonePathCycling, MultiMethod::kAuxBufferZone,
                              MultiMethod::kDelay}) {
          auto o = options(m, width, nozzles);
          o.rail_axis = seed % 2 ? RailAxis::kX : RailAxis::kY;
          const MultiNozzlePlan plan =
              plan_layer_multi(layer, machine::MachineModel::defaults(), o);
          if (!plan.collision_free) continue;
          SCOPED_TRACE("seed " + std::to_string(seed) + " " + to_string(m) + " nozzles " +
                       std::to_string(nozzles));
          expect_sound(layer, plan, o);
          ++plans;
        }
      }
    }
  }
  EXPECT_GT(plans, 40);  // most combinations do produce a plan to check
}

TEST(MultiNozzle, AutoAlwaysFindsAPlanWhenTheRailsLeaveRoom) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const floors::Layer layer =
        testing::floor_plan_layer(4 + 4 * static_cast<int>(seed), seed + 100);
    for (double width : {1.0, 2.5, 4.0}) {
      auto o = options(MultiMethod::kAuto, width, 2 + static_cast<int>(seed % 2));
      const MultiNozzlePlan plan = plan_layer_multi(layer, machine::MachineModel::defaults(), o);
      SCOPED_TRACE("seed " + std::to_string(seed) + " width " + std::to_string(width));
      expect_sound(layer, plan, o);
    }
  }
}

TEST(MultiNozzle, PlatformBuildsLongLayoutsInStages) {
  const floors::Layer layer = testing::floor_plan_layer(40, 3);
  auto o = options(MultiMethod::kAuto, 1.0);
  double length = 0.0;
  for (const auto& p : layer.points) length = std::max(length, p.x());
  o.platform_width_m = 0.4 * length;
  const MultiNozzlePlan plan = plan_layer_multi(layer, machine::MachineModel::defaults(), o);
  expect_sound(layer, plan, o);
  EXPECT_EQ(plan.stages.size(), 3u);
  EXPECT_GT(plan.platform_travel_s, 0.0);
  for (const auto& stage : plan.stages) {
    EXPECT_LE(stage.to_m - stage.from_m, *o.platform_width_m + 1e-9);
    for (const auto& n : stage.nozzles)
      for (const auto& p : n.layer.points) {
        EXPECT_GE(p.x(), stage.from_m - 1e-6);
        EXPECT_LE(p.x(), stage.to_m + 1e-6);
      }
  }
}

TEST(MultiNozzle, ImpossibleParametersAreInputErrors) {
  const auto layer = two_far_rooms();
  const auto machine = machine::MachineModel::defaults();
  auto o = options(MultiMethod::kAuto, 1.0);
  o.nozzles = 1;
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "at least 2"));
  o = options(MultiMethod::kAuto, 0.0);
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "must be positive"));
  o = options(MultiMethod::kAuto, -2.0);
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "must be positive"));
  o = options(MultiMethod::kAuto, 10.0, 6);  // 5 x 10 m of spacing on 50 m of rails
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "do not fit"));
  o = options(MultiMethod::kAuto, 2.0, 3);
  o.platform_width_m = 3.0;
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "platform"));
  o.platform_width_m = -1.0;
  EXPECT_TRUE(contains(expect_input_error([&] { plan_layer_multi(layer, machine, o); }).what(),
                       "must be positive"));
}

}  // namespace
}  // namespace ccbuild::planner
