// The dispatch library on one site clock, in one process over memq:// (the integration
// tests run real processes over udpm://): two simulated machines on the site clock, the
// dispatcher and the rail guard stepped together, at 1x and at 10,000x. A stalled rail
// axis and a parked gantry in the way are paused before the gantries touch (and touch
// without the guard); lost, repeated and reordered messages cost no job twice.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ccbuild/dispatch/dispatcher.hpp"
#include "ccbuild/dispatch/site_run.hpp"
#include "ccbuild/machine/bus.hpp"
#include "ccbuild/machine/sim_machine.hpp"

namespace ccbuild::dispatch {
namespace {

constexpr double kWidth_m = 1.5;

/// A deposit job along x at y = 1 m: through (t_s, x_m) waypoints.
DispatchJob along_x(const std::string& machine, std::int64_t id,
                    const std::vector<std::pair<double, double>>& points) {
  DispatchJob d;
  d.machine_id = machine;
  d.job_id = id;
  d.kind = JobKind::kDeposit;
  d.floor = 0;
  d.layer = 0;
  d.nozzle = machine == "gantry-1" ? 0 : 1;
  d.plan = "g1n2";
  d.detail = machine + " along x";
  for (std::size_t k = 0; k < points.size(); ++k)
    d.path.push_back(points[k].first, points[k].second, 1.0, 0.1, 0.0, k + 1 < points.size(),
                     static_cast<std::int64_t>(id), 1);
  d.duration_s = d.path.t_s.back();
  return d;
}

/// Two machines on the site clock, gantry-1 and gantry-2, each parked at `homes`, the jobs
/// sent by a dispatcher, the clock moved on by a SiteRun at `speed`; stepped a simulated
/// millisecond of real time at a time.
struct TwoGantries {
  TwoGantries(double speed, std::vector<DispatchJob> jobs, std::array<double, 2> homes_m,
              double stall_at_s, bool guard, double drop = 0.0)
      : bus("memq://"), journal(":memory:") {
    for (int k = 0; k < 2; ++k) {
      machine::SimOptions so;
      so.machine_id = "gantry-" + std::to_string(k + 1);
      so.site_clock = true;
      so.home = {homes_m[k], 1.0, 0.1, 0.0};
      so.drop = so.duplicate = so.reorder = drop;
      so.seed = 7 + k;
      if (k == 0) so.stall_at_s = stall_at_s;
      sims.push_back(std::make_unique<machine::SimMachine>(bus, so));
    }
    DispatchOptions o;
    o.speed = speed;
    dispatcher = std::make_unique<Dispatcher>(bus, std::move(jobs), journal, o);
    SiteRunOptions ro;
    ro.speed = speed;
    ro.guard = guard;
    run.emplace(bus, *dispatcher, std::vector<std::string>{"gantry-1", "gantry-2"},
                machine::RailAxis::kX, kWidth_m, ro);
  }
  /// Steps until done, or `real_s` of (simulated) real time.
  void go(double real_s) {
    const double dt_s = 1e-3;
    for (double t = 0.0; t < real_s && !dispatcher->finished(); t += dt_s) {
      dispatcher->step(dt_s);
      if (auto why = run->step(dt_s)) stops.push_back(*why);
      bus.handle(0);
      for (auto& s : sims) s->step(dt_s);
      bus.handle(0);
    }
  }
  double gap_m() const { return sims[1]->position()[0] - sims[0]->position()[0]; }

  machine::Bus bus;
  Journal journal;
  std::vector<std::unique_ptr<machine::SimMachine>> sims;
  std::unique_ptr<Dispatcher> dispatcher;
  std::optional<SiteRun> run;
  std::vector<std::string> stops;
};

/// gantry-1 goes out to x = 6 m and back to 2.5 m; gantry-2 comes in from 12 m to 6.5 m:
/// never closer than 3.8 m as planned (at t = 8 s), but gantry-1's rail stalls there at 6 m.
std::vector<DispatchJob> crossing_paths() {
  return {along_x("gantry-1", 10, {{0.0, 2.0}, {8.0, 6.0}, {15.0, 2.5}}),
          along_x("gantry-2", 20, {{0.0, 12.0}, {20.0, 6.5}})};
}

class AtEverySpeed : public ::testing::TestWithParam<double> {};

TEST_P(AtEverySpeed, AStalledAxisIsPausedBeforeTheGantriesTouch) {
  TwoGantries site(GetParam(), crossing_paths(), {2.0, 12.0}, 8.0, /*guard=*/true);
  site.go(120.0);
  ASSERT_TRUE(site.dispatcher->stopped());
  EXPECT_EQ(site.dispatcher->stopped()->rfind("site watchdog", 0), 0u)
      << *site.dispatcher->stopped();
  EXPECT_FALSE(site.run->collided());
  // Paused before contact, and no more than two status periods of closing before it.
  EXPECT_GE(site.gap_m(), kWidth_m - 1e-9);
  EXPECT_LT(site.gap_m(), kWidth_m + 0.05);
  EXPECT_GE(site.run->guard().smallest_gap_m(), kWidth_m - 1e-9);
  EXPECT_NEAR(site.sims[0]->position()[0], 6.0, 1e-9) << "gantry-1 stalled at 6 m";
  // Every tick was measured once, at one instant for both.
  EXPECT_GT(site.run->guard().gaps_measured(), 1);
}

TEST_P(AtEverySpeed, WithoutTheGuardTheStalledGantryIsHit) {
  TwoGantries site(GetParam(), crossing_paths(), {2.0, 12.0}, 8.0, /*guard=*/false);
  site.go(120.0);
  EXPECT_TRUE(site.run->collided());
  EXPECT_LT(site.run->guard().smallest_gap_m(), kWidth_m);
}

TEST_P(AtEverySpeed, AGantryClosingOnAParkedOneIsPausedBeforeContact) {
  // gantry-2 has no jobs: parked at 9 m. gantry-1's path runs to 7.6 m.
  TwoGantries site(GetParam(), {along_x("gantry-1", 10, {{0.0, 2.0}, {20.0, 7.6}})}, {2.0, 9.0},
                   -1.0, /*guard=*/true);
  site.go(120.0);
  ASSERT_TRUE(site.dispatcher->stopped());
  EXPECT_EQ(site.dispatcher->stopped()->rfind("site watchdog", 0), 0u);
  EXPECT_GE(site.gap_m(), kWidth_m - 1e-9);
  EXPECT_LT(site.gap_m(), kWidth_m + 0.05);
  EXPECT_NEAR(site.sims[1]->position()[0], 9.0, 1e-12) << "the parked gantry never moved";
}

TEST_P(AtEverySpeed, PlannedPathsRunToTheirEndsAtTheirPlannedTimes) {
  TwoGantries site(GetParam(), crossing_paths(), {2.0, 12.0}, -1.0, /*guard=*/true);
  site.go(120.0);
  ASSERT_TRUE(site.dispatcher->finished());
  EXPECT_FALSE(site.dispatcher->stopped());
  EXPECT_EQ(site.sims[0]->executed(), std::vector<std::int64_t>{10});
  EXPECT_EQ(site.sims[1]->executed(), std::vector<std::int64_t>{20});
  // Both started at 0 on the one clock and ended when planned.
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(10).first, 0.0);
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(10).second, 15.0);
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(20).second, 20.0);
  EXPECT_GE(site.run->guard().smallest_gap_m(), 3.8 - 1e-9);  // at t = 8 s, as planned
}

INSTANTIATE_TEST_SUITE_P(SiteRun, AtEverySpeed, ::testing::Values(1.0, 10'000.0),
                         [](const auto& info) { return info.param == 1.0 ? "At1x" : "At10000x"; });

TEST(SiteRun, LostRepeatedAndReorderedMessagesRunNoJobTwice) {
  TwoGantries site(10'000.0, crossing_paths(), {2.0, 12.0}, -1.0, true, /*drop=*/0.2);
  site.go(120.0);
  ASSERT_TRUE(site.dispatcher->finished());
  EXPECT_FALSE(site.dispatcher->stopped());
  EXPECT_EQ(site.sims[0]->executed(), std::vector<std::int64_t>{10});
  EXPECT_EQ(site.sims[1]->executed(), std::vector<std::int64_t>{20});
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(20).second, 20.0);
  EXPECT_GT(site.run->clock().repeats() + site.dispatcher->resent(), 0);
}

TEST(TerminationCondition, CancelledFromAnotherThreadThroughACopy) {
  const TerminationCondition done;
  const TerminationCondition copy = done;
  EXPECT_FALSE(done());
  std::thread([copy] { copy.cancel(); }).join();
  EXPECT_TRUE(done());
  EXPECT_TRUE(done.cancelled());
  EXPECT_FALSE(TerminationCondition::after_real_s(60.0)());
  EXPECT_TRUE(TerminationCondition::after_real_s(0.0)());
}

}  // namespace
}  // namespace ccbuild::dispatch
