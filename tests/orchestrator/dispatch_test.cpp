// The dispatch groundwork: a schedule's jobs (every layer's path for each nozzle, in
// chunks under 64 kB, nothing lost or reordered; the events as whole-machine jobs) and
// the typed bus over memq:// (messages delivered, malformed ones counted, never handed on).

#include "ccbuild/orchestrator/dispatch_jobs.hpp"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include "ccbuild/machine/bus.hpp"
#include "ccbuild/orchestrator/schedule.hpp"
#include "ccbuild/orchestrator/schedule_json.hpp"
#include "test_support.hpp"

namespace ccbuild::orchestrator {
namespace {

using ccbuild_lcm::ccbuild_job_t;
using ccbuild_lcm::ccbuild_path_chunk_t;

nlohmann::json house_schedule() {
  static const nlohmann::json doc = [] {
    const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
    ScheduleOptions o;
    o.max_kicks = 200;
    return nlohmann::json(schedule_json(house, o, build_schedule(house, o)));
  }();
  return doc;
}

TEST(DispatchJobs, EveryLayerPathGoesOutWholeAndInOrder) {
  const nlohmann::json s = house_schedule();
  const auto jobs = jobs_of_schedule(s);
  int deposits = 0, slabs = 0, purges = 0;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const auto& j = jobs[k].job;
    EXPECT_EQ(j.job_id, static_cast<std::int64_t>(k + 1));
    if (k > 0) {
      EXPECT_LE(jobs[k - 1].job.start_s, j.start_s);  // schedule order
    }
    EXPECT_EQ(static_cast<int>(jobs[k].chunks.size()), j.chunk_count);
    slabs += j.kind == ccbuild_job_t::SLAB;
    purges += j.kind == ccbuild_job_t::PURGE;
    if (j.kind != ccbuild_job_t::DEPOSIT) continue;
    ++deposits;
    // The chunks put back together are the plan's waypoints, at this layer's height.
    const nlohmann::json* layer = nullptr;
    for (const auto& l : s["layers"])
      if (l["floor"] == j.floor && l["layer"] == j.layer) layer = &l;
    ASSERT_NE(layer, nullptr);
    const auto& plan = s["plans"][j.plan];
    const auto& path = plan["nozzles"][j.nozzle]["waypoints"];
    ASSERT_EQ(j.point_count, static_cast<int>(path.size()));
    int at = 0;
    for (const auto& c : jobs[k].chunks) {
      EXPECT_EQ(c.job_id, j.job_id);
      EXPECT_LE(c.n, ccbuild_path_chunk_t::MAX_POINTS);
      EXPECT_LE(c.getEncodedSize(), 64'000);
      for (int p = 0; p < c.n; ++p, ++at) {
        EXPECT_EQ(c.t_s[p], path[at]["t_s"].get<double>());
        EXPECT_EQ(c.wall[p], path[at]["wall"].get<std::int64_t>());
        EXPECT_NEAR(c.z_m[p],
                    path[at]["z_m"].get<double>() - plan["z_top_m"].get<double>() +
                        (*layer)["z_m"].get<double>(),
                    1e-9);
      }
    }
    EXPECT_EQ(at, j.point_count);
    EXPECT_DOUBLE_EQ(j.start_s, (*layer)["start_s"].get<double>());
  }
  EXPECT_EQ(deposits, 60);  // one nozzle, 60 layers
  EXPECT_EQ(slabs, 1);
  EXPECT_EQ(purges, 1);
}

TEST(DispatchJobs, PathsSplitIntoChunksAtTheirBoundary) {
  // A one-layer schedule whose path has exactly MAX_POINTS waypoints, then one more.
  const int most = ccbuild_path_chunk_t::MAX_POINTS;
  for (int points : {most, most + 1}) {
    nlohmann::json path = nlohmann::json::array();
    for (int k = 0; k < points; ++k)
      path.push_back({{"t_s", k * 1.0},
                      {"x_m", k * 0.01},
                      {"y_m", 0.0},
                      {"z_m", 0.1},
                      {"heading_rad", 0.0},
                      {"extruding", k + 1 < points},
                      {"wall", 1},
                      {"piece", 1}});
    nlohmann::json s = {
        {"layers",
         {{{"floor", 0}, {"layer", 0}, {"plan", "g1n1"}, {"start_s", 0.0}, {"z_m", 0.1}}}},
        {"plans",
         {{"g1n1", {{"z_top_m", 0.1}, {"nozzles", {{{"nozzle", 0}, {"waypoints", path}}}}}}}},
        {"events", nlohmann::json::array()}};
    const auto jobs = jobs_of_schedule(s);
    ASSERT_EQ(jobs.size(), 1u);
    const int expected = points == most ? 1 : 2;
    EXPECT_EQ(jobs[0].job.chunk_count, expected) << points;
    EXPECT_EQ(jobs[0].chunks.back().n, expected == 1 ? points : 1);
    EXPECT_EQ(jobs[0].chunks.back().chunk_index, expected - 1);
  }
  // A schedule without what jobs need is an input error, not a crash.
  EXPECT_EQ(
      testing::expect_input_error([] { jobs_of_schedule(nlohmann::json::object()); }).first().field,
      "schedule");
}

TEST(Bus, DeliversTypedMessagesAndCountsMalformedOnes) {
  machine::Bus bus("memq://");
  std::vector<std::int64_t> received;
  bus.subscribe<ccbuild_job_t>(machine::channel("JOB", "gantry-1"),
                               [&](const ccbuild_job_t& j) { received.push_back(j.job_id); });
  std::vector<std::string> malformed;
  bus.on_malformed([&](const std::string& ch, int) { malformed.push_back(ch); });
  auto jobs = jobs_of_schedule(house_schedule());
  bus.publish(machine::channel("JOB", "gantry-1"), jobs[0].job);
  bus.publish(machine::channel("JOB", "gantry-1"), jobs[0].chunks[0]);  // the wrong type
  EXPECT_GE(bus.handle(500), 2);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0], jobs[0].job.job_id);
  EXPECT_EQ(bus.malformed_count(), 1);
  ASSERT_EQ(malformed.size(), 1u);
  EXPECT_EQ(malformed[0], "CCBUILD_JOB_gantry-1");
  EXPECT_EQ(testing::expect_input_error([] { machine::Bus("nosuch://x"); }).first().field,
            "--lcm-url");
}

}  // namespace
}  // namespace ccbuild::orchestrator
