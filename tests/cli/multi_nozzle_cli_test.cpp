// plan-layer --nozzles and sweep end to end.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::run_ccbuild;

TEST(MultiNozzleCli, HouseWithTwoNozzlesInJson) {
  const auto r = run_ccbuild(
      "plan-layer config/buildings/house.yaml --floor 0 --layer 12 --nozzles 2 "
      "--gantry-width 5ft --objective time --max-kicks 300 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "solved");
  EXPECT_EQ(j["status_reason"], "");
  EXPECT_LT(j["layer_time_s"].get<double>(), j["single_nozzle_layer_time_s"].get<double>());
  EXPECT_GE(j["min_gap_m"].get<double>(), j["gantry_width_m"].get<double>() - 1e-9);
  EXPECT_NEAR(j["gantry_width_m"].get<double>(), 1.524, 1e-9);
  ASSERT_EQ(j["stages"].size(), 1u);
  const auto& stage = j["stages"][0];
  EXPECT_TRUE(stage["method"].is_string());
  EXPECT_TRUE(stage.contains("faster_delay_s"));  // null unless delay would have been faster
  ASSERT_EQ(stage["nozzles"].size(), 2u);
  std::size_t walls = 0;
  for (const auto& n : stage["nozzles"]) {
    for (const char* key : {"section_m", "sequence", "start_offset", "busy_s", "wait_s", "finish_s",
                            "zones", "waypoints"})
      EXPECT_TRUE(n.contains(key)) << key;
    walls += n["sequence"].size();
  }
  EXPECT_GE(walls, 69u);  // every wall piece, plus pieces cut at the section border
}

TEST(MultiNozzleCli, TextAndDrawing) {
  const fs::path svg =
      fs::temp_directory_path() / ("ccbuild_multi_" + std::to_string(::getpid()) + ".svg");
  const auto r = run_ccbuild(
      "plan-layer config/buildings/house.yaml --floor 1 --layer 5 --nozzles 3 --gantry-width 1m "
      "--rail-axis y --max-kicks 200 --svg " +
      svg.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "3 nozzles on y rails"));
  EXPECT_TRUE(contains(r.out, "collision-free"));
  EXPECT_TRUE(contains(r.out, "nozzle 3"));
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(contains(text.str(), "over time"));
  fs::remove(svg);
}

TEST(MultiNozzleCli, ATimeLimitIsACapNotAnAnytimeSearch) {
  // Before, --time-limit made each section search until the limit, and no method was
  // left time to find a plan; now the answer is the one without the limit.
  const std::string args =
      "plan-layer config/buildings/apartment.yaml --layer 10 --nozzles 2 --gantry-width 5ft";
  const auto plain = run_ccbuild(args);
  const auto capped = run_ccbuild(args + " --time-limit 5");
  ASSERT_EQ(plain.exit_code, 0) << plain.out;
  ASSERT_EQ(capped.exit_code, 0) << capped.out;
  EXPECT_TRUE(contains(capped.out, "method        path-cycling")) << capped.out;
  auto layer_time = [](const std::string& out) {
    return out.substr(out.find("layer time"),
                      out.find('\n', out.find("layer time")) - out.find("layer time"));
  };
  EXPECT_EQ(layer_time(capped.out), layer_time(plain.out));
}

TEST(MultiNozzleCli, NoPlanIsAnAnswerWithExitOne) {
  const auto r = run_ccbuild(
      "plan-layer tests/data/plans/narrow_room.txt --nozzles 2 --gantry-width 3.5 "
      "--method path-cycling");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.out, "none found"));
  EXPECT_TRUE(contains(r.out, "path-cycling: collision: no combination"));
  // auto falls back to waits, turns or parking and succeeds.
  EXPECT_EQ(
      run_ccbuild("plan-layer tests/data/plans/narrow_room.txt --nozzles 2 --gantry-width 3.5")
          .exit_code,
      0);
}

TEST(MultiNozzleCli, BadParametersExitTwo) {
  struct Case {
    const char* args;
    const char* message;
  };
  const Case cases[] = {
      {"--nozzles 2", "--gantry-width: is required"},
      {"--nozzles 2 --gantry-width 0", "--gantry-width: must be more than 0"},
      {"--nozzles 2 --gantry-width five", "expected a length"},
      {"--nozzles 16 --gantry-width 15ft", "--nozzles: 16 gantries 4.57 m wide do not fit"},
      {"--nozzles 30 --gantry-width 1ft", "--nozzles: must be from 1 to 16, got 30"},
      {"--nozzles 3 --gantry-width 5ft --platform-width 2ft", "--platform-width: 3 gantries"},
      {"--gantry-width 5ft", "--gantry-width: applies only with --nozzles 2 or more"},
      {"--nozzles 2 --gantry-width 1 --start-vertex 1", "closed tours"},
      {"--nozzles 2 --gantry-width 1 --algorithm exact",
       "--algorithm: exact plans one nozzle; with --nozzles every section is planned by cc-tsp"},
      {"--nozzles 2 --gantry-width 1 --algorithm nearest", "--algorithm: nearest plans one nozzle"},
      {"--nozzles 2 --gantry-width 1 --method sideways", "sideways"},
      {"--nozzles 2 --gantry-width 1 --rail-axis z", "z"},
      {"--nozzles 0", "--nozzles: must be from 1 to 16, got 0"},
  };
  for (const auto& c : cases) {
    const auto r = run_ccbuild(std::string("plan-layer tests/data/plans/cottage.yaml ") + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_TRUE(contains(r.err, c.message)) << c.args << ": " << r.err;
  }
}

TEST(MultiNozzleCli, AFeetBuildingHearsFeet) {
  const auto r =
      run_ccbuild("plan-layer config/buildings/apartment.yaml --nozzles 16 --gantry-width 15ft");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "16 gantries 15.00 ft wide do not fit on the machine's 209.97 ft"))
      << r.err;
}

TEST(MultiNozzleCli, SweepWritesTheTableAndReportsProgress) {
  const fs::path csv =
      fs::temp_directory_path() / ("ccbuild_sweep_" + std::to_string(::getpid()) + ".csv");
  const auto r = run_ccbuild(
      "sweep tests/data/plans/cottage.yaml --nozzles 2 --platform-width 8m,20m "
      "--gantry-width 1m,1.5m --rail-axis x,y --csv " +
      csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "sweep: 8/8"));
  EXPECT_TRUE(contains(r.out, "construction min"));
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_TRUE(contains(line, "construction_time_s"));
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 8);
  fs::remove(csv);
  // A configuration with no plan names the lowest layer that has none.
  const auto none = run_ccbuild(
      "sweep tests/data/buildings/cottage.yaml --nozzles 3 --rail-axis x --platform-width 8m "
      "--gantry-width 2m");
  // ... and when no configuration has one, the answer is "no": exit 1.
  EXPECT_EQ(none.exit_code, 1) << none.err;
  EXPECT_TRUE(contains(none.out, "floor 0 layer 0 (and 3 more like it): stage 1")) << none.out;
  EXPECT_TRUE(contains(none.err, "no configuration has a collision-free plan"));
  const auto bad = run_ccbuild("sweep tests/data/plans/cottage.yaml --gantry-width -1m");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "--gantry-width: must be more than 0"));
}

TEST(MultiNozzleCli, SweepHasAOneNozzleBaselineWithPlanLayersNumbers) {
  // The baseline row is the sum of plan-layer's one-nozzle layer times: the same machine,
  // the same options, whichever command plans the layer.
  const auto sweep = run_ccbuild(
      "sweep tests/data/plans/cottage.yaml --nozzles 1,2 --platform-width 20m --gantry-width 1m "
      "--rail-axis x --objective time --json");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const auto j = nlohmann::json::parse(sweep.out);
  ASSERT_EQ(j["rows"].size(), 2u);
  const auto& baseline = j["rows"][0];
  EXPECT_EQ(baseline["nozzles"], 1);
  EXPECT_TRUE(baseline["gantry_width_m"].is_null());
  EXPECT_EQ(baseline["status"], "solved");
  const auto single =
      run_ccbuild("plan-layer tests/data/plans/cottage.yaml --objective time --json");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  EXPECT_NEAR(baseline["construction_time_s"].get<double>(),
              nlohmann::json::parse(single.out)["layer_time_s"].get<double>(), 1e-6);
}

}  // namespace
}  // namespace ccbuild
