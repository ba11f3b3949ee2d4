// The ccbuild binary end to end: exit codes 0/2, messages that name file and line, and
// JSON that parses.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
using testing::contains;
using testing::run_ccbuild;

TEST(Cli, ValidateBundledHouse) {
  const auto r = run_ccbuild("validate config/buildings/house.yaml");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "valid building"));
  EXPECT_TRUE(contains(r.out, "total: 2 floor(s)"));
  EXPECT_TRUE(contains(r.out, "CC gantry, up to three nozzles"));
}

TEST(Cli, ValidateJsonAgreesWithTheModel) {
  const auto r = run_ccbuild("validate config/buildings/apartment.yaml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["floors"].size(), 5u);
  EXPECT_EQ(j["units"], "ft");
  EXPECT_EQ(j["totals"]["layer_count"], 125);
  EXPECT_GE(j["floors"][0]["wall_count"].get<int>(), 180);
}

// A building drawn in feet is shown in feet; --units m shows it in metres (and says so),
// and a plan file without its own unit is read in --units.
TEST(ShownUnits, AFeetBuildingInFeetUnlessMetresAreAskedFor) {
  const auto feet = run_ccbuild("validate config/buildings/apartment.yaml");
  ASSERT_EQ(feet.exit_code, 0) << feet.err;
  EXPECT_TRUE(contains(feet.out, "  units      ft in the file, metres inside\n")) << feet.out;
  EXPECT_TRUE(contains(feet.out, "size       128.00 ft x 52.00 ft, 50.00 ft tall")) << feet.out;
  const auto metres = run_ccbuild("validate config/buildings/apartment.yaml --units m");
  ASSERT_EQ(metres.exit_code, 0) << metres.err;
  EXPECT_TRUE(contains(metres.out, "units      ft in the file, metres inside, shown in m"))
      << metres.out;
  EXPECT_TRUE(contains(metres.out, "size       39.01 m x 15.85 m, 15.24 m tall")) << metres.out;
  EXPECT_FALSE(std::regex_search(metres.out, std::regex("[0-9] ft"))) << metres.out;
  const auto json = run_ccbuild("validate config/buildings/apartment.yaml --units m --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["units"], "ft");
  EXPECT_EQ(j["shown_in"], "m");
  // The metric house in feet: its 3 m floors are 9.843 ft.
  const auto house = run_ccbuild("validate config/buildings/house.yaml --units ft");
  ASSERT_EQ(house.exit_code, 0) << house.err;
  EXPECT_TRUE(contains(house.out, "9.843 ft")) << house.out;
  EXPECT_FALSE(std::regex_search(house.out, std::regex("[0-9] m\\b"))) << house.out;
}

// A schedule's exports and report take the schedule's unit, or --units: the apartment's
// concrete in cubic yards, or in cubic metres on request (16 trucks of 8 m³ are 167.42 yd³).
TEST(ShownUnits, ExportsOfAFeetScheduleInCubicYardsUnlessMetresAreAskedFor) {
  const std::filesystem::path dir = testing::scratch_dir("cli", "shown_units");
  const std::string golden = "tests/regression/apartment.schedule.json";
  const std::string days = "export " + golden + " --format days --start 2027-03-01T07:00 -o ";
  const auto yards = run_ccbuild(days + (dir / "yd.txt").string());
  ASSERT_EQ(yards.exit_code, 0) << yards.err;
  const std::string yards_text = testing::slurp(dir / "yd.txt");
  EXPECT_TRUE(contains(yards_text, "deliver  07:00-23:49  16 trucks, 167.42 yd³"))
      << yards_text.substr(0, 2000);
  EXPECT_FALSE(contains(yards_text, "m³"));
  const auto metres = run_ccbuild(days + (dir / "m.txt").string() + " --units m");
  ASSERT_EQ(metres.exit_code, 0) << metres.err;
  const std::string metres_text = testing::slurp(dir / "m.txt");
  EXPECT_TRUE(contains(metres_text, "deliver  07:00-23:49  16 trucks, 128.00 m³"))
      << metres_text.substr(0, 2000);
  EXPECT_FALSE(contains(metres_text, "yd³"));
  EXPECT_EQ(run_ccbuild(days + (dir / "x.txt").string() + " --units yd").exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.txt"));
  std::filesystem::remove_all(dir);
}

TEST(Cli, ValidatePlanInEachEncoding) {
  for (const char* file : {"cottage.yaml", "cottage.json", "cottage.txt"}) {
    const auto r = run_ccbuild(std::string("validate tests/data/plans/") + file + " --json");
    ASSERT_EQ(r.exit_code, 0) << file << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "plan");
    EXPECT_EQ(j["totals"]["wall_count"], 7);
    EXPECT_EQ(j["totals"]["opening_count"], 2);
    EXPECT_EQ(j["totals"]["layer_count"], 30);  // default 3 m floor of 0.1 m layers
  }
}

TEST(Cli, BrokenPlanExitsTwoWithFileAndLine) {
  const auto r = run_ccbuild("validate tests/data/broken/unknown_vertex.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "tests/data/broken/unknown_vertex.yaml:7: walls[1].end: "));
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(Cli, BrokenBuildingReportsEveryFloorProblem) {
  const auto r = run_ccbuild("validate tests/data/buildings/head_above_floor.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "is above the floor height"));
}

TEST(Cli, BuildingLargerThanTheMachineReachIsRejected) {
  const auto r = run_ccbuild("validate tests/data/buildings/too_big_for_machine.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "tiny_gantry.yaml"));
  EXPECT_TRUE(
      contains(r.err, "the building is 6.00 m x 4.00 m but the machine reaches 5.00 m x 29.00 m"));
  // Every command checks it, not only validate.
  for (const char* command : {"layers", "plan-layer", "sweep"}) {
    const auto other =
        run_ccbuild(std::string(command) + " tests/data/buildings/too_big_for_machine.yaml");
    EXPECT_EQ(other.exit_code, 2) << command;
    EXPECT_TRUE(contains(other.err, "but the machine reaches")) << command;
  }
}

TEST(Cli, LayersListsRunsPerFloor) {
  const auto r = run_ccbuild("layers config/buildings/house.yaml --floor 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["floors"].size(), 1u);
  const auto& runs = j["floors"][0]["runs"];
  ASSERT_GE(runs.size(), 2u);
  // Runs cover layers 0..29 without gaps.
  int next = 0;
  for (const auto& run : runs) {
    EXPECT_EQ(run["first_layer"], next);
    next = run["last_layer"].get<int>() + 1;
  }
  EXPECT_EQ(next, 30);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_ccbuild("").exit_code, 2);
  EXPECT_EQ(run_ccbuild("validate").exit_code, 2);
  EXPECT_EQ(run_ccbuild("validate x.yaml --no-such-flag").exit_code, 2);
  EXPECT_EQ(run_ccbuild("frobnicate").exit_code, 2);
  const auto floor = run_ccbuild("layers config/buildings/house.yaml --floor 7");
  EXPECT_EQ(floor.exit_code, 2);
  EXPECT_TRUE(contains(floor.err, "no floor 7"));
  const auto missing = run_ccbuild("validate no/such/file.yaml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.err, "no/such/file.yaml: file not found"));
}

TEST(Cli, HelpTeachesAndExitsZero) {
  const auto r = run_ccbuild("layers --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(contains(r.out, "Examples:"));
  EXPECT_TRUE(contains(r.out, "--floor"));
}

}  // namespace
}  // namespace ccbuild
