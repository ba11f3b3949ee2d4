// The dispatch groundwork: a schedule's jobs (every layer's path for each nozzle, in
// chunks under 64 kB, nothing lost or reordered; the events as whole-machine jobs) and
// the typed bus over memq:// (messages delivered, malformed ones counted, never handed on).

#include "ccbuild/dispatch/dispatch_jobs.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include <lcm/lcm-cpp.hpp>

#include "ccbuild/dispatch/dispatcher.hpp"
#include "ccbuild/dispatch/job_messages.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/sim/sim_machine.hpp"
#include "ccbuild/wire/bus.hpp"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"
#include "test_support.hpp"

namespace ccbuild::dispatch {
namespace {
using schedule::build_schedule;
using schedule::open_project;
using schedule::Project;
using schedule::recorded_inputs;
using schedule::ScheduledLayer;
using schedule::ScheduleDocument;
using schedule::ScheduleOptions;
using schedule::SchedulePlan;

using ccbuild_lcm::ccbuild_job_t;
using ccbuild_lcm::ccbuild_path_chunk_t;

const ScheduleDocument& house_schedule() {
  static const ScheduleDocument doc = [] {
    const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
    ScheduleOptions o;
    o.max_kicks = 200;
    return ScheduleDocument{recorded_inputs(house, o), build_schedule(house, o)};
  }();
  return doc;
}

TEST(DispatchJobs, EveryLayerPathGoesOutWholeAndInOrder) {
  const ScheduleDocument& s = house_schedule();
  const auto jobs = jobs_of_schedule(s);
  int deposits = 0, slabs = 0, purges = 0, joints = 0;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const JobMessages sent = messages_of(jobs[k]);  // as they go on the wire
    const auto& j = sent.job;
    EXPECT_EQ(j.job_id, static_cast<std::int64_t>(10 * (k + 1)));
    if (k > 0) {
      EXPECT_LE(jobs[k - 1].start_s, j.start_s);  // schedule order
    }
    EXPECT_EQ(static_cast<int>(sent.chunks.size()), j.chunk_count);
    slabs += j.kind == ccbuild_job_t::SLAB;
    purges += j.kind == ccbuild_job_t::PURGE;
    if (j.kind != ccbuild_job_t::DEPOSIT) continue;
    ++deposits;
    // The chunks put back together are the plan's waypoints, at this layer's height.
    const ScheduledLayer* layer = nullptr;
    for (const auto& l : s.schedule.layers)
      if (l.floor == j.floor && l.layer == j.layer) layer = &l;
    // A layer on a planned joint (after the stop for lintels) says so on the wire.
    if (layer) {
      EXPECT_EQ(j.on_planned_joint, layer->planned_joint);
    }
    joints += j.on_planned_joint;
    ASSERT_NE(layer, nullptr);
    const SchedulePlan& plan = s.schedule.plans.at(j.plan);
    const auto& path = plan.waypoints.at(j.nozzle);
    ASSERT_EQ(j.point_count, static_cast<int>(path.size()));
    int at = 0;
    for (const auto& c : sent.chunks) {
      EXPECT_EQ(c.job_id, j.job_id);
      EXPECT_LE(c.n, ccbuild_path_chunk_t::MAX_POINTS);
      EXPECT_LE(c.getEncodedSize(), 64'000);
      for (int p = 0; p < c.n; ++p, ++at) {
        EXPECT_EQ(c.t_s[p], path[at].t_s);
        EXPECT_EQ(c.wall[p], path[at].wall);
        EXPECT_NEAR(c.z_m[p], path[at].z_m - plan.z_top_m + layer->z_top_m, 1e-9);
      }
    }
    EXPECT_EQ(at, j.point_count);
    EXPECT_DOUBLE_EQ(j.start_s, layer->start_s);
  }
  EXPECT_EQ(deposits, 60);  // one nozzle, 60 layers
  EXPECT_EQ(slabs, 1);
  // A purge job where the schedule purges: after the slab, and after the stops for lintels.
  const auto purged = std::count_if(s.schedule.layers.begin(), s.schedule.layers.end(),
                                    [](const auto& l) { return l.purge_before; });
  EXPECT_GE(purged, 2);
  EXPECT_EQ(joints, 2);  // one nozzle: the layer over each floor's lintels
  EXPECT_EQ(purges, purged);
}

TEST(DispatchJobs, PathsSplitIntoChunksAtTheirBoundary) {
  // A one-layer schedule whose path has exactly MAX_POINTS waypoints, then one more.
  const int most = ccbuild_path_chunk_t::MAX_POINTS;
  for (int points : {most, most + 1}) {
    ScheduleDocument s;
    SchedulePlan plan;
    plan.key = "g1n1";
    plan.z_top_m = 0.1;
    plan.waypoints.resize(1);
    for (int k = 0; k < points; ++k) {
      planner::Waypoint w;
      w.t_s = k * 1.0;
      w.position_m = {k * 0.01, 0.0};
      w.z_m = 0.1;
      w.extruding = k + 1 < points;
      w.wall = 1;
      w.piece = 1;
      plan.waypoints[0].push_back(w);
    }
    s.schedule.plans["g1n1"] = plan;
    ScheduledLayer layer;
    layer.plan = "g1n1";
    layer.z_top_m = 0.1;
    s.schedule.layers.push_back(layer);
    const auto jobs = jobs_of_schedule(s);
    ASSERT_EQ(jobs.size(), 1u);
    const int expected = points == most ? 1 : 2;
    const JobMessages sent = messages_of(jobs[0]);
    EXPECT_EQ(sent.job.chunk_count, expected) << points;
    EXPECT_EQ(sent.chunks.back().n, expected == 1 ? points : 1);
    EXPECT_EQ(sent.chunks.back().chunk_index, expected - 1);
  }
  // A layer whose plan is missing is an input error, not a crash.
  ScheduleDocument broken;
  broken.schedule.layers.emplace_back().plan = "g9n1";
  EXPECT_EQ(testing::expect_input_error([&] { jobs_of_schedule(broken); }).first().field,
            "schedule");
}

TEST(Bus, DeliversTypedMessagesAndCountsMalformedOnes) {
  wire::Bus bus("memq://");
  std::vector<std::int64_t> received;
  bus.subscribe<ccbuild_job_t>(wire::channel("JOB", "gantry-1"),
                               [&](const ccbuild_job_t& j) { received.push_back(j.job_id); });
  std::vector<std::string> malformed;
  bus.on_malformed([&](const std::string& ch, int) { malformed.push_back(ch); });
  const JobMessages first = messages_of(jobs_of_schedule(house_schedule())[0]);
  bus.publish(wire::channel("JOB", "gantry-1"), first.job);
  bus.publish(wire::channel("JOB", "gantry-1"), first.chunks[0]);  // the wrong type
  EXPECT_GE(bus.handle(500), 2);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0], first.job.job_id);
  EXPECT_EQ(bus.malformed_count(), 1);
  ASSERT_EQ(malformed.size(), 1u);
  EXPECT_EQ(malformed[0], "CCBUILD_JOB_gantry-1");
  EXPECT_EQ(testing::expect_input_error([] { wire::Bus("nosuch://x"); }).first().field,
            "--lcm-url");
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("ccbuild_dispatch_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Steps the dispatcher and the machine on one memq:// bus, a millisecond of real time a
// step, until the dispatcher is done or `steps` have passed.
void run(wire::Bus& bus, Dispatcher& d, sim::SimMachine& sim, int steps) {
  for (int k = 0; k < steps && !d.finished(); ++k) {
    d.step(1e-3);
    bus.handle(0);
    sim.step(1e-3);
    bus.handle(0);
  }
}

TEST(Dispatch, TheHouseRunsEveryJobExactlyOnceInOrder) {
  const auto dir = scratch("once");
  wire::Bus bus("memq://");
  const auto jobs = jobs_of_schedule(house_schedule());
  Journal journal(dir / "journal.sqlite");
  sim::SimOptions so;
  so.speed = 1e6;
  so.state_file = dir / "gantry-1.state";
  sim::SimMachine sim(bus, so);
  DispatchOptions o;
  o.speed = so.speed;
  Dispatcher d(bus, jobs, journal, o);
  run(bus, d, sim, 100'000);
  ASSERT_TRUE(d.finished());
  // The machine's own record: every job once, in schedule order.
  ASSERT_EQ(sim.executed().size(), jobs.size());
  for (std::size_t k = 0; k < jobs.size(); ++k) EXPECT_EQ(sim.executed()[k], jobs[k].job_id);
  for (const auto& [id, state] : journal.states())
    EXPECT_EQ(state, dispatch::JobState::kDone) << id;
  // Each job started no earlier than planned and ran for its planned duration.
  for (const auto& j : jobs) {
    const auto& [start_s, end_s] = d.executed().at(j.job_id);
    EXPECT_GE(start_s, j.start_s - 1e-6);
    EXPECT_NEAR(end_s - start_s, j.duration_s, 1e-6);
  }
  EXPECT_EQ(sim.faults(), 0);
  std::filesystem::remove_all(dir);
}

TEST(Dispatch, ARestartedDispatcherAndMachineLoseNothingAndRunNothingTwice) {
  const auto dir = scratch("resume");
  wire::Bus bus("memq://");
  const auto jobs = jobs_of_schedule(house_schedule());
  sim::SimOptions so;
  so.speed = 1e6;
  so.state_file = dir / "gantry-1.state";
  DispatchOptions o;
  o.speed = so.speed;
  o.ack_timeout_s = 0.01;
  o.done_slack_s = 0.01;
  auto sim = std::make_unique<sim::SimMachine>(bus, so);
  {
    Journal journal(dir / "journal.sqlite");
    Dispatcher first(bus, jobs, journal, o);
    run(bus, first, *sim, 40);  // part of the way, then "killed"
    ASSERT_FALSE(first.finished());
  }
  const std::size_t before = sim->executed().size();
  ASSERT_GT(before, 0u);
  // The machine restarts from its state file too.
  wire::Bus bus2("memq://");
  sim = std::make_unique<sim::SimMachine>(bus2, so);
  EXPECT_EQ(sim->executed().size(), before);
  Journal journal(dir / "journal.sqlite");
  Dispatcher second(bus2, jobs, journal, o);
  run(bus2, second, *sim, 100'000);
  ASSERT_TRUE(second.finished());
  const auto& ran = sim->executed();
  EXPECT_EQ(std::set<std::int64_t>(ran.begin(), ran.end()).size(), ran.size()) << "a job ran twice";
  EXPECT_EQ(ran.size(), jobs.size()) << "a job was lost";
  std::filesystem::remove_all(dir);
}

TEST(Journal, BelongsToTheScheduleItWasWrittenFor) {
  const auto dir = scratch("journal");
  const std::string mine(64, 'a'), other(64, 'b');
  const auto path = dir / "journal.sqlite";
  {
    Journal journal(path, mine);
    journal.record(10, "gantry-1", dispatch::JobState::kDone);
  }
  {
    Journal again(path, mine);  // the same schedule resumes
    EXPECT_EQ(again.states().at(10), dispatch::JobState::kDone);
  }
  const InputError e = testing::expect_input_error([&] { Journal(path, other); });
  EXPECT_EQ(e.first().field, "--journal");
  EXPECT_TRUE(testing::contains(e.what(), "belongs to another schedule (SHA-256 aaaaaaaaaaaa"));
  // A journal with records but no schedule named (an older ccbuild's): not guessed.
  const auto old = dir / "old.sqlite";
  { Journal(old).record(10, "gantry-1", dispatch::JobState::kDone); }
  EXPECT_TRUE(testing::contains(testing::expect_input_error([&] { Journal(old, mine); }).what(),
                                "names no schedule"));
  // An empty one takes the schedule given.
  { Journal(dir / "new.sqlite"); }
  { Journal(dir / "new.sqlite", other); }
  EXPECT_TRUE(testing::contains(
      testing::expect_input_error([&] { Journal(dir / "new.sqlite", mine); }).what(),
      "another schedule"));
  std::filesystem::remove_all(dir);
}

// A job's state is one of the journal's words, each read back as what it says; a word the
// journal never writes (a hand edit, another program's row) is refused with the job, not
// taken for a state the dispatcher would act on.
TEST(Journal, EachStateReadsBackAndAnUnknownWordIsRefused) {
  const auto dir = scratch("journal-states");
  const auto path = dir / "journal.sqlite";
  const std::vector<JobState> all = {JobState::kSent,  JobState::kAcked,   JobState::kRefused,
                                     JobState::kDone,  JobState::kClogged, JobState::kPinMissed,
                                     JobState::kFailed};
  {
    Journal journal(path);
    for (std::size_t k = 0; k < all.size(); ++k) journal.record(10 * (k + 1), "gantry-1", all[k]);
  }
  {
    Journal again(path);
    const auto states = again.states();
    for (std::size_t k = 0; k < all.size(); ++k)
      EXPECT_EQ(states.at(10 * (k + 1)), all[k]) << to_string(all[k]);
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE job_state SET state = 'finished' WHERE job_id = 40", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  Journal damaged(path);
  const InputError e = testing::expect_input_error([&] { damaged.states(); });
  EXPECT_EQ(e.first().field, "job_state");
  EXPECT_TRUE(testing::contains(e.what(), "job 40 has the state 'finished'")) << e.what();
  std::filesystem::remove_all(dir);
}

TEST(Dispatch, AMachineRefusesJobsOutOfOrderAndPathsThatDoNotAddUp) {
  wire::Bus bus("memq://");
  auto jobs = jobs_of_schedule(house_schedule());
  sim::SimOptions so;
  so.speed = 1e9;
  sim::SimMachine sim(bus, so);
  std::vector<std::int8_t> faults;
  bus.subscribe<ccbuild_lcm::ccbuild_fault_t>(
      wire::channel("FAULT", "gantry-1"),
      [&](const ccbuild_lcm::ccbuild_fault_t& f) { faults.push_back(f.kind); });
  std::int64_t seq = 0;
  auto send = [&](JobMessages d) {
    d.job.utime = wire::utime_now();
    d.job.seq = ++seq;
    bus.publish(wire::channel("JOB", "gantry-1"), d.job);
    for (auto& c : d.chunks) {
      c.utime = d.job.utime;
      c.seq = ++seq;
      bus.publish(wire::channel("PATH", "gantry-1"), c);
    }
    bus.handle(0);
    for (int k = 0; k < 5; ++k) {
      sim.step(1.0);
      bus.handle(0);
    }
  };
  send(messages_of(jobs[2]));
  ASSERT_EQ(sim.executed().size(), 1u);
  send(messages_of(jobs[1]));  // older than the one run: refused
  EXPECT_EQ(sim.executed().size(), 1u);
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0], +ccbuild_lcm::ccbuild_fault_t::OUT_OF_ORDER);
  JobMessages short_path = messages_of(jobs[3]);
  short_path.job.point_count += 1;  // one waypoint missing from its chunks
  send(short_path);
  EXPECT_EQ(sim.executed().size(), 1u);
  ASSERT_EQ(faults.size(), 2u);
  EXPECT_EQ(faults[1], +ccbuild_lcm::ccbuild_fault_t::PATH_MISMATCH);
  send(messages_of(jobs[2]));  // a repeat of one it ran: acknowledged, not run again
  EXPECT_EQ(sim.executed().size(), 1u);
  EXPECT_EQ(faults.size(), 2u);
}

}  // namespace
}  // namespace ccbuild::dispatch

namespace ccbuild::dispatch {
namespace {

// The apartment block on three gantries: some layers use one or two. An idle gantry first
// parks at the far end of the rails (a travel job of its own, each a gantry width from the
// next), and comes back from there: every gantry's jobs join up, none jumps.
TEST(DispatchJobs, AGantryIdleForALayerParksAtTheFarEndAndComesBackFromThere) {
  const Project apartment = open_project(testing::source_path("config/buildings/apartment.yaml"));
  ScheduleOptions o;
  o.max_kicks = 200;
  const ScheduleDocument doc{recorded_inputs(apartment, o), build_schedule(apartment, o)};
  const auto& m = doc.inputs.machine;
  ASSERT_EQ(m.nozzles, 3);
  const auto jobs = jobs_of_schedule(doc);
  int parks = 0;
  for (int g = 0; g < m.nozzles; ++g) {
    const std::string id = gantry_id(g);
    const double park_m = m.x_max_m - (m.nozzles - 1 - g) * m.gantry_width_m;
    std::optional<std::array<double, 2>> at;  // where its last job left it (x, y)
    for (const auto& j : jobs) {
      if (j.machine_id != id || j.path.size() == 0) continue;
      const std::size_t last = j.path.size() - 1;
      if (at) {
        EXPECT_NEAR(j.path.x_m[0], (*at)[0], 1e-9) << j.detail;
        EXPECT_NEAR(j.path.y_m[0], (*at)[1], 1e-9) << j.detail;
      }
      at = std::array<double, 2>{j.path.x_m[last], j.path.y_m[last]};
      if (j.detail.find("parks clear") == std::string::npos) continue;
      ++parks;
      EXPECT_EQ(j.kind, JobKind::kTravel);
      EXPECT_DOUBLE_EQ(j.path.x_m[last], park_m) << j.detail;
      // At the rail axis's speed, no faster.
      EXPECT_GE(j.duration_s * m.x_speed_m_s + 1e-9, std::abs(j.path.x_m[last] - j.path.x_m[0]))
          << j.detail;
    }
  }
  EXPECT_GT(parks, 0) << "the apartment has layers on fewer gantries than it has";
  // No layer on fewer gantries reaches into the parks of the idle ones.
  for (const auto& [key, plan] : doc.schedule.plans)
    for (const auto& path : plan.waypoints)
      for (const auto& w : path)
        EXPECT_LE(w.position_m.x(),
                  m.x_max_m -
                      (m.nozzles - static_cast<int>(plan.waypoints.size())) * m.gantry_width_m +
                      1e-6)
            << key;
}

}  // namespace
}  // namespace ccbuild::dispatch
