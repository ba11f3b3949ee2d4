// ccbuild plan-layer end to end: text and JSON answers, the SVG file, and bad input.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ccbuild/common/format.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::run_ccbuild;

TEST(PlanLayerCli, ReferenceExampleInText) {
  // The papers' examples are in feet; lengths are printed in the plan's unit.
  const auto r = run_ccbuild(
      "plan-layer tests/data/plans/paper_example1.txt --units ft --start-vertex 1 --first-wall 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "airtime       25.000 ft"));
  EXPECT_TRUE(contains(r.out, "lower bound   25.000 ft (matching), gap 0.00%"));
  EXPECT_TRUE(contains(r.out, "sequence      1 "));
}

TEST(PlanLayerCli, TimeObjectiveSaysItsGapIsInDistance) {
  const auto r = run_ccbuild(
      "plan-layer tests/data/plans/paper_example2.txt --units ft --start-vertex 1 --first-wall 1 "
      "--objective time");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "in distance (time objective)")) << r.out;
}

TEST(PlanLayerCli, JsonCarriesEveryRequiredField) {
  const auto r = run_ccbuild(
      "plan-layer tests/data/plans/paper_example2.txt --units ft --start-vertex 1 --first-wall 1 "
      "--metric rectilinear --objective time --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"format",
                          "file",
                          "floor",
                          "layer",
                          "z_bottom_m",
                          "z_top_m",
                          "seed",
                          "machine",
                          "pieces",
                          "nozzles",
                          "algorithm",
                          "metric",
                          "objective",
                          "closed",
                          "start_m",
                          "piece_count",
                          "airtime_distance_m",
                          "airtime_s",
                          "deposition_s",
                          "layer_time_s",
                          "lower_bound_distance_m",
                          "lower_bound_source",
                          "gap_fraction",
                          "solve_s",
                          "stopped_by",
                          "kicks",
                          "polish_kicks",
                          "max_idle_s",
                          "idle_limit_s",
                          "idle_limit_violations",
                          "lift_count",
                          "total_rotation_rad",
                          "sequence",
                          "moves",
                          "waypoints"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["metric"], "rectilinear");
  EXPECT_TRUE(j["layer"].is_null());  // a lone plan with every wall whole
  ASSERT_EQ(j["sequence"].size(), 8u);
  EXPECT_EQ(j["sequence"][0]["wall"], 1);
  EXPECT_EQ(j["sequence"][0]["piece"], 1);
  EXPECT_EQ(j["sequence"][0]["reversed"], false);
  EXPECT_EQ(j["moves"].size(), 8u);
  EXPECT_NEAR(j["layer_time_s"].get<double>(),
              j["airtime_s"].get<double>() + j["deposition_s"].get<double>(), 1e-5);
  const auto& move = j["moves"][1];
  for (const char* key : {"from_m", "to_m", "distance_m", "time_s", "lifted", "rotation_rad"})
    EXPECT_TRUE(move.contains(key));
  // The waypoints end when the layer does.
  EXPECT_NEAR(j["waypoints"].back()["t_s"].get<double>(), j["layer_time_s"].get<double>(), 1e-5);
}

TEST(PlanLayerCli, SameSeedSameJson) {
  const std::string args =
      "plan-layer config/buildings/house.yaml --floor 1 --layer 12 --objective time --seed 7 "
      "--json";
  auto a = nlohmann::json::parse(run_ccbuild(args).out);
  auto b = nlohmann::json::parse(run_ccbuild(args).out);
  a.erase("solve_s");
  b.erase("solve_s");
  EXPECT_EQ(a.dump(), b.dump());
}

TEST(PlanLayerCli, ALongSearchReportsItsBestTourOnStderr) {
  // Ground-floor layer 12 of the house has a gap to its bound, so an anytime run goes on
  // to its limit: lines at 1 and 2 s, none after it ends.
  const std::string args = "plan-layer config/buildings/house.yaml --layer 12 --time-limit 2.5";
  const auto r = run_ccbuild(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "time-limit after")) << r.out;
  std::vector<double> reported_m;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) {
    double seconds = 0.0, best_m = 0.0;
    ASSERT_EQ(
        std::sscanf(line.c_str(), "plan-layer: %lf s, best tour so far %lf m", &seconds, &best_m),
        2)
        << line;
    reported_m.push_back(best_m);
  }
  ASSERT_EQ(reported_m.size(), 2u) << r.err;
  double airtime_m = 0.0;
  ASSERT_EQ(std::sscanf(r.out.substr(r.out.find("airtime")).c_str(), "airtime %lf m", &airtime_m),
            1);
  // Each line's best is the best so far: never shorter than the answer, never growing.
  EXPECT_GE(reported_m[1], airtime_m - 0.0005);
  EXPECT_LE(reported_m[1], reported_m[0]);
  EXPECT_TRUE(contains(r.err, "plan-layer: 1 s, ")) << r.err;
  EXPECT_TRUE(contains(r.err, "plan-layer: 2 s, ")) << r.err;

  EXPECT_EQ(run_ccbuild(args + " --quiet").err, "");
  // Under the time objective the exact-time polish takes the time and reports the
  // exact airtime.
  const auto time = run_ccbuild(args + " --objective time");
  ASSERT_EQ(time.exit_code, 0) << time.err;
  const std::string last = time.err.substr(time.err.rfind("plan-layer: "));
  double due_s = 0.0, best_s = 0.0, airtime_s = 0.0;
  ASSERT_EQ(std::sscanf(last.c_str(),
                        "plan-layer: %lf s, best tour so far %lf s of airtime "
                        "(exact-time polish",
                        &due_s, &best_s),
            2)
      << time.err;
  EXPECT_EQ(due_s, 2.0);
  EXPECT_TRUE(contains(last, " s of airtime (exact-time polish, found at ")) << last;
  ASSERT_EQ(std::sscanf(time.out.substr(time.out.find("airtime")).c_str(), "airtime %*f m, %lf s",
                        &airtime_s),
            1);
  EXPECT_GE(best_s, airtime_s - 0.005);
  // A search that ends within its first second says nothing.
  EXPECT_EQ(run_ccbuild("plan-layer config/buildings/house.yaml --layer 12").err, "");
}

TEST(PlanLayerCli, AnAnytimeRunPrintsTheFlagsThatReplayIt) {
  // Under the time objective the replay needs the polish's kicks as well as the
  // search's; the run's own output names both, and the JSON carries them.
  const std::string args =
      "plan-layer config/buildings/house.yaml --layer 12 --objective time --quiet";
  const auto r = run_ccbuild(args + " --time-limit 1.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.out.find("replay");
  ASSERT_NE(at, std::string::npos) << r.out;
  long kicks = 0, polish_kicks = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "replay --max-kicks %ld --polish-kicks %ld", &kicks,
                        &polish_kicks),
            2)
      << r.out;
  EXPECT_TRUE(contains(r.out, "time-limit after " + std::to_string(kicks) +
                                  " kicks, exact-time polish " + std::to_string(polish_kicks) +
                                  " kicks"))
      << r.out;
  const std::string replay = args + " --max-kicks " + std::to_string(kicks) + " --polish-kicks " +
                             std::to_string(polish_kicks);
  const auto again = run_ccbuild(replay + " --json");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto j = nlohmann::json::parse(again.out);
  EXPECT_EQ(j["kicks"], kicks);
  EXPECT_EQ(j["polish_kicks"], polish_kicks);
  EXPECT_EQ(j["stopped_by"], "converged");
  // The same plan: its sequence line, word for word.
  const std::string sequence = r.out.substr(r.out.find("sequence"));
  const auto text = run_ccbuild(replay);
  EXPECT_EQ(text.out.substr(text.out.find("sequence")), sequence);
  // A default run replays itself: no replay line; the distance objective has no polish.
  EXPECT_FALSE(contains(run_ccbuild(args).out, "replay"));
  EXPECT_TRUE(
      nlohmann::json::parse(run_ccbuild("plan-layer config/buildings/house.yaml --layer 12 --json")
                                .out)["polish_kicks"]
          .is_null());
}

TEST(PlanLayerCli, BuildingLayerWithCutWalls) {
  const auto r = run_ccbuild("plan-layer config/buildings/house.yaml --floor 0 --layer 12 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sequence"].size(), j["piece_count"].get<std::size_t>());
  EXPECT_EQ(j["pieces"].size(), j["piece_count"].get<std::size_t>());
  EXPECT_EQ(j["floor"], 0);
  EXPECT_EQ(j["layer"], 12);
  EXPECT_NEAR(j["z_bottom_m"].get<double>(), 1.2, 1e-9);
  EXPECT_LE(j["lower_bound_distance_m"].get<double>(),
            j["airtime_distance_m"].get<double>() + 1e-9);
  // Pieces are numbered from 1 in the JSON as in the text ("12:2").
  const auto text = run_ccbuild("plan-layer config/buildings/house.yaml --floor 0 --layer 12");
  std::size_t cut = 0;
  for (const auto& step : j["sequence"]) {
    const auto id = step["wall"].get<long>();
    const auto piece = step["piece"].get<int>();
    EXPECT_GE(piece, 1);
    std::string signed_id = step["reversed"].get<bool>() ? "-" : "";
    signed_id += std::to_string(id);
    signed_id += ":";
    signed_id += std::to_string(piece);
    if (contains(text.out, " " + signed_id + " ") || contains(text.out, " " + signed_id + "\n"))
      ++cut;
  }
  EXPECT_GT(cut, 10u);  // layer 12 cuts many walls at doors and windows
}

TEST(PlanLayerCli, SvgIsWrittenWholeAndNotOverwrittenUnasked) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_svg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string svg = (dir / "plan.svg").string();
  const auto first = run_ccbuild("plan-layer tests/data/plans/cottage.yaml --svg " + svg);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(text, "<svg"));
  EXPECT_TRUE(contains(text, "</svg>"));
  EXPECT_TRUE(contains(text, "start"));
  const auto again = run_ccbuild("plan-layer tests/data/plans/cottage.yaml --svg " + svg);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(contains(again.err, "--force"));
  EXPECT_EQ(run_ccbuild("plan-layer tests/data/plans/cottage.yaml --force --svg " + svg).exit_code,
            0);
  // Never over an input.
  const auto onto_input = run_ccbuild(
      "plan-layer tests/data/plans/cottage.yaml --force --svg tests/data/plans/cottage.yaml");
  EXPECT_EQ(onto_input.exit_code, 2);
  fs::remove_all(dir);
}

TEST(PlanLayerCli, TheBoundsCertificateIsWrittenWithTheRoundsItRan) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_certificate_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string certificate = (dir / "bound.json").string();
  const std::string svg = (dir / "plan.svg").string();
  const std::string args = "plan-layer config/buildings/house.yaml --layer 12 --bound-rounds 3 ";
  const auto r = run_ccbuild(args + "--bound-certificate " + certificate);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "after 3 rounds (round-limit)")) << r.out;
  EXPECT_TRUE(contains(r.out, "moats (tests/tools/check_bound.py " + certificate)) << r.out;
  std::ifstream in(certificate);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["format"], "ccbuild-bound-certificate-1");
  EXPECT_EQ(j["rounds"], 3);
  EXPECT_EQ(j["stopped_by"], "round-limit");
  EXPECT_EQ(j["walls"].size(), j["pieces"].size());
  EXPECT_GT(j["moats"].size(), 0u);
  // The same bound as the plan's text, to the printed millimetre.
  EXPECT_TRUE(contains(
      r.out, printf_string("connected     %.3f m", j["lower_bound_distance_m"].get<double>())))
      << r.out;
  // The same inputs give the same file, byte for byte.
  const std::string twin = (dir / "twin.json").string();
  ASSERT_EQ(run_ccbuild(args + "--bound-certificate " + twin).exit_code, 0);
  EXPECT_EQ(testing::slurp(twin), testing::slurp(certificate));
  // Not overwritten unasked.
  const auto again = run_ccbuild(args + "--bound-certificate " + certificate);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(contains(again.err, "--force"));
  // No time for the bound: neither file is written, and the reason is given.
  const std::string late = (dir / "late.json").string();
  const auto no_time =
      run_ccbuild(args + "--time-limit 0.0001 --svg " + svg + " --bound-certificate " + late);
  EXPECT_EQ(no_time.exit_code, 2);
  EXPECT_TRUE(contains(no_time.err, "the connected bound did not run")) << no_time.err;
  EXPECT_FALSE(fs::exists(late));
  EXPECT_FALSE(fs::exists(svg));
  fs::remove_all(dir);
}

TEST(PlanLayerCli, BadInputExitsTwoWithAReason) {
  struct Case {
    const char* args;
    const char* message;
  };
  const Case cases[] = {
      {"plan-layer tests/data/broken/unknown_vertex.yaml", "unknown_vertex.yaml:7"},
      {"plan-layer tests/data/plans/cottage.yaml --first-wall 3",
       "--first-wall: needs --start-vertex"},
      {"plan-layer tests/data/plans/cottage.yaml --start-vertex 99",
       "vertex 99 is not in the plan"},
      {"plan-layer tests/data/plans/cottage.yaml --start-vertex 1 --first-wall 42",
       "wall 42 is not in this layer"},
      {"plan-layer tests/data/plans/cottage.yaml --metric manhattan", "manhattan"},
      {"plan-layer tests/data/plans/cottage.yaml --time-limit -1",
       "--time-limit: must be more than 0 and at most 86400 s, got -1"},
      {"plan-layer tests/data/plans/cottage.yaml --time-limit nan", "expected a number"},
      {"plan-layer tests/data/plans/cottage.yaml --polish-kicks 5",
       "--polish-kicks: applies only with --objective time"},
      {"plan-layer tests/data/plans/cottage.yaml --objective time --polish-kicks -1",
       "--polish-kicks"},
      {"plan-layer tests/data/plans/cottage.yaml --objective time --algorithm nearest "
       "--polish-kicks 5",
       "--polish-kicks: applies only to one nozzle's cc-tsp search"},
      {"plan-layer config/buildings/apartment.yaml --algorithm exact",
       "exact handles layers of at most"},
      {"plan-layer config/buildings/house.yaml --layer 99", "no layer 99"},
      {"plan-layer tests/data/plans/cottage.yaml --bound matching --bound-certificate b.json",
       "--bound-certificate: applies only to the connected bound"},
      {"plan-layer tests/data/plans/cottage.yaml --nozzles 2 --gantry-width 1 --bound-rounds 9",
       "--bound-rounds: applies only to one nozzle's plan"},
      {"plan-layer tests/data/plans/cottage.yaml --bound-rounds 0", "--bound-rounds"},
      {"plan-layer tests/data/plans/cottage.yaml --svg same.svg --bound-certificate same.svg",
       "--bound-certificate: is the same file as --svg"},
      {"plan-layer tests/data/plans/cottage.yaml --force --bound-certificate "
       "tests/data/plans/cottage.yaml",
       "cottage.yaml"},
      {"plan-layer tests/data/plans/cottage.yaml --machine tests/data/machines/missing_joint.yaml",
       "bridge_why"},
  };
  for (const auto& c : cases) {
    const auto r = run_ccbuild(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_TRUE(contains(r.err, c.message)) << c.args;
    EXPECT_TRUE(r.out.empty()) << c.args << ": " << r.out;
  }
}

}  // namespace
}  // namespace ccbuild
