// `ccbuild climb`: broken climbing machines (each a one-edit copy of the bundled URDF or
// profile) refused with their message and exit 2; the apartment's climbs printed, as
// JSON and drawn; an unstable machine answered with exit 1 and its reason; a fixed
// gantry told it needs no climbs.

#include <gtest/gtest.h>
#include <unistd.h>

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
using testing::slurp;

// `text` with its one occurrence of `from` replaced by `to` (the test fails when
// `from` is not there exactly once: the fixture would no longer be what it says).
std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "'";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' twice";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

// The bundled climber (URDF and profile) copied to a temporary folder, edited.
class BrokenClimber {
 public:
  BrokenClimber()
      : dir_(fs::temp_directory_path() / ("ccbuild_climber_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
    urdf_ = slurp(testing::source_path("config/machines/cc_climber.urdf"));
    profile_ = slurp(testing::source_path("config/machines/cc-climber.yaml"));
  }
  ~BrokenClimber() { fs::remove_all(dir_); }
  void edit_urdf(const std::string& from, const std::string& to) { urdf_ = edit(urdf_, from, to); }
  void edit_profile(const std::string& from, const std::string& to) {
    profile_ = edit(profile_, from, to);
  }
  // Writes both and runs `ccbuild climb` on the apartment with them.
  testing::CommandResult climb() const {
    std::ofstream(dir_ / "cc_climber.urdf", std::ios::binary) << urdf_;
    std::ofstream(dir_ / "cc-climber.yaml", std::ios::binary) << profile_;
    return run_ccbuild("climb config/buildings/apartment.yaml --machine " +
                       (dir_ / "cc-climber.yaml").string());
  }
  std::string urdf_path() const { return (dir_ / "cc_climber.urdf").string(); }
  std::string profile_path() const { return (dir_ / "cc-climber.yaml").string(); }
  // The 1-based line of the first line containing `text` in the URDF.
  int urdf_line(const std::string& text) const {
    std::istringstream in(urdf_);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (line.find(text) != std::string::npos) return n;
    return 0;
  }

 private:
  fs::path dir_;
  std::string urdf_, profile_;
};

void expect_refused(const testing::CommandResult& r, const std::string& message) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "ccbuild: error: ")) << r.err;
  EXPECT_TRUE(contains(r.err, message)) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(ClimberFixtures, TheBundledOnePlans) {
  // The edits below are refused because of them, not because the copy is broken.
  BrokenClimber good;
  const auto r = good.climb();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "5 stages, 4 climbs planned")) << r.out;
}

TEST(ClimberFixtures, AUnitMissingAJointInTheUrdf) {
  BrokenClimber b;
  b.edit_urdf("<joint name=\"u2_reach\"", "<joint name=\"u2_telescope\"");
  expect_refused(b.climb(), b.profile_path() + ":");
  expect_refused(b.climb(), "URDF " + b.urdf_path() + " has no joint 'u2_reach' (the reach)");
}

TEST(ClimberFixtures, AUnitMissingAJointInTheProfile) {
  BrokenClimber b;
  b.edit_profile("stroke: u3_stroke, ", "");
  expect_refused(b.climb(),
                 b.profile_path() + ":26: climbing.units[2]: missing required key 'stroke'");
}

TEST(ClimberFixtures, AUnitListedTwiceIsRefusedNotInfeasible) {
  // The same joints under a second name once made `climb` answer "not feasible" (exit 1).
  BrokenClimber b;
  b.edit_profile(
      "{name: U2, swing: u2_swing, reach: u2_reach, wrist: u2_wrist_yaw, stroke: u2_stroke, "
      "pin: u2_pin_slide}",
      "{name: U2, swing: u1_swing, reach: u1_reach, wrist: u1_wrist_yaw, stroke: u1_stroke, "
      "pin: u1_pin_slide}");
  expect_refused(b.climb(), b.profile_path() +
                                ":25: climbing.units[1].swing: joint 'u1_swing' is already unit "
                                "U1's; each unit moves joints of its own");
  BrokenClimber names;
  names.edit_profile("{name: U2,", "{name: U1,");
  expect_refused(names.climb(), names.profile_path() +
                                    ":25: climbing.units[1].name: unit name 'U1' is used twice");
}

TEST(ClimberFixtures, AJointOfTheWrongType) {
  BrokenClimber b;
  b.edit_urdf("<joint name=\"u1_swing\" type=\"revolute\"",
              "<joint name=\"u1_swing\" type=\"prismatic\"");
  expect_refused(b.climb(), "joint 'u1_swing' in " + b.urdf_path() + ":" +
                                std::to_string(b.urdf_line("<joint name=\"u1_swing\"")) +
                                " is prismatic, expected revolute (the swing)");
}

TEST(ClimberFixtures, AStrokeOnTheWrongAxis) {
  BrokenClimber b;
  b.edit_urdf(
      "<axis xyz=\"0 0 -1\"/><limit lower=\"1.2\" upper=\"5.6\" velocity=\"0.05\" "
      "effort=\"200000.0\"/></joint>\n  <link name=\"u1_pin\"",
      "<axis xyz=\"1 0 0\"/><limit lower=\"1.2\" upper=\"5.6\" velocity=\"0.05\" "
      "effort=\"200000.0\"/></joint>\n  <link name=\"u1_pin\"");
  expect_refused(b.climb(), "joint 'u1_stroke' in " + b.urdf_path());
  expect_refused(b.climb(), "moves along (1, 0, 0), expected (0, 0, -1) for the stroke");
}

TEST(ClimberFixtures, ALimitTheWrongWayRound) {
  BrokenClimber b;
  b.edit_urdf(
      "<limit lower=\"0.4\" upper=\"2.8\" velocity=\"0.05\" effort=\"50000.0\"/></joint>\n"
      "  <link name=\"u1_wrist\"",
      "<limit lower=\"2.8\" upper=\"0.4\" velocity=\"0.05\" effort=\"50000.0\"/></joint>\n"
      "  <link name=\"u1_wrist\"");
  const auto r = b.climb();
  expect_refused(r, b.urdf_path() + ":" + std::to_string(b.urdf_line("<joint name=\"u1_reach\"")) +
                        ": joint[u1_reach].limit: limits the wrong way round: lower 2.8 is above "
                        "upper 0.4");
}

TEST(ClimberFixtures, ALinkWithoutCollisionGeometry) {
  BrokenClimber b;
  b.edit_urdf(
      "<link name=\"u4_boom\"><collision><origin xyz=\"-1.3 0 -0.325\" rpy=\"0 0 0\"/>"
      "<geometry><box size=\"2.6 0.25 0.25\"/></geometry></collision>",
      "<link name=\"u4_boom\">");
  expect_refused(b.climb(), b.urdf_path() + ":" +
                                std::to_string(b.urdf_line("<link name=\"u4_boom\"")) +
                                ": link[u4_boom]: has no collision geometry");
}

TEST(ClimberFixtures, ALinkWithoutMass) {
  BrokenClimber b;
  b.edit_urdf(
      "<inertial><origin xyz=\"0 0 -1.25\"/><mass value=\"300\"/><inertia ixx=\"1\" "
      "ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n  <joint "
      "name=\"u3_wrist_yaw\"",
      "</link>\n  <joint name=\"u3_wrist_yaw\"");
  expect_refused(b.climb(), b.urdf_path() + ":" +
                                std::to_string(b.urdf_line("<link name=\"u3_wrist\"")) +
                                ": link[u3_wrist].inertial.mass: must be more than 0");
}

TEST(ClimberFixtures, TwoUnitsAreNotEnough) {
  BrokenClimber b;
  b.edit_profile(
      "    - {name: U3, swing: u3_swing, reach: u3_reach, wrist: u3_wrist_yaw, stroke: "
      "u3_stroke, pin: u3_pin_slide}\n",
      "");
  b.edit_profile(
      "    - {name: U4, swing: u4_swing, reach: u4_reach, wrist: u4_wrist_yaw, stroke: "
      "u4_stroke, pin: u4_pin_slide}\n",
      "");
  expect_refused(b.climb(), "a climbing machine has 3 to 16 units, got 2");
}

TEST(ClimberFixtures, TooManyUnitsMovingAtOnce) {
  // Two of four moving leave two pins: a line, no support polygon.
  BrokenClimber b;
  b.edit_profile("units_per_transfer: 1 ", "units_per_transfer: 2 ");
  expect_refused(b.climb(), b.profile_path() +
                                ":28: climbing.units_per_transfer: must be from 1 "
                                "to 1 for 4 units (at least 3 units hold the "
                                "platform while the others move)");
}

TEST(ClimberFixtures, ANumberOutOfItsRange) {
  BrokenClimber b;
  b.edit_profile("anchor_strength_mpa: 10 ", "anchor_strength_mpa: 1000 ");
  expect_refused(b.climb(),
                 "climbing.anchor_strength_mpa: must be from 5 to 100 MPa, "
                 "got 1000 MPa");
  // Under the least strength a climbing anchor is loaded from (its lower end, 5, is in).
  BrokenClimber low;
  low.edit_profile("anchor_strength_mpa: 10 ", "anchor_strength_mpa: 4.99 ");
  expect_refused(low.climb(), "must be from 5 to 100 MPa, got 4.99 MPa");
}

TEST(ClimbCommand, TheApartmentClimbsOnTheClimber) {
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "5 stages, 4 climbs planned")) << r.out;
  for (const char* climb : {"climb 0 -> 1: feasible", "climb 1 -> 2: feasible",
                            "climb 2 -> 3: feasible", "climb 3 -> 4: feasible"})
    EXPECT_TRUE(contains(r.out, climb)) << climb;
  // Climbs between floors (the default): each stage prints one floor. The pipes with the
  // layer they are cast after, the lift with its strokes.
  EXPECT_TRUE(contains(r.out,
                       "stage 1  platform at 21.55 ft, prints floor 1 layer 0 to floor 1 "
                       "layer 24 (top 20.00 ft)"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "U1->A1 (wall 1, cast after floor 0 layer 2")) << r.out;
  EXPECT_TRUE(contains(r.out, "7 strokes")) << r.out;
}

TEST(ClimbCommand, JsonListsTheClimbsWithTheirPhases) {
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml --floor 3 "
      "--json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["format"], "ccbuild-climbs-1");
  EXPECT_EQ(doc["stages"].size(), 5u);
  ASSERT_EQ(doc["climbs"].size(), 1u);  // the one made while floor 3 is printed
  const auto& climb = doc["climbs"][0];
  EXPECT_EQ(climb["from_stage"], 3);
  ASSERT_EQ(climb["phases"].size(), 18u);
  EXPECT_EQ(climb["phases"][0]["kind"], "park");
  EXPECT_EQ(climb["phases"][17]["kind"], "lift");
  EXPECT_EQ(climb["phases"][3]["joints"],
            nlohmann::json::array({"u1_swing", "u1_reach", "u1_wrist_yaw", "u1_stroke"}));
}

TEST(ClimbCommand, AFloorWithoutClimbsSaysSo) {
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml --floor 4");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "no climb is made while floor 4 is printed")) << r.out;
  const auto bad = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml --floor 5");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "no floor 5; config/buildings/apartment.yaml has floors 0 to 4"))
      << bad.err;
}

TEST(ClimbCommand, AnUnstableMachineIsAnAnswerWithItsReason) {
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine tests/data/machines/tippy-climber.yaml "
      "--floor 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.out, "climb 2 -> 3: NOT feasible: unstable")) << r.out;
  EXPECT_TRUE(contains(r.out, "with the gantry as counterweight anywhere on its rails")) << r.out;
}

TEST(ClimbCommand, TheTimeLimitHolds) {
  // 10 ms cannot plan a climb (about 0.6 s here): the answer says so, it does not run on.
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml --floor 2 "
      "--time-limit 0.01");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.out, "NOT feasible: time-limit: ")) << r.out;
  // Where the 10 ms run out depends on the machine's speed: before a phase starts, or
  // inside one; either way the answer says so.
  EXPECT_TRUE(r.out.find("the climb's planning time (0.01 s) ran out") != std::string::npos ||
              r.out.find("no motion within the time") != std::string::npos)
      << r.out;
}

TEST(ClimbCommand, AFixedGantryNeedsNoClimbs) {
  const auto r = run_ccbuild("climb config/buildings/house.yaml");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out,
                       "a fixed gantry; the building (6.00 m tall) is within its reach, "
                       "so no climbs are needed"))
      << r.out;
}

TEST(ClimbCommand, TheDrawingIsNeverWrittenOverAnInput) {
  const auto r = run_ccbuild(
      "climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml --svg "
      "config/machines/cc_climber.urdf --force");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "cc_climber.urdf")) << r.err;
  EXPECT_TRUE(contains(slurp(testing::source_path("config/machines/cc_climber.urdf")), "<robot"));
}

}  // namespace
}  // namespace ccbuild
