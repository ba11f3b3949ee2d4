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
#include "ccbuild/dispatch/site_clock.hpp"
#include "ccbuild/dispatch/site_run.hpp"
#include "ccbuild/sim/sim_machine.hpp"
#include "ccbuild/wire/bus.hpp"
#include "ccbuild_lcm/ccbuild_clock_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

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
      sim::SimOptions so;
      so.machine_id = "gantry-" + std::to_string(k + 1);
      so.site_clock = true;
      so.home = {homes_m[k], 1.0, 0.1, 0.0};
      so.drop = so.duplicate = so.reorder = drop;
      so.seed = 7 + k;
      if (k == 0) so.stall_at_s = stall_at_s;
      sims.push_back(std::make_unique<sim::SimMachine>(bus, so));
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

  wire::Bus bus;
  Journal journal;
  std::vector<std::unique_ptr<sim::SimMachine>> sims;
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

TEST_P(AtEverySpeed, AJobPlannedAtAnotherOnesEndStartsExactlyThere) {
  // Layer 0: gantry-1 out to 6 m and gantry-2 in to 9 m, both in 8 s; layer 1 (planned
  // at 8 s): gantry-1 back to 3 m by 15 s. A tick lands on the layer's planned end, so the
  // next starts on time, not a status period or a step of the clock later.
  std::vector<DispatchJob> jobs = {along_x("gantry-1", 10, {{0.0, 2.0}, {8.0, 6.0}}),
                                   along_x("gantry-2", 20, {{0.0, 12.0}, {8.0, 9.0}}),
                                   along_x("gantry-1", 30, {{0.0, 6.0}, {7.0, 3.0}})};
  jobs[2].start_s = 8.0;
  jobs[2].layer = 1;
  TwoGantries site(GetParam(), jobs, {2.0, 12.0}, -1.0, /*guard=*/true);
  site.go(120.0);
  ASSERT_TRUE(site.dispatcher->finished());
  EXPECT_FALSE(site.dispatcher->stopped());
  EXPECT_EQ(site.sims[0]->executed(), (std::vector<std::int64_t>{10, 30}));
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(10).second, 8.0);
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(20).second, 8.0);
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(30).first, 8.0);
  EXPECT_DOUBLE_EQ(site.dispatcher->executed().at(30).second, 15.0);
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

/// `machine`'s answer to `tick`, idle at `t_s`.
ccbuild_lcm::ccbuild_status_t answer(const std::string& machine, std::int64_t tick, double t_s) {
  ccbuild_lcm::ccbuild_status_t s{};
  s.machine_id = machine;
  s.state = ccbuild_lcm::ccbuild_status_t::IDLE;
  s.sim_time_s = t_s;
  s.tick = tick;
  s.idle_until_s = -1.0;
  return s;
}

TEST(SiteClock, MovesOnOnlyOnceEveryMachineHasAnsweredTheCurrentTick) {
  wire::Bus bus("memq://");
  SiteClockOptions o;
  o.machines = {"gantry-1", "gantry-2"};
  o.copies = 1;
  SiteClock clock(bus, o);
  std::vector<std::int64_t> ticks_sent;
  bus.subscribe<ccbuild_lcm::ccbuild_clock_t>(
      wire::kClockChannel,
      [&](const ccbuild_lcm::ccbuild_clock_t& c) { ticks_sent.push_back(c.tick); });
  const auto say = [&](const ccbuild_lcm::ccbuild_status_t& s) {
    bus.publish(wire::channel("STATUS", s.machine_id), s);
    while (bus.handle(0) > 0) {
    }
  };
  const std::vector<std::string> both = {"gantry-1", "gantry-2"}, second = {"gantry-2"};

  // Before the first tick: answered once each machine has been heard; the site's time is
  // the latest a machine reported.
  EXPECT_FALSE(clock.answered());
  say(answer("gantry-1", 0, 5.0));
  EXPECT_FALSE(clock.answered());
  EXPECT_EQ(clock.waiting_for(), second);
  say(answer("gantry-2", 0, 3.0));
  EXPECT_TRUE(clock.answered());
  EXPECT_DOUBLE_EQ(clock.now_s(), 5.0);

  clock.advance_to(6.0);
  say(answer("gantry-1", 0, 5.0));  // a copy of an earlier answer, delivered late
  EXPECT_EQ(clock.tick(), 1);
  EXPECT_EQ(clock.waiting_for(), both);
  say(answer("gantry-1", 1, 6.0));
  EXPECT_FALSE(clock.answered());
  EXPECT_EQ(clock.waiting_for(), second);
  // An answer to the tick before is not an answer to this one (one tick behind).
  say(answer("gantry-2", 0, 5.0));
  EXPECT_FALSE(clock.answered());
  EXPECT_EQ(clock.waiting_for(), second);
  // Unanswered: the tick is sent again after repeat_after_s, not before.
  const std::size_t sent = ticks_sent.size();
  clock.step(o.repeat_after_s * 0.5);
  while (bus.handle(0) > 0) {
  }
  EXPECT_EQ(ticks_sent.size(), sent);
  clock.step(o.repeat_after_s * 0.5);
  while (bus.handle(0) > 0) {
  }
  ASSERT_EQ(ticks_sent.size(), sent + 1);
  EXPECT_EQ(ticks_sent.back(), 1);
  say(answer("gantry-2", 1, 6.0));
  EXPECT_TRUE(clock.answered());
  EXPECT_TRUE(clock.waiting_for().empty());
  // An older answer arriving after a newer one changes nothing.
  say(answer("gantry-1", 0, 5.0));
  EXPECT_EQ(clock.instants().at("gantry-1").tick, 1);
  EXPECT_TRUE(clock.answered());
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
