#include "ccbuild/machine/machine_model.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace ccbuild::machine {
namespace {
using testing::contains;
using testing::data;
using testing::expect_input_error;

TEST(MachineModel, BundledProfileReadsKinematicsFromTheUrdf) {
  const MachineModel m = load_machine(testing::source_path("config/machines/cc-gantry.yaml"));
  EXPECT_EQ(m.name, "CC gantry, up to three nozzles");
  EXPECT_DOUBLE_EQ(m.x.speed_m_s, 0.5);
  EXPECT_DOUBLE_EQ(m.x.max_m, 62.0);
  EXPECT_DOUBLE_EQ(m.y.max_m, 27.0);
  EXPECT_DOUBLE_EQ(m.z.speed_m_s, 0.05);
  EXPECT_NEAR(m.rotation_speed_rad_s, M_PI / 2, 1e-12);
  EXPECT_NEAR(m.stopper_min_rad, -2 * M_PI, 1e-12);
  EXPECT_NEAR(m.stopper_max_rad, 2 * M_PI, 1e-12);
  EXPECT_DOUBLE_EQ(m.deposition_speed_m_s, 0.2);
  EXPECT_TRUE(m.rotate_while_moving);
  EXPECT_NEAR(m.lift_time_s, 3.0, 1e-12);  // 0.15 m at the z joint's 0.05 m/s
  EXPECT_NEAR(m.lower_time_s, 3.0, 1e-12);
}

TEST(MachineModel, ExplicitLiftTimes) {
  const MachineModel m = load_machine(data("machines/explicit_lift.yaml"));
  EXPECT_DOUBLE_EQ(m.lift_time_s, 1.5);
  EXPECT_DOUBLE_EQ(m.lower_time_s, 2.5);
  EXPECT_FALSE(m.rotate_while_moving);
}

TEST(MachineModel, UnparsableUrdfIsNamed) {
  const InputError e = expect_input_error([] { load_machine(data("machines/broken_urdf.yaml")); });
  EXPECT_TRUE(contains(e.first().file, "broken.urdf"));
  EXPECT_TRUE(contains(e.what(), "not a valid URDF"));
}

TEST(MachineModel, MissingJointNamesFieldAndListsTheJoints) {
  const InputError e =
      expect_input_error([] { load_machine(data("machines/missing_joint.yaml")); });
  EXPECT_EQ(e.first().line, 5);
  EXPECT_EQ(e.first().field, "joints.y");
  EXPECT_TRUE(contains(e.what(), "has no joint 'bridge_why'"));
  EXPECT_TRUE(contains(e.what(), "bridge_y"));
}

TEST(MachineModel, WrongJointTypeIsExplained) {
  const InputError e =
      expect_input_error([] { load_machine(data("machines/wrong_joint_type.yaml")); });
  EXPECT_EQ(e.first().field, "joints.z");
  EXPECT_TRUE(contains(e.what(), "is revolute, expected prismatic"));
}

TEST(MachineModel, NegativeSpeedIsRejected) {
  const InputError e =
      expect_input_error([] { load_machine(data("machines/negative_speed.yaml")); });
  EXPECT_EQ(e.first().line, 4);
  EXPECT_EQ(e.first().field, "deposition_speed_m_s");
  EXPECT_TRUE(contains(e.what(), "must be more than 0 and at most 2 m/s, got -0.2 m/s"));
}

// The bundled gantry's profile with `extra` lines appended, next to its URDF.
std::string gantry_with(const std::string& extra) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_profile_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ifstream in(testing::source_path("config/machines/cc-gantry.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string profile = text.str();
  // Drop the bundled gantries' keys, so that `extra` sets them.
  for (const char* key :
       {"nozzles:", "gantry_width_m:", "rail_axis:", "purge_s:", "bead_width_m:"}) {
    const auto at = profile.find(std::string("\n") + key);
    if (at != std::string::npos) profile.erase(at + 1, profile.find('\n', at + 1) - at);
  }
  std::filesystem::copy_file(testing::source_path("config/machines/cc_gantry.urdf"),
                             dir / "cc_gantry.urdf",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "p.yaml") << profile << extra;
  return (dir / "p.yaml").string();
}

TEST(MachineModel, GantriesOnTheRailsAtTheirBoundaries) {
  const MachineModel defaults = load_machine(gantry_with(""));
  EXPECT_EQ(defaults.nozzles, 1);
  EXPECT_EQ(defaults.rail_axis, RailAxis::kX);
  EXPECT_DOUBLE_EQ(defaults.gantry_width_m, 1.5);
  EXPECT_DOUBLE_EQ(defaults.purge_s, 120.0);
  const MachineModel most = load_machine(gantry_with("nozzles: 16\nrail_axis: y\npurge_s: 3600\n"));
  EXPECT_EQ(most.nozzles, 16);
  EXPECT_EQ(most.rail_axis, RailAxis::kY);
  EXPECT_DOUBLE_EQ(most.purge_s, 3600.0);
  EXPECT_EQ(load_machine(gantry_with("nozzles: 1\n")).nozzles, 1);
  const InputError none = expect_input_error([] { load_machine(gantry_with("nozzles: 0\n")); });
  EXPECT_EQ(none.first().field, "nozzles");
  EXPECT_TRUE(contains(none.what(), "1 to 16"));
  EXPECT_EQ(expect_input_error([] { load_machine(gantry_with("nozzles: 17\n")); }).first().field,
            "nozzles");
  const InputError axis = expect_input_error([] { load_machine(gantry_with("rail_axis: z\n")); });
  EXPECT_EQ(axis.first().field, "rail_axis");
  EXPECT_TRUE(contains(axis.what(), "must be x or y, got 'z'"));
  EXPECT_EQ(
      expect_input_error([] { load_machine(gantry_with("purge_s: 3600.5\n")); }).first().field,
      "purge_s");
  EXPECT_EQ(
      expect_input_error([] { load_machine(gantry_with("gantry_width_m: 0\n")); }).first().field,
      "gantry_width_m");
  std::filesystem::remove_all(std::filesystem::path(gantry_with("")).parent_path());
}

// bead_width_m: [narrowest, widest], the nozzle's own width within it (both ends allowed).
TEST(MachineModel, BeadWidthsAreARangeHoldingTheNozzlesWidth) {
  const MachineModel bundled = load_machine(testing::source_path("config/machines/cc-gantry.yaml"));
  EXPECT_EQ(bundled.bead_widths(), std::make_pair(0.10, 0.25));
  const MachineModel unstated = load_machine(gantry_with(""));
  EXPECT_FALSE(unstated.bead_width_range_m);
  EXPECT_EQ(unstated.bead_widths(), std::make_pair(0.15, 0.15));
  EXPECT_EQ(load_machine(gantry_with("bead_width_m: [0.15, 0.15]\n")).bead_widths(),
            std::make_pair(0.15, 0.15));
  EXPECT_EQ(load_machine(gantry_with("bead_width_m: [0.15, 0.3]\n")).bead_widths(),
            std::make_pair(0.15, 0.3));
  EXPECT_EQ(load_machine(gantry_with("bead_width_m: [0.05, 0.15]\n")).bead_widths(),
            std::make_pair(0.05, 0.15));
  const auto refused = [](const std::string& line) {
    return expect_input_error([&] { load_machine(gantry_with(line)); });
  };
  const InputError below = refused("bead_width_m: [0.16, 0.3]\n");
  EXPECT_EQ(below.first().field, "bead_width_m");
  EXPECT_TRUE(contains(below.what(), "nozzle_width_m 0.15 m, must lie in the range [0.16, 0.3]"))
      << below.what();
  EXPECT_TRUE(contains(refused("bead_width_m: [0.1, 0.149]\n").what(), "must lie in the range"));
  EXPECT_TRUE(contains(refused("bead_width_m: [0.2, 0.1]\n").what(), "wrong way round"));
  EXPECT_TRUE(contains(refused("bead_width_m: [0.1]\n").what(), "got 1 values"));
  EXPECT_EQ(refused("bead_width_m: [0.001, 0.2]\n").first().field, "bead_width_m[0]");
  std::filesystem::remove_all(std::filesystem::path(gantry_with("")).parent_path());
}

}  // namespace
}  // namespace ccbuild::machine
