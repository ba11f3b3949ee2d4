// What the simulated machine refuses and what the dispatcher does about faults: the
// machine's limits from its URDF (the examples' paths keep them; a path just over one
// does not), the material's interval window at its boundary (from when a late layer
// really starts), where the machine is between waypoints, the site watchdog at the
// gantry width plus its margin (positions interpolated from the right end, within its
// span), a pin that misses (tried again, then a safe stop) and a clog (purged, the rest
// of the layer re-planned, the same recovery after a restart; a gantry moved clear only
// when closer than its width).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "ccbuild/dispatch/dispatch_jobs.hpp"
#include "ccbuild/dispatch/dispatcher.hpp"
#include "ccbuild/dispatch/run_report.hpp"
#include "ccbuild/dispatch/site_watchdog.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/sim/sim_machine.hpp"
#include "ccbuild/wire/bus.hpp"
#include "test_support.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"
#pragma GCC diagnostic pop

namespace ccbuild::dispatch {
namespace {
using schedule::build_schedule;
using schedule::open_project;
using schedule::parse_schedule;
using schedule::Project;
using schedule::recorded_inputs;
using schedule::ScheduleDocument;
using schedule::ScheduleOptions;

using ccbuild_lcm::ccbuild_fault_t;
using testing::contains;

/// The ends of each extruding run of one wall piece in `p`, in path order: (waypoint,
/// wall) pairs, two per run.
std::vector<std::pair<std::size_t, std::int64_t>> piece_ends(const wire::TimedPath& p) {
  std::vector<std::pair<std::size_t, std::int64_t>> ends;
  std::size_t k = 0;
  while (k + 1 < p.size()) {
    if (!p.extruding[k]) {
      ++k;
      continue;
    }
    // A run: from its first waypoint to the one where the nozzle stops depositing this
    // piece (the next waypoint after the last extruding segment).
    const std::size_t first = k;
    while (k + 1 < p.size() && p.extruding[k] && p.wall[k] == p.wall[first] &&
           p.piece[k] == p.piece[first])
      ++k;
    ends.emplace_back(first, p.wall[first]);
    ends.emplace_back(k, p.wall[first]);
  }
  return ends;
}

const wire::TimedPath& path_of(const DispatchJob& d) {
  return d.path;
}

ScheduleDocument golden(const std::string& name) {
  const auto path = testing::source_path("tests/regression/" + name + ".schedule.json");
  return parse_schedule(testing::slurp(path), path.string());
}

/// An example's schedule with its paths: the golden where it keeps them (the house), else
/// scheduled again (the apartment's and the tower's goldens keep their digests only).
ScheduleDocument example(const std::string& name) {
  if (name == "house") return golden(name);
  const Project project = open_project(testing::source_path("config/buildings/" + name + ".yaml"));
  const ScheduleOptions options;
  return {recorded_inputs(project, options), build_schedule(project, options)};
}

TEST(SimMachine, TheExamplesPathsKeepTheirMachinesLimits) {
  const struct {
    const char* building;
    const char* machine;
    bool check_z;
  } cases[] = {{"house", "cc-gantry", true},
               {"apartment", "cc-gantry", true},
               {"tower", "cc-climber", false}};
  for (const auto& c : cases) {
    const auto model = machine::load_machine(
        testing::source_path(std::string("config/machines/") + c.machine + ".yaml"));
    int checked = 0;
    for (const auto& job : jobs_of_schedule(example(c.building))) {
      if (job.path.size() == 0) continue;
      const auto breach = sim::limit_breach(model, path_of(job), c.check_z);
      EXPECT_FALSE(breach) << c.building << " job " << job.job_id << ": " << breach->second;
      ++checked;
    }
    EXPECT_GT(checked, 10) << c.building;
  }
}

wire::TimedPath two_points(double t_s, double x0, double x1) {
  wire::TimedPath p;
  p.push_back(0.0, x0, 1.0, 1.0, 0.0, true, 1, 1);
  p.push_back(t_s, x1, 1.0, 1.0, 0.0, false, 0, 0);
  return p;
}

TEST(SimMachine, LimitsHoldAtTheirBoundary) {
  const auto m = machine::MachineModel::defaults();  // x 0..50 m at 0.5 m/s
  ASSERT_DOUBLE_EQ(m.x.speed_m_s, 0.5);
  ASSERT_DOUBLE_EQ(m.x.max_m, 50.0);
  EXPECT_FALSE(sim::limit_breach(m, two_points(10.0, 0.0, 5.0), true));  // exactly 0.5 m/s
  const auto fast = sim::limit_breach(m, two_points(10.0, 0.0, 5.01), true);
  ASSERT_TRUE(fast);
  EXPECT_EQ(fast->first, +ccbuild_fault_t::VELOCITY_LIMIT);
  EXPECT_FALSE(sim::limit_breach(m, two_points(100.0, 0.0, 50.0), true));  // at its end
  const auto beyond = sim::limit_breach(m, two_points(100.0, 0.0, 50.01), true);
  ASSERT_TRUE(beyond);
  EXPECT_EQ(beyond->first, +ccbuild_fault_t::JOINT_LIMIT);
  // Both ends of a move count: it may not start outside either.
  const auto start_outside = sim::limit_breach(m, two_points(200.0, -0.01, 10.0), true);
  ASSERT_TRUE(start_outside);
  EXPECT_EQ(start_outside->first, +ccbuild_fault_t::JOINT_LIMIT);
  // The stopper, and a turn faster than the nozzle's rotation.
  auto turn = two_points(4.0, 1.0, 1.0);
  turn.heading_rad = {0.0, m.stopper_max_rad};
  EXPECT_FALSE(sim::limit_breach(m, turn, true));
  turn.heading_rad = {0.0, m.stopper_max_rad + 0.01};
  ASSERT_TRUE(sim::limit_breach(m, turn, true));
  turn.t_s = {0.0, 3.9};
  turn.heading_rad = {0.0, m.stopper_max_rad};
  EXPECT_EQ(sim::limit_breach(m, turn, true)->first, +ccbuild_fault_t::VELOCITY_LIMIT);
  // A turn planned at exactly the rotation limit reaches the machine rounded to µs and
  // µrad: within that rounding it holds, 3 µrad past the limit's reach it does not.
  const double at_limit_rad = m.rotation_speed_rad_s * 0.3338;
  turn.t_s = {0.0, 0.3338};
  turn.heading_rad = {0.0, at_limit_rad + 0.9e-6};
  EXPECT_FALSE(sim::limit_breach(m, turn, true));
  turn.heading_rad = {0.0, at_limit_rad + 3e-6};
  ASSERT_TRUE(sim::limit_breach(m, turn, true));
  EXPECT_EQ(sim::limit_breach(m, turn, true)->first, +ccbuild_fault_t::VELOCITY_LIMIT);
  // Two waypoints at one time, their headings one µrad apart as rounded (1.570797 -
  // 1.570796 is 1.0000000000287557e-06 in doubles): no move (the public Gymzaal's clean
  // dry-run stopped on it). Four µrad apart at one time is a turn with no time: refused.
  turn.t_s = {5.0, 5.0};
  turn.heading_rad = {1.570796, 1.570797};
  EXPECT_FALSE(sim::limit_breach(m, turn, true));
  turn.heading_rad = {1.570796, 1.5708};
  ASSERT_TRUE(sim::limit_breach(m, turn, true));
  EXPECT_EQ(sim::limit_breach(m, turn, true)->first, +ccbuild_fault_t::VELOCITY_LIMIT);
  // Heights: outside z range is refused, unless the machine climbs.
  auto high = two_points(10.0, 1.0, 1.0);
  high.z_m = {m.z.max_m + 0.5, m.z.max_m + 0.5};
  EXPECT_TRUE(sim::limit_breach(m, high, true));
  EXPECT_FALSE(sim::limit_breach(m, high, false));
}

/// A deposit job of one wall piece from (0, 0) to (1, 0) in 5 s, for `layer` of floor 0.
DispatchJob piece_job(std::int64_t id, int layer, double start_s) {
  DispatchJob d;
  d.machine_id = "gantry-1";
  d.job_id = id;
  d.kind = JobKind::kDeposit;
  d.floor = 0;
  d.layer = layer;
  d.nozzle = 0;
  d.start_s = start_s;
  d.duration_s = 5.0;
  d.plan = "g1n1";
  d.detail = "test";
  const double z_m = 0.1 * (layer + 1);
  d.path.push_back(0.0, 0.0, 0.0, z_m, 0.0, true, 1, 1);
  d.path.push_back(5.0, 1.0, 0.0, z_m, 0.0, false, 0, 0);
  return d;
}

/// Runs `jobs` through a dispatcher and a machine on one memq:// bus until done.
struct Rig {
  explicit Rig(sim::SimOptions so, std::vector<DispatchJob> jobs,
               std::filesystem::path journal_path = ":memory:", DispatchOptions o = {})
      : bus("memq://"), journal(journal_path), sim(bus, so) {
    o.speed = so.speed;
    o.ack_timeout_s = 0.05;
    o.done_slack_s = 0.05;
    dispatcher = std::make_unique<Dispatcher>(bus, std::move(jobs), journal, o);
  }
  void run(int steps = 200'000) {
    for (int k = 0; k < steps && !dispatcher->finished(); ++k) {
      dispatcher->step(1e-3);
      bus.handle(0);
      sim.step(1e-3);
      bus.handle(0);
    }
  }
  std::set<std::int8_t> fault_kinds() const {
    std::set<std::int8_t> out;
    for (const auto& f : dispatcher->fault_records()) out.insert(static_cast<std::int8_t>(f.kind));
    return out;
  }
  wire::Bus bus;
  Journal journal;
  sim::SimMachine sim;
  std::unique_ptr<Dispatcher> dispatcher;
};

sim::SimOptions window(double min_s, double max_s) {
  sim::SimOptions so;
  so.speed = 1e4;
  so.min_interval_s = min_s;
  so.max_interval_s = max_s;
  return so;
}

TEST(SimMachine, TheIntervalWindowHoldsAtItsBoundary) {
  // Layer 1 covers the piece exactly as long after layer 0 as the start times differ.
  const struct {
    double interval_s;
    std::int8_t fault;  // 0: accepted
  } cases[] = {{500.0, 0},
               {500.01, ccbuild_fault_t::COLD_JOINT},
               {60.0, 0},
               {59.99, ccbuild_fault_t::TOO_EARLY}};
  for (const auto& c : cases) {
    Rig rig(window(60.0, 500.0), {piece_job(10, 0, 0.0), piece_job(20, 1, c.interval_s)});
    rig.run();
    ASSERT_TRUE(rig.dispatcher->finished()) << c.interval_s;
    if (c.fault == 0) {
      EXPECT_FALSE(rig.dispatcher->stopped()) << c.interval_s;
      EXPECT_EQ(rig.sim.executed().size(), 2u) << c.interval_s;
    } else {
      ASSERT_TRUE(rig.dispatcher->stopped()) << c.interval_s;
      EXPECT_EQ(rig.fault_kinds(), std::set<std::int8_t>{c.fault}) << c.interval_s;
      EXPECT_EQ(rig.sim.executed().size(), 1u) << "the refused layer ran: " << c.interval_s;
    }
  }
}

DispatchJob climb_phase(std::int64_t id, const std::string& what, double start_s,
                        double duration_s) {
  DispatchJob d = piece_job(id, -1, start_s);
  d.kind = JobKind::kClimbPhase;
  d.floor = 0;
  d.layer = -1;
  d.nozzle = -1;
  d.duration_s = duration_s;
  d.plan = "";
  d.detail = "climb from stage 0 to 1: " + what;
  d.path = {};
  // The machine reads the phase and the unit from their fields, never from the words.
  if (what.rfind("insert ", 0) == 0) {
    d.phase = ccbuild_lcm::ccbuild_job_t::INSERT;
    d.unit = what.substr(7);
  } else if (what == "lift") {
    d.phase = ccbuild_lcm::ccbuild_job_t::LIFT;
  }
  return d;
}

TEST(Dispatch, AMissedPinIsTriedAgainUpToThreeTimesThenEverythingStops) {
  const std::vector<DispatchJob> climb = {climb_phase(10, "insert U1", 0.0, 60.0),
                                          climb_phase(20, "lift", 60.0, 100.0)};
  {
    sim::SimOptions so = window(0.0, 1e9);
    so.pin_failures = 2;  // the third attempt finds its pipe
    Rig rig(so, climb);
    rig.run();
    ASSERT_TRUE(rig.dispatcher->finished());
    EXPECT_FALSE(rig.dispatcher->stopped());
    EXPECT_EQ(rig.sim.executed(), (std::vector<std::int64_t>{10, 11, 12, 20}));
    EXPECT_EQ(rig.fault_kinds(), std::set<std::int8_t>{ccbuild_fault_t::PIN_MISSED});
    EXPECT_DOUBLE_EQ(rig.dispatcher->delay_s(), 120.0);  // two insertions more
    EXPECT_DOUBLE_EQ(rig.dispatcher->executed().at(20).first, 180.0);
    const auto states = rig.journal.states();
    EXPECT_EQ(states.at(10), dispatch::JobState::kPinMissed);
    EXPECT_EQ(states.at(11), dispatch::JobState::kPinMissed);
    EXPECT_EQ(states.at(12), dispatch::JobState::kDone);
    EXPECT_EQ(states.at(20), dispatch::JobState::kDone);
  }
  {
    sim::SimOptions so = window(0.0, 1e9);
    so.pin_failures = 3;  // never: stop after the third
    Rig rig(so, climb);
    rig.run();
    ASSERT_TRUE(rig.dispatcher->stopped());
    EXPECT_NE(rig.dispatcher->stopped()->find("no recovery left"), std::string::npos);
    EXPECT_EQ(rig.sim.executed(), (std::vector<std::int64_t>{10, 11, 12}));
    const auto states = rig.journal.states();
    EXPECT_EQ(states.count(20), 0u) << "the lift was sent after a pin that never held";
    const auto faults = rig.journal.faults();
    ASSERT_EQ(faults.size(), 4u);  // three misses, then the stop
    EXPECT_EQ(faults.back().policy, dispatch::FaultPolicy::kStop);
  }
}

TEST(SimMachine, APinGoesIntoAnAnchorOnlyOnceItIsOldEnough) {
  DispatchJob pipe = climb_phase(10, "", 0.0, 120.0);
  pipe.kind = JobKind::kPipe;
  pipe.detail = "pipe A1 for unit U1";
  pipe.unit = "U1";
  pipe.anchor = "A1";
  for (const double age_s : {3600.0, 3599.99}) {
    sim::SimOptions so = window(0.0, 1e9);
    so.anchor_min_age_s = 3600.0;
    Rig rig(so, {pipe, climb_phase(20, "insert U2", 120.0, 60.0),
                 climb_phase(30, "insert U1", 120.0 + age_s, 60.0)});
    rig.run();
    ASSERT_TRUE(rig.dispatcher->finished());
    if (age_s >= 3600.0) {
      EXPECT_FALSE(rig.dispatcher->stopped());
      EXPECT_EQ(rig.sim.executed().size(), 3u);
    } else {
      ASSERT_TRUE(rig.dispatcher->stopped());
      EXPECT_EQ(rig.fault_kinds(), std::set<std::int8_t>{ccbuild_fault_t::ANCHOR_TOO_YOUNG});
      EXPECT_EQ(rig.sim.executed(), (std::vector<std::int64_t>{10, 20}));  // U2 has no pipe yet
    }
  }
}

TEST(SimMachine, FollowsItsPathBetweenWaypointsOnItsClock) {
  // At machine speed 1, a quarter of the way into the 5 s piece from (0, 0) to (1, 0):
  // at 0.25 m, and so says its status.
  sim::SimOptions so = window(0.0, 1e9);
  so.speed = 1.0;
  Rig rig(so, {piece_job(10, 0, 0.0)});
  std::vector<double> reported_x_m;
  rig.bus.subscribe<ccbuild_lcm::ccbuild_status_t>(
      wire::channel("STATUS", "gantry-1"),
      [&](const ccbuild_lcm::ccbuild_status_t& s) { reported_x_m.push_back(s.x_m); });
  // Until the machine has started the job (on its arrival or at the end of a step).
  for (int k = 0; k < 5'000 && !rig.sim.busy(); ++k) {
    rig.dispatcher->step(1e-3);
    rig.bus.handle(0);
    if (!rig.sim.busy()) rig.sim.step(1e-3);
    rig.bus.handle(0);
  }
  ASSERT_TRUE(rig.sim.busy());
  const double started_s = rig.sim.clock_s();
  EXPECT_DOUBLE_EQ(started_s, 0.0);
  rig.sim.step(1.25);
  rig.bus.handle(0);
  EXPECT_DOUBLE_EQ(rig.sim.clock_s(), 1.25);
  EXPECT_NEAR(rig.sim.position()[0], 0.25, 1e-12);
  EXPECT_NEAR(rig.sim.position()[1], 0.0, 1e-12);
  ASSERT_FALSE(reported_x_m.empty());
  EXPECT_NEAR(reported_x_m.back(), 0.25, 1e-12);
  rig.run();
  EXPECT_EQ(rig.sim.executed(), std::vector<std::int64_t>{10});
  EXPECT_DOUBLE_EQ(rig.sim.position()[0], 1.0);
}

TEST(SimMachine, ALayerStartedLateIsCheckedFromWhenItStarts) {
  // Layer 1 is planned 3 s after layer 0, which takes 5 s: the machine starts it when it
  // is free, at 5 s, and its piece is covered 5 s after it was deposited: a cold joint
  // over a 4.5 s maximum, and no longer too early for a 4 s minimum.
  const struct {
    double min_s, max_s;
    std::int8_t fault;  // 0: accepted
  } cases[] = {{0.0, 4.5, ccbuild_fault_t::COLD_JOINT}, {4.0, 1e9, 0}};
  for (const auto& c : cases) {
    Rig rig(window(c.min_s, c.max_s), {piece_job(10, 0, 0.0), piece_job(20, 1, 3.0)});
    rig.run();
    ASSERT_TRUE(rig.dispatcher->finished());
    if (c.fault == 0) {
      ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
      EXPECT_DOUBLE_EQ(rig.dispatcher->executed().at(20).first, 5.0);
    } else {
      ASSERT_TRUE(rig.dispatcher->stopped());
      EXPECT_EQ(rig.fault_kinds(), std::set<std::int8_t>{c.fault});
      EXPECT_TRUE(contains(*rig.dispatcher->stopped(), "covered 5.0 s after it was deposited"))
          << *rig.dispatcher->stopped();
    }
  }
}

TEST(Dispatch, AClogIsPurgedAndTheRestOfTheLayerRunsTheSameAfterARestart) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_clog_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto jobs = jobs_of_schedule(golden("house"));
  sim::SimOptions so = window(0.0, 1e9);
  so.speed = 1e6;
  so.clog_floor = 0;
  so.clog_layer = 2;
  so.state_file = dir / "gantry-1.state";
  std::vector<DispatchJob> made_first;
  {
    Rig rig(so, jobs, dir / "journal.sqlite");
    // Until the recovery jobs exist, then "killed".
    for (int k = 0; k < 200'000 && rig.dispatcher->jobs().size() == jobs.size(); ++k) rig.run(1);
    ASSERT_EQ(rig.dispatcher->jobs().size(), jobs.size() + 2);
    made_first.assign(rig.dispatcher->jobs().begin() + jobs.size(), rig.dispatcher->jobs().end());
  }
  sim::SimOptions again = so;
  again.clog_floor = -1;
  Rig rig(again, jobs, dir / "journal.sqlite");
  ASSERT_EQ(rig.dispatcher->jobs().size(), jobs.size() + 2) << "the recovery was not made again";
  const auto& purge = rig.dispatcher->jobs()[jobs.size()];
  const auto& rest = rig.dispatcher->jobs()[jobs.size() + 1];
  EXPECT_EQ(purge.job_id, made_first[0].job_id);
  EXPECT_EQ(rest.job_id, made_first[1].job_id);
  EXPECT_EQ(purge.kind, JobKind::kPurge);
  EXPECT_DOUBLE_EQ(purge.duration_s, 120.0);
  // The rest is the clogged path from where it stopped, its times from there.
  const auto rows = rig.journal.rows();
  const std::int64_t clogged = purge.job_id - 1;
  ASSERT_EQ(rows.at(clogged).state, dispatch::JobState::kClogged);
  const int stopped_at = rows.at(clogged).stopped_at;
  const DispatchJob* original = nullptr;
  for (const auto& j : jobs)
    if (j.job_id == clogged) original = &j;
  ASSERT_NE(original, nullptr);
  const auto whole = path_of(*original), tail = path_of(rest);
  ASSERT_EQ(tail.size(), whole.size() - stopped_at);
  EXPECT_DOUBLE_EQ(tail.t_s.front(), 0.0);
  EXPECT_DOUBLE_EQ(tail.x_m.front(), whole.x_m[stopped_at]);
  EXPECT_DOUBLE_EQ(tail.x_m.back(), whole.x_m.back());
  EXPECT_NEAR(rest.duration_s + whole.t_s[stopped_at], original->duration_s, 1e-9);
  EXPECT_NEAR(rest.start_s, rows.at(clogged).finished_s + 120.0, 1e-9);
  rig.run();
  ASSERT_TRUE(rig.dispatcher->finished());
  EXPECT_FALSE(rig.dispatcher->stopped());
  const auto& ran = rig.sim.executed();
  EXPECT_EQ(std::set<std::int64_t>(ran.begin(), ran.end()).size(), ran.size()) << "a job ran twice";
  EXPECT_EQ(ran.size(), jobs.size() + 2);
  // The schedule JSON keeps times to the microsecond: moves may start 10 us late.
  EXPECT_NEAR(rig.dispatcher->delay_s(), 120.0, 1e-3);
  std::filesystem::remove_all(dir);
}

/// A deposit job of one straight wall piece along x, from `x0` to `x1` at 0.2 m/s.
DispatchJob along_x(const std::string& machine, std::int64_t id, double x0, double x1) {
  DispatchJob d = piece_job(id, 0, 0.0);
  d.machine_id = machine;
  d.path = {};
  for (int k = 0; k <= 10; ++k) {
    const bool last = k == 10;
    d.path.push_back(k * std::abs(x1 - x0) / 10.0 / 0.2, x0 + (x1 - x0) * k / 10.0, 1.0, 0.1, 0.0,
                     !last, last ? 0 : 1, last ? 0 : 1);
  }
  d.duration_s = d.path.t_s.back();
  return d;
}

/// gantry-1 lays x 0 -> 6 while gantry-2 lays x 13 -> `gantry2_to_m`; gantry-1 clogs at
/// 40%, and the rest of its wall (up to 6 m) needs gantry-2 a gantry width (2 m) clear.
struct ClogBesideANeighbour {
  explicit ClogBesideANeighbour(double gantry2_to_m)
      : bus("memq://"), journal(":memory:"), sim1(bus, gantry(1)), sim2(bus, gantry(2)) {
    DispatchOptions o;
    o.speed = window(0.0, 1e9).speed;
    o.gantry_width_m = 2.0;
    o.purge_s = 1.0;  // over before gantry-2's wall is: the rest must still wait for it
    o.rail_axis = machine::RailAxis::kX;
    o.rail_min_m = -2.0;
    o.rail_max_m = 20.0;
    dispatcher.emplace(bus,
                       std::vector<DispatchJob>{along_x("gantry-1", 10, 0.0, 6.0),
                                                along_x("gantry-2", 20, 13.0, gantry2_to_m)},
                       journal, o);
    for (int k = 0; k < 100'000 && !dispatcher->finished(); ++k) {
      dispatcher->step(1e-3);
      bus.handle(0);
      sim1.step(1e-3);
      sim2.step(1e-3);
      bus.handle(0);
    }
  }
  static sim::SimOptions gantry(int k) {
    sim::SimOptions o = window(0.0, 1e9);
    o.machine_id = "gantry-" + std::to_string(k);
    if (k == 1) o.clog_floor = o.clog_layer = 0;
    return o;
  }
  wire::Bus bus;
  Journal journal;
  sim::SimMachine sim1, sim2;
  std::optional<Dispatcher> dispatcher;
};

TEST(Dispatch, TheRestOfAClogRunsAloneWithTheGantriesInItsWayMovedClear) {
  // gantry-2 parks at 7.6, too close (2 m apart) for the rest of gantry-1's wall up to 6.
  ClogBesideANeighbour run(7.6);
  const Dispatcher& d = *run.dispatcher;
  ASSERT_TRUE(d.finished());
  ASSERT_FALSE(d.stopped()) << *d.stopped();
  // clog, purge, rest (its id after one left free for a treatment it did not need)
  EXPECT_EQ(run.sim1.executed(), (std::vector<std::int64_t>{10, 11, 13}));
  EXPECT_EQ(run.sim2.executed(), (std::vector<std::int64_t>{20, 21}));  // its wall, the move
  const auto& move = d.jobs().at(4);
  EXPECT_EQ(move.kind, JobKind::kTravel);
  EXPECT_DOUBLE_EQ(move.path.x_m.back(), 8.0);  // the rest reaches 6: 6 + 2
  EXPECT_DOUBLE_EQ(run.sim2.position()[0], 8.0);
  // The rest started only once gantry-2 had moved clear.
  EXPECT_GE(d.executed().at(13).first, d.executed().at(21).second - 1e-9);
}

TEST(Dispatch, AGantryAlreadyAWidthClearOfTheRestOfAClogStaysWhereItIs) {
  // gantry-2's wall ends at 8 m: exactly the gantry width past the rest of gantry-1's wall
  // (up to 6 m). Nothing to move clear; the rest runs as soon as gantry-2 is done.
  ClogBesideANeighbour run(8.0);
  const Dispatcher& d = *run.dispatcher;
  ASSERT_TRUE(d.finished());
  ASSERT_FALSE(d.stopped()) << *d.stopped();
  EXPECT_EQ(run.sim1.executed(), (std::vector<std::int64_t>{10, 11, 13}));  // clog, purge, rest
  EXPECT_EQ(run.sim2.executed(), (std::vector<std::int64_t>{20}));          // no move
  EXPECT_EQ(d.jobs().size(), 4u);
  EXPECT_DOUBLE_EQ(run.sim2.position()[0], 8.0);
  EXPECT_DOUBLE_EQ(d.executed().at(13).first, d.executed().at(20).second);
}

/// A status of machine `id` at machine time `t_s`, on `channel_of`'s status channel (by
/// default its own).
void status(wire::Bus& bus, const std::string& id, double t_s, double x_m,
            const std::string& channel_of = "") {
  static std::int64_t seq = 0;
  ccbuild_lcm::ccbuild_status_t s{};
  s.utime = wire::utime_now();
  s.machine_id = id;
  s.seq = ++seq;
  s.state = ccbuild_lcm::ccbuild_status_t::BUSY;
  s.sim_time_s = t_s;
  s.x_m = x_m;
  bus.publish(wire::channel("STATUS", channel_of.empty() ? id : channel_of), s);
  bus.handle(0);
}

TEST(SiteWatchdog, PausesBelowTheGantryWidthPlusItsMarginNotAtIt) {
  wire::Bus bus("memq://");
  WatchdogOptions w;
  w.machines = {"gantry-1", "gantry-2"};
  w.gantry_width_m = 1.5;
  w.margin_m = 0.5;
  SiteWatchdog dog(bus, w);
  status(bus, "gantry-1", 0.0, 0.0);
  status(bus, "gantry-2", 0.0, 2.0);  // exactly width plus margin
  EXPECT_FALSE(dog.check(0.01));
  EXPECT_DOUBLE_EQ(dog.smallest_gap_m(), 2.0);
  // gantry-1 moves up at 0.1 m/s; gantry-2 reports at 5 s: gantry-1 is at 0.5 m then.
  status(bus, "gantry-1", 10.0, 1.0);
  status(bus, "gantry-2", 5.0, 2.501);
  EXPECT_FALSE(dog.check(0.01));
  EXPECT_NEAR(dog.smallest_gap_m(), 2.0, 1e-9);
  // Another machine's status on gantry-2's channel is not believed: "gantry-3" at 1.2 m,
  // 0.2 m from gantry-1, is neither gantry-2's position nor its heartbeat.
  EXPECT_FALSE(dog.check(1.5));
  status(bus, "gantry-1", 10.0, 1.0);
  status(bus, "gantry-3", 10.0, 1.2, "gantry-2");
  EXPECT_FALSE(dog.check(1.0));
  EXPECT_NEAR(dog.smallest_gap_m(), 2.0, 1e-9);
  EXPECT_EQ(dog.silent(), std::vector<std::string>{"gantry-2"});  // 2.5 s since its last
  status(bus, "gantry-2", 10.0, 2.999);                           // 1.999 m: under by a millimetre
  EXPECT_TRUE(dog.silent().empty());
  const auto why = dog.check(0.01);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("every machine paused"), std::string::npos);
  EXPECT_FALSE(dog.check(0.01)) << "said twice";
  EXPECT_EQ(dog.check(5.0), std::nullopt);
  EXPECT_EQ(dog.silent(), (std::vector<std::string>{"gantry-1", "gantry-2"}));
}

TEST(SiteWatchdog, MeasuresTheGapAtOneInstantInterpolatingFromTheEarlierStatus) {
  // Gaps are taken at the latest instant both machines have reported; the one that
  // reported later is placed between its two statuses, in proportion to the time from the
  // earlier one. Off the middle of the span, so that the wrong end shows.
  WatchdogOptions w;
  w.machines = {"gantry-1", "gantry-2"};
  w.gantry_width_m = 1.5;
  w.margin_m = 0.5;  // acted on under 2 m
  for (const double span_s : {8.0, 8.5}) {
    // gantry-1 moves up at 0.125 m/s and has reported at 0 s and `span_s`; gantry-2 has
    // reported 2 s: gantry-1 was at 0.25 m then, exactly 2 m from gantry-2 (at 0.75 m from
    // the wrong end). Statuses at most 8 s apart are interpolated: 8 s is, 8.5 s is not.
    wire::Bus bus("memq://");
    WatchdogOptions spanned = w;
    spanned.max_span_s = 8.0;
    SiteWatchdog dog(bus, spanned);
    status(bus, "gantry-1", 0.0, 0.0);
    status(bus, "gantry-2", 0.0, 3.0);
    EXPECT_FALSE(dog.check(0.01));
    EXPECT_EQ(dog.gaps_measured(), 1);
    status(bus, "gantry-1", span_s, 0.125 * span_s);
    status(bus, "gantry-2", 2.0, 2.25);
    EXPECT_FALSE(dog.check(0.01));
    if (span_s > spanned.max_span_s) {
      EXPECT_EQ(dog.gaps_measured(), 1) << "a position guessed over " << span_s << " s";
      EXPECT_DOUBLE_EQ(dog.smallest_gap_m(), 3.0);
      continue;
    }
    EXPECT_EQ(dog.gaps_measured(), 2);
    EXPECT_DOUBLE_EQ(dog.smallest_gap_m(), 2.0);
    // At 3 s: gantry-1 at 0.375 m, gantry-2 at 2.374 m: a millimetre under.
    status(bus, "gantry-2", 3.0, 2.374);
    const auto why = dog.check(0.01);
    ASSERT_TRUE(why);
    EXPECT_TRUE(contains(*why,
                         "at 3.0 s of machine time gantry-1 at 0.375 m and "
                         "gantry-2 at 2.374 m on the rails are 1.999 m apart"))
        << *why;
  }
  {
    // Now gantry-2 reported later: it moves down from 4 m at 0.2 m/s; at 7.5 s (gantry-1's
    // last status, at 0.5 m) it was at 2.5 m, 2 m from gantry-1; at 8 s, 1.95 m.
    wire::Bus bus("memq://");
    SiteWatchdog dog(bus, w);
    status(bus, "gantry-1", 0.0, 0.0);
    status(bus, "gantry-2", 0.0, 4.0);
    status(bus, "gantry-2", 10.0, 2.0);
    status(bus, "gantry-1", 7.5, 0.5);
    EXPECT_FALSE(dog.check(0.01));
    EXPECT_DOUBLE_EQ(dog.smallest_gap_m(), 2.0);
    status(bus, "gantry-1", 8.0, 0.45);
    const auto why = dog.check(0.01);
    ASSERT_TRUE(why);
    EXPECT_TRUE(contains(*why, "gantry-2 at 2.400 m")) << *why;
    EXPECT_NEAR(dog.smallest_gap_m(), 1.95, 1e-9);
  }
}

// --- Re-planning a late run from what the machines laid (replan.hpp) ---

/// What was laid below: one span of `wall` from (x0, y0) at t0 to (x1, y1) at t1.
rules::DepositIndex laid(std::int64_t wall, double x0, double y0, double t0, double x1, double y1,
                         double t1, rules::DepositIndex index = {}) {
  index.add(wall, {Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1), t0, t1, 1});
  return index;
}

/// The start window of piece_job's path over `below` (rules/intervals.hpp).
StartWindow window_over(const rules::DepositIndex& below, double min_s, double max_s) {
  rules::DepositIndex above;
  wire::add_deposits(above, piece_job(20, 1, 0.0).path, 0.0);
  return rules::start_window(rules::interval_offsets(above, below), min_s, max_s);
}

TEST(Replan, AStartWindowKeepsEachStretchWithinTheIntervalWithTheBeadsThatCoverIt) {
  // piece_job's path: one piece of wall 1 from x = 0 (t 0) to x = 1 m (t 5 s).
  StartWindow w = window_over(laid(1, 0.0, 0.0, 100.0, 1.0, 0.0, 110.0), 60.0, 500.0);
  EXPECT_EQ(w.ends_covered, 2);
  EXPECT_DOUBLE_EQ(w.earliest_s, 165.0);  // x = 0: 100 + 60 - 0; x = 1: 110 + 60 - 5
  EXPECT_DOUBLE_EQ(w.latest_s, 600.0);    // x = 0: 100 + 500 - 0; x = 1: 110 + 500 - 5
  EXPECT_DOUBLE_EQ(w.newest_below_s, 110.0);
  // Laid the other way: the end further along the path bounds the latest start.
  w = window_over(laid(1, 1.0, 0.0, 95.0, 0.0, 0.0, 100.0), 60.0, 500.0);
  EXPECT_DOUBLE_EQ(w.earliest_s, 160.0);  // x = 0: 100 + 60 - 0; x = 1: 95 + 60 - 5
  EXPECT_DOUBLE_EQ(w.latest_s, 590.0);    // x = 1: 95 + 500 - 5
  EXPECT_DOUBLE_EQ(w.newest_below_s, 100.0);
  EXPECT_FALSE(w.empty());
  // A bead 1.9 mm off the line is under it (layers merge points 1 mm apart); 2.1 mm off,
  // or of another wall, is not.
  EXPECT_EQ(window_over(laid(1, 0.0, 0.0019, 100.0, 1.0, 0.0019, 110.0), 60, 500).ends_covered, 2);
  EXPECT_EQ(window_over(laid(1, 0.0, 0.0021, 100.0, 1.0, 0.0021, 110.0), 60, 500).ends_covered, 0);
  EXPECT_EQ(window_over(laid(2, 0.0, 0.0, 100.0, 1.0, 0.0, 110.0), 60, 500).ends_covered, 0);
  // The piece of the same wall that meets it at its end, laid much later (a two-skin
  // wall's loop turning the corner), is not under it: the interval at x = 1 m is the
  // bead along the piece's (until 2026-12-07 the dispatcher paired every end there,
  // and re-planned a clean run of a valid schedule 37 times).
  w = window_over(
      laid(1, 1.0, 0.0, 400.0, 1.0, 0.5, 402.5, laid(1, 0.0, 0.0, 100.0, 1.0, 0.0, 110.0)), 60.0,
      500.0);
  EXPECT_EQ(w.ends_covered, 2);
  EXPECT_DOUBLE_EQ(w.earliest_s, 165.0);
  EXPECT_DOUBLE_EQ(w.newest_below_s, 110.0);
  // Two beads below meeting mid-piece (two gantries): each stretch with its own bead,
  // the meeting point once from each side.
  w = window_over(
      laid(1, 0.0, 0.0, 100.0, 0.5, 0.0, 102.5, laid(1, 0.5, 0.0, 300.0, 1.0, 0.0, 302.5)), 60.0,
      500.0);
  EXPECT_EQ(w.ends_covered, 4);
  EXPECT_DOUBLE_EQ(w.earliest_s, 357.5);  // from x = 0.5 on: 300 + 60 - 2.5
  EXPECT_DOUBLE_EQ(w.latest_s, 600.0);    // up to x = 0.5: 100 + 500 - 0 = 102.5 + 500 - 2.5
  // Ends laid 440 s apart leave no start for a 60-500 s window; 440 s is its width.
  StartWindow apart = window_over(laid(1, 0.0, 0.0, 0.0, 1.0, 0.0, 445.0), 60.0, 500.0);
  EXPECT_DOUBLE_EQ(apart.earliest_s, apart.latest_s);
  EXPECT_FALSE(apart.empty());
  apart = window_over(laid(1, 0.0, 0.0, 0.0, 1.0, 0.0, 445.001), 60.0, 500.0);
  EXPECT_TRUE(apart.empty());
  // What a deposit laid: every stretch, or those up to the waypoint it stopped at.
  const wire::TimedPath path = piece_job(20, 1, 0.0).path;
  rules::DepositIndex all, none, one;
  wire::add_deposits(all, path, 10.0);
  wire::add_deposits(none, path, 10.0, 0);
  wire::add_deposits(one, path, 10.0, 1);
  EXPECT_EQ(all.spans.at(1).size(), 1u);
  EXPECT_TRUE(none.empty());
  EXPECT_DOUBLE_EQ(one.spans.at(1).back().tb, 15.0);
}

/// A layer of two wall pieces along x at 0.2 m/s: wall 1 from x = 0 to 1 m, wall 2 from
/// 1 to 2 m; a clog stops it at x = 1 m (the first extruding waypoint past 40% of it).
DispatchJob two_walls(std::int64_t id, int layer, double start_s) {
  DispatchJob d = piece_job(id, layer, start_s);
  const double z_m = 0.1 * (layer + 1);
  d.path = {};
  d.path.push_back(0.0, 0.0, 0.0, z_m, 0.0, true, 1, 1);
  d.path.push_back(5.0, 1.0, 0.0, z_m, 0.0, true, 2, 1);
  d.path.push_back(10.0, 2.0, 0.0, z_m, 0.0, false, 0, 0);
  d.duration_s = 10.0;
  return d;
}

/// Four layers a minute apart, the pump clogging in layer 1, on a mix that bonds within
/// `max_interval_s` (from 30 s), re-planned by a dispatcher that knows the window.
struct LateRun {
  explicit LateRun(double max_interval_s,
                   std::filesystem::path journal = ":memory:", sim::SimOptions so = clogging(),
                   double stop_after_replans = 1e9, double joint_min_age_s = 0.0)
      : rig(with_window(so, max_interval_s), layers(), journal,
            options(max_interval_s, joint_min_age_s)) {
    for (int k = 0; k < 200'000 && !rig.dispatcher->finished() &&
                    rig.dispatcher->replans().size() < stop_after_replans;
         ++k)
      rig.run(1);
  }
  static sim::SimOptions clogging() {
    sim::SimOptions so = window(30.0, 0.0);
    so.clog_floor = 0;
    so.clog_layer = 1;
    return so;
  }
  static sim::SimOptions with_window(sim::SimOptions so, double max_interval_s) {
    so.max_interval_s = max_interval_s;
    return so;
  }
  static std::vector<DispatchJob> layers() {
    return {two_walls(10, 0, 0.0), two_walls(20, 1, 60.0), two_walls(30, 2, 120.0),
            two_walls(40, 3, 180.0)};
  }
  static DispatchOptions options(double max_interval_s, double joint_min_age_s = 0.0) {
    DispatchOptions o;
    o.joint_min_age_s = joint_min_age_s;
    o.purge_s = 120.0;
    o.min_interval_s = 30.0;
    o.max_interval_s = max_interval_s;
    o.joint_treatment_s = 50.0;
    return o;
  }
  /// Every piece end's interval to the end below it, from the machine's own record of
  /// each job (when it started, where it stopped) and the paths it was sent: (interval,
  /// laid on a planned joint).
  std::vector<std::pair<double, bool>> intervals() const {
    struct End {
      std::int64_t wall;
      double x_m, t_s;
    };
    std::map<int, std::vector<End>> laid;
    std::vector<std::pair<double, bool>> out;
    for (const std::int64_t id : rig.sim.executed()) {
      const DispatchJob& j = *rig.dispatcher->job(id);
      if (j.kind != JobKind::kDeposit) continue;
      const auto row = rig.journal.rows().at(id);
      const double started_s = rig.dispatcher->executed().at(id).first;
      std::vector<End> ends;
      for (const auto& [k, wall] : piece_ends(j.path))
        if (row.state == dispatch::JobState::kDone || static_cast<int>(k) <= row.stopped_at)
          ends.push_back({wall, j.path.x_m[k], started_s + j.path.t_s[k]});
      for (const End& e : ends)
        for (const End& b : laid[j.layer - 1])
          if (b.wall == e.wall && std::abs(b.x_m - e.x_m) < 1e-9)
            out.emplace_back(e.t_s - b.t_s, j.on_planned_joint);
      laid[j.layer].insert(laid[j.layer].end(), ends.begin(), ends.end());
    }
    return out;
  }
  Rig rig;
};

TEST(Dispatch, AClogOnATightMixEndsInPlannedJointsTreatedFirstWhereNoStartKeepsItWarm) {
  // Layer 1 clogs at x = 1 m (65 s); after the 120 s purge its rest would cover layer
  // 0's wall 2 (laid at 5 and 10 s) 180 s later, past the 100 s maximum: the top of layer
  // 0 is treated first (50 s) and the rest laid on a planned joint. Layer 2 then covers
  // ends of layer 1 laid 170 s apart, more than the 70 s the window is wide: a planned
  // joint again. Layer 3 keeps every joint within the window.
  LateRun late(100.0);
  const Dispatcher& d = *late.rig.dispatcher;
  ASSERT_TRUE(d.finished());
  ASSERT_FALSE(d.stopped()) << *d.stopped();
  // clog, purge, treatment, rest; treatment, layer 2; layer 3.
  EXPECT_EQ(late.rig.sim.executed(), (std::vector<std::int64_t>{10, 20, 21, 22, 23, 29, 30, 40}));
  ASSERT_EQ(d.replans().size(), 2u);
  EXPECT_EQ(d.replans()[0].what, "planned joint");
  EXPECT_EQ(d.replans()[0].job_id, 23);
  EXPECT_EQ(d.replans()[0].treatment_job_id, 22);
  EXPECT_DOUBLE_EQ(d.replans()[0].treatment_start_s, 185.0);  // clog 65 + purge 120
  EXPECT_DOUBLE_EQ(d.replans()[0].start_s, 235.0);
  EXPECT_EQ(d.replans()[1].job_id, 30);
  EXPECT_EQ(d.replans()[1].treatment_job_id, 29);
  // Layer 2 at 120 s + the 170 s the rest ended late, after its treatment.
  EXPECT_DOUBLE_EQ(d.replans()[1].treatment_start_s, 290.0);
  EXPECT_DOUBLE_EQ(d.replans()[1].start_s, 340.0);
  EXPECT_TRUE(contains(d.replans()[1].detail, "laid 170.0 s apart")) << d.replans()[1].detail;
  // Each treatment ran before the deposit it prepares, which started when re-planned.
  EXPECT_DOUBLE_EQ(d.executed().at(22).second, d.executed().at(23).first);
  EXPECT_DOUBLE_EQ(d.executed().at(29).second, d.executed().at(30).first);
  EXPECT_DOUBLE_EQ(d.executed().at(40).first, 400.0);  // 180 + the delay of 220 s
  // By the machine's record: every joint not on a planned one is within 30-100 s.
  int warm = 0, planned = 0;
  for (const auto& [interval_s, on_joint] : late.intervals()) {
    if (on_joint) {
      ++planned;
      continue;
    }
    ++warm;
    EXPECT_GE(interval_s, 30.0 - 1e-6);
    EXPECT_LE(interval_s, 100.0 + 1e-6);
  }
  EXPECT_GT(warm, 0);
  EXPECT_GT(planned, 0);
  EXPECT_EQ(late.rig.journal.replans().size(), 2u);
  // A treatment that needs the layer below 300 s old waits for it: wall 2's last end
  // below was laid at 10 s, so from 310 s, not 185 s.
  LateRun aged(100.0, ":memory:", LateRun::clogging(), 1e9, 300.0);
  ASSERT_FALSE(aged.rig.dispatcher->replans().empty());
  EXPECT_DOUBLE_EQ(aged.rig.dispatcher->replans()[0].treatment_start_s, 310.0);
  EXPECT_DOUBLE_EQ(aged.rig.dispatcher->executed().at(22).first, 310.0);
}

TEST(Dispatch, AClogWhoseRestStillFitsTheWindowNeedsNoPlannedJoint) {
  // With a 180 s maximum the rest (at 185 s) covers wall 2's ends (laid at 5 and 10 s)
  // exactly 180 s later, and layer 2 (at 240 s) covers layer 1's first end exactly 180 s
  // after it: both at the boundary, kept warm, nothing re-planned.
  LateRun late(180.0);
  const Dispatcher& d = *late.rig.dispatcher;
  ASSERT_TRUE(d.finished());
  ASSERT_FALSE(d.stopped()) << *d.stopped();
  EXPECT_TRUE(d.replans().empty());
  EXPECT_EQ(late.rig.sim.executed(), (std::vector<std::int64_t>{10, 20, 21, 23, 30, 40}));
  double longest_s = 0.0;
  for (const auto& [interval_s, on_joint] : late.intervals()) {
    EXPECT_FALSE(on_joint);
    longest_s = std::max(longest_s, interval_s);
  }
  EXPECT_NEAR(longest_s, 180.0, 1e-6);
  // 10 ms less and the rest is past it: treated first, laid on a planned joint.
  LateRun tighter(179.99);
  ASSERT_FALSE(tighter.rig.dispatcher->stopped()) << *tighter.rig.dispatcher->stopped();
  ASSERT_FALSE(tighter.rig.dispatcher->replans().empty());
  EXPECT_EQ(tighter.rig.dispatcher->replans()[0].job_id, 23);
  EXPECT_EQ(tighter.rig.dispatcher->replans()[0].what, "planned joint");
}

TEST(Dispatch, AClogMidPieceLeavesNoPieceEndWhereThePathStopped) {
  // One wall piece a layer, x = 0 to 2 m in 10 s; layer 1 clogs at x = 1 m (65 s), in
  // the middle of its piece: it laid x = 0 to 1 m only, and its rest (after the 120 s
  // purge) lays x = 1 to 2 m by 190 s. Layer 2, twice as slow, starts at 240 s: x = 0
  // covered 180 s after it was laid, x = 1 m (where the clogged bead ends) 185 s, the
  // maximum 186 s; the rest's stretch 65 and 70 s after. Had the clogged job been counted
  // as laying x = 1 to 2 m by 70 s, x = 2 m would be covered 190 s after it: a planned
  // joint.
  const auto piece = [](std::int64_t id, int layer, double start_s, double duration_s) {
    DispatchJob d = piece_job(id, layer, start_s);
    const double z_m = 0.1 * (layer + 1);
    d.path = {};
    d.path.push_back(0.0, 0.0, 0.0, z_m, 0.0, true, 1, 1);
    d.path.push_back(duration_s / 2, 1.0, 0.0, z_m, 0.0, true, 1, 1);
    d.path.push_back(duration_s, 2.0, 0.0, z_m, 0.0, false, 0, 0);
    d.duration_s = duration_s;
    return d;
  };
  Rig rig(LateRun::with_window(LateRun::clogging(), 186.0),
          {piece(10, 0, 0.0, 10.0), piece(20, 1, 60.0, 10.0), piece(30, 2, 120.0, 20.0)},
          ":memory:", LateRun::options(186.0));
  rig.run();
  ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
  EXPECT_TRUE(rig.dispatcher->replans().empty());
  EXPECT_DOUBLE_EQ(rig.dispatcher->executed().at(30).first, 240.0);
  EXPECT_EQ(rig.sim.executed(), (std::vector<std::int64_t>{10, 20, 21, 23, 30}));
}

/// The mix of the absorbing-wait tests: 2200 kg/m3, safety factor 1.5, its strength
/// growing linearly to what 0.2 m of wall needs at `age_s` (never, when 0).
floors::MaterialProfile mix_carrying_at(double age_s) {
  floors::MaterialProfile m;
  m.density_kg_m3 = 2200.0;
  m.safety_factor = 1.5;
  const double needed_mpa = m.strength_to_carry_mpa(0.2);
  if (age_s > 0.0)
    m.strength_curve = {{0.0, 0.0}, {2 * age_s, 2 * needed_mpa}};
  else
    m.strength_curve = {{0.0, 0.0}, {1e6, needed_mpa / 2}};
  return m;
}

/// Layer 0 (two walls, from 0 s; 0.1 m), then job 20 of `kind` (no path; about layer 1 when
/// a wait) from `start_s` for `duration_s`, then layer 1 (to 0.2 m) from `layer1_s`.
std::vector<DispatchJob> around(JobKind kind, double start_s, double duration_s,
                                DelayAbsorption absorbs, double layer1_s) {
  DispatchJob between = piece_job(20, kind == JobKind::kWait ? 1 : -1, start_s);
  between.kind = kind;
  between.duration_s = duration_s;
  between.path = {};
  between.absorbs = absorbs;
  std::vector<DispatchJob> out = {two_walls(10, 0, 0.0), between, two_walls(30, 1, layer1_s)};
  out[0].z_top_m = out[2].z_bottom_m = 0.1;
  out[2].z_top_m = 0.2;
  return out;
}

TEST(Dispatch, AWaitAbsorbsDelayAsFarAsTheLayersBelowCanCarryTheNext) {
  // Layer 0 clogs at 5 s: purged (120 s), its rest ends at 130 s, 120 s late. Layer 1 is
  // planned after a 1,000 s wait (working hours, say) at 1,010 s.
  const auto jobs = [](bool absorbs) {
    return around(JobKind::kWait, 10.0, 1000.0,
                  absorbs ? DelayAbsorption::kShortenWait : DelayAbsorption::kNone, 1010.0);
  };
  sim::SimOptions so = window(30.0, 5000.0);
  so.clog_floor = so.clog_layer = 0;
  const struct {
    double carry_age_s;  // when layer 0 can carry layer 1 (0: never)
    bool absorbs;
    double layer1_s;  // when layer 1 starts
  } cases[] = {
      {1.0, true, 1010.0},     // strong at once: all 120 s absorbed, as planned
      {950.0, true, 1080.0},   // layer 0 (ended at 130 s) carries it from 950 s on: 50 s absorbed
      {950.0, false, 1130.0},  // a wait that may not absorb: 120 s late
      {0.0, true, 1130.0},     // never strong enough: nothing absorbed
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.carry_age_s);
    const floors::MaterialProfile mix = mix_carrying_at(c.carry_age_s);
    DispatchOptions o = LateRun::options(5000.0);
    o.material = &mix;
    Rig rig(so, jobs(c.absorbs), ":memory:", o);
    rig.run();
    ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
    const Dispatcher& d = *rig.dispatcher;
    EXPECT_NEAR(d.executed().at(30).first, c.layer1_s, 1e-6);
    EXPECT_NEAR(d.executed().at(20).second, c.layer1_s, 1e-6) << "the wait ends as it starts";
    EXPECT_NEAR(d.executed().at(20).first, 130.0, 1e-6);
    if (c.layer1_s < 1130.0) {
      ASSERT_EQ(d.replans().size(), 1u);
      EXPECT_EQ(d.replans()[0].what, "absorbed");
      EXPECT_NEAR(d.replans()[0].delay_s, c.layer1_s - 1010.0, 1e-6);
      EXPECT_NEAR(d.replans()[0].duration_s, c.layer1_s - 130.0, 1e-6);
    } else {
      EXPECT_TRUE(d.replans().empty());
    }
  }
}

TEST(Dispatch, AWaitAbsorbsNoMoreThanItselfAndTheWorkAfterItKeepsItsLength) {
  // Layer 0 clogs at 5 s: its rest ends at 130 s, 120 s late. A 100 s wait from 10 s, then
  // 120 s of other work (a joint's treatment, a purge) before layer 1 at 230 s: the wait
  // is all absorbed (from 130 s, of no length), and layer 1 starts 120 s after it, at
  // 250 s, 20 s late. A wait of 200 s absorbs all 120 s: layer 1 at 330 s as planned.
  sim::SimOptions so = window(30.0, 5000.0);
  so.clog_floor = so.clog_layer = 0;
  for (const double wait_s : {100.0, 200.0}) {
    SCOPED_TRACE(wait_s);
    const double planned_s = 10.0 + wait_s + 120.0;
    const floors::MaterialProfile mix = mix_carrying_at(1.0);
    DispatchOptions o = LateRun::options(5000.0);
    o.material = &mix;
    Rig rig(so, around(JobKind::kWait, 10.0, wait_s, DelayAbsorption::kShortenWait, planned_s),
            ":memory:", o);
    rig.run();
    ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
    const Dispatcher& d = *rig.dispatcher;
    const double absorbed_s = std::min(wait_s, 120.0);
    ASSERT_EQ(d.replans().size(), 1u);
    EXPECT_EQ(d.replans()[0].what, "absorbed");
    EXPECT_NEAR(d.replans()[0].duration_s, wait_s - absorbed_s, 1e-6);
    EXPECT_NEAR(d.replans()[0].delay_s, 120.0 - absorbed_s, 1e-6);
    ASSERT_EQ(d.executed().count(20), 1u);  // the wait and layer 1 were run
    ASSERT_EQ(d.executed().count(30), 1u);
    EXPECT_NEAR(d.executed().at(20).first, 130.0, 1e-6);
    EXPECT_NEAR(d.executed().at(20).second, 130.0 + wait_s - absorbed_s, 1e-6);
    EXPECT_NEAR(d.executed().at(30).first, planned_s + 120.0 - absorbed_s, 1e-6);
  }
}

TEST(Dispatch, CrewWorkPlannedAfterASlackStartsOnceTheLateWorkBeforeItEnded) {
  // Layer 0 clogs at 5 s: purged (120 s), its rest ends at 130 s, 120 s late. A slab
  // stage (500 s of crew work) follows it, planned with slack before it (the next working
  // hours, say), and layer 1 10 s after the slab.
  const auto jobs = [](double slab_s, bool absorbs) {
    return around(JobKind::kSlab, slab_s, 500.0,
                  absorbs ? DelayAbsorption::kStartWhenReady : DelayAbsorption::kNone,
                  slab_s + 510.0);
  };
  sim::SimOptions so = window(30.0, 5000.0);
  so.clog_floor = so.clog_layer = 0;
  const struct {
    double slab_s;       // planned start of the slab stage
    double carry_age_s;  // when layer 0 can carry layer 1 (0: never)
    bool absorbs;
    double slab_from_s;  // when the slab stage starts
  } cases[] = {
      {1000.0, 1.0, true, 1000.0},     // a slack longer than the delay: on time again
      {130.0, 1.0, true, 130.0},       // a slack exactly the delay: on time again
      {70.0, 1.0, true, 130.0},        // 60 s of slack: 60 s late after it
      {1000.0, 1.0, false, 1120.0},    // work that may not absorb: 120 s late
      {1000.0, 1420.0, true, 1040.0},  // layer 1 carried from 1,550 s: 40 s late after it
      {1000.0, 0.0, true, 1120.0},     // never strong enough: nothing absorbed
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(::testing::Message() << c.slab_s << " " << c.carry_age_s << " " << c.absorbs);
    const floors::MaterialProfile mix = mix_carrying_at(c.carry_age_s);
    DispatchOptions o = LateRun::options(5000.0);
    o.material = &mix;
    Rig rig(so, jobs(c.slab_s, c.absorbs), ":memory:", o);
    rig.run();
    ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
    const Dispatcher& d = *rig.dispatcher;
    EXPECT_NEAR(d.executed().at(20).first, c.slab_from_s, 1e-6);
    EXPECT_NEAR(d.executed().at(20).second, c.slab_from_s + 500.0, 1e-6) << "as long as planned";
    EXPECT_NEAR(d.executed().at(30).first, c.slab_from_s + 510.0, 1e-6);
    const double late_s = c.slab_from_s - c.slab_s;
    EXPECT_NEAR(d.delay_s(), late_s, 1e-6);
    if (late_s < 120.0) {
      ASSERT_EQ(d.replans().size(), 1u);
      EXPECT_EQ(d.replans()[0].what, "absorbed");
      EXPECT_EQ(d.replans()[0].job_id, 20);
      EXPECT_NEAR(d.replans()[0].delay_s, late_s, 1e-6);
    } else {
      EXPECT_TRUE(d.replans().empty());
    }
  }
}

TEST(Dispatch, ALayerThatWouldCoverAPieceEndTooSoonStartsLater) {
  // Planned 25 s after the layer below, under the 30 s minimum: started 5 s later (the
  // machine would refuse it). Planned at exactly 30 s: as planned.
  for (const double planned_s : {25.0, 30.0}) {
    Rig rig(window(30.0, 100.0), {piece_job(10, 0, 0.0), piece_job(20, 1, planned_s)},
            ":memory:", LateRun::options(100.0));
    rig.run();
    ASSERT_FALSE(rig.dispatcher->stopped()) << *rig.dispatcher->stopped();
    EXPECT_DOUBLE_EQ(rig.dispatcher->executed().at(20).first, 30.0) << planned_s;
    EXPECT_EQ(rig.dispatcher->replans().size(), planned_s < 30.0 ? 1u : 0u);
    if (planned_s < 30.0) {
      EXPECT_EQ(rig.dispatcher->replans()[0].what, "later");
      EXPECT_DOUBLE_EQ(rig.dispatcher->delay_s(), 5.0);
    }
  }
}

TEST(RunReport, ALayerIsOffItsPlanFromOverASecond) {
  // Layer 1, planned 30 s after layer 0, re-planned later to the minimum interval: 1 s
  // late is on plan, 1.01 s late is off it.
  for (const double min_s : {31.0, 31.01}) {
    DispatchOptions o = LateRun::options(100.0);
    o.min_interval_s = min_s;
    Rig rig(window(min_s, 100.0), {piece_job(10, 0, 0.0), piece_job(20, 1, 30.0)}, ":memory:", o);
    rig.run();
    ASSERT_TRUE(rig.dispatcher->finished());
    const RunReport r = report_of(*rig.dispatcher);
    ASSERT_EQ(r.layers.size(), 2u);
    EXPECT_NEAR(r.layers[1].deviation_s(), min_s - 30.0, 1e-9);
    EXPECT_EQ(r.layers[1].off_plan(), min_s > 31.0);
    EXPECT_EQ(r.off_plan, min_s > 31.0 ? 1 : 0);
    ASSERT_EQ(r.floors.size(), 1u);
    EXPECT_EQ(r.floors[0].layers, 2);
    EXPECT_NEAR(r.floors[0].worst_s, min_s - 30.0, 1e-9);
    EXPECT_NEAR(r.floors[0].ended_s, min_s + 5.0, 1e-9);
    EXPECT_NEAR(r.finished_s, min_s + 5.0, 1e-9);
    EXPECT_EQ(r.later, 1);
  }
}

TEST(RunReport, CountsTheRecoveryJobsThatRanAndTheLayersThatDidNot) {
  // The clog in layer 1 is purged (a purge the schedule did not plan); stopped after the
  // first re-plan, layers 2 and 3 never ran.
  LateRun late(100.0, ":memory:", LateRun::clogging(), 1);
  const RunReport r = report_of(*late.rig.dispatcher);
  EXPECT_EQ(r.crew_and_climber.at("purges").planned, 0);
  EXPECT_EQ(r.crew_and_climber.at("purges").ran, 1);
  ASSERT_EQ(r.layers.size(), 4u);
  EXPECT_EQ(r.not_run, 2);
  EXPECT_FALSE(r.layers[3].ran());
  EXPECT_DOUBLE_EQ(r.layers[3].deviation_s(), 0.0);
  EXPECT_EQ(r.planned_joints, 1);
  EXPECT_EQ(r.treatments_ran, 0);
}

TEST(Dispatch, ARestartedDispatcherReplansIdenticallyFromItsJournal) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_replan_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  sim::SimOptions so = LateRun::clogging();
  so.state_file = dir / "gantry-1.state";
  std::vector<Replan> first;
  std::vector<DispatchJob> made;
  {
    // "Killed" once the first re-plan is journalled.
    LateRun late(100.0, dir / "journal.sqlite", so, 1);
    ASSERT_EQ(late.rig.dispatcher->replans().size(), 1u);
    first = late.rig.dispatcher->replans();
    made = late.rig.dispatcher->jobs();
  }
  so.clog_floor = -1;
  LateRun again(100.0, dir / "journal.sqlite", so);
  const Dispatcher& d = *again.rig.dispatcher;
  ASSERT_FALSE(d.stopped()) << *d.stopped();
  ASSERT_EQ(d.replans().size(), 2u);
  EXPECT_EQ(d.replans()[0].job_id, first[0].job_id);
  EXPECT_EQ(d.replans()[0].treatment_job_id, first[0].treatment_job_id);
  EXPECT_DOUBLE_EQ(d.replans()[0].start_s, first[0].start_s);
  EXPECT_DOUBLE_EQ(d.replans()[0].treatment_start_s, first[0].treatment_start_s);
  // The same jobs as before the restart, then the same second re-plan as in one run.
  for (const DispatchJob& j : made) {
    const DispatchJob* now = d.job(j.job_id);
    ASSERT_NE(now, nullptr) << j.job_id;
    EXPECT_EQ(now->kind, j.kind) << j.job_id;
    EXPECT_DOUBLE_EQ(now->start_s, j.start_s) << j.job_id;
  }
  EXPECT_TRUE(d.job(23)->on_planned_joint);
  EXPECT_DOUBLE_EQ(d.replans()[1].start_s, 340.0);
  const auto& ran = again.rig.sim.executed();
  EXPECT_EQ(std::set<std::int64_t>(ran.begin(), ran.end()).size(), ran.size()) << "a job ran twice";
  EXPECT_EQ(ran.size(), 8u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::dispatch
