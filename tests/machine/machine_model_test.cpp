#include "ccbuild/machine/machine_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace ccbuild::machine
