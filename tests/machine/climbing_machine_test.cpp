// The climbing machine read from its URDF: units and their joints by role, forward
// kinematics and the centre of mass against hand-computed values, the units' inverse
// kinematics, and the stroke margin at its edges.

#include "ccbuild/machine/climbing_machine.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ccbuild/machine/kinematics.hpp"
#include "test_support.hpp"

namespace ccbuild::machine {
namespace {

const ClimbingMachine& climber() {
  static const MachineProfile profile =
      load_machine_profile(testing::source_path("config/machines/cc-climber.yaml"));
  return *profile.climbing;
}

TEST(ClimbingMachine, UnitsAndTheirJointsByRole) {
  const ClimbingMachine& m = climber();
  ASSERT_EQ(m.units.size(), 4u);
  EXPECT_EQ(m.units[2].name, "U3");
  const char* names[] = {"u3_swing", "u3_reach", "u3_wrist_yaw", "u3_stroke", "u3_pin_slide"};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(m.robot->joint_info(m.units[2].joints[k]).name, names[k]);
  EXPECT_EQ(m.robot->link_info(m.units[2].foot_link).name, "u3_foot");
  EXPECT_EQ(m.robot->link_info(m.robot->root()).name, "platform");
  EXPECT_DOUBLE_EQ(m.stroke_end_margin_m, 0.015);
  EXPECT_DOUBLE_EQ(m.anchor_strength_mpa, 10.0);
}

TEST(ClimbingMachine, ForwardKinematicsOfALeg) {
  // U1 hangs from (0.6, -1.2) under the platform: the swing 0.3 m down turned a quarter
  // turn (its boom along +y), the stroke 0.45 m below the boom; at zero the foot is 0.75 m
  // below the platform's frame, over the mount. Reach r moves it r along +y.
  const ClimbingMachine& m = climber();
  std::vector<double> q = m.robot->zero();
  const Eigen::Isometry3d platform(Eigen::Translation3d(1.0, 2.0, 10.0));
  Eigen::Vector3d foot = m.robot->link_poses(platform, q)[m.units[0].foot_link].translation();
  EXPECT_NEAR(foot.x(), 1.6, 1e-4);
  EXPECT_NEAR(foot.y(), 0.8, 1e-4);
  EXPECT_NEAR(foot.z(), 10.0 - 0.75, 1e-9);
  q[m.units[0].joints[1]] = 2.0;  // reach
  q[m.units[0].joints[3]] = 3.0;  // stroke: down
  foot = m.robot->link_poses(platform, q)[m.units[0].foot_link].translation();
  EXPECT_NEAR(foot.x(), 1.6, 1e-3);
  EXPECT_NEAR(foot.y(), 2.8, 1e-3);
  EXPECT_NEAR(foot.z(), 10.0 - 3.75, 1e-9);
}

TEST(ClimbingMachine, TheCentreOfMassWeighsEveryLink) {
  const ClimbingMachine& m = climber();
  double mass = 0.0;
  for (int l = 0; l < m.robot->link_count(); ++l) mass += m.robot->link_info(l).mass_kg;
  EXPECT_DOUBLE_EQ(m.robot->total_mass_kg(), mass);
  // Moving the bridge (3,500 kg and what it carries) 10 m along x moves the centre of
  // mass by 10 m times its share of the mass.
  std::vector<double> q = m.robot->zero();
  const Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d before = m.robot->centre_of_mass(m.robot->link_poses(at, q));
  q[m.gantry_joints[0]] += 10.0;
  const Eigen::Vector3d after = m.robot->centre_of_mass(m.robot->link_poses(at, q));
  double moving = 0.0;
  for (int l : m.gantry_links) moving += m.robot->link_info(l).mass_kg;
  EXPECT_GE(moving, 3500.0);
  EXPECT_NEAR(after.x() - before.x(), 10.0 * moving / mass, 1e-9);
  EXPECT_NEAR(after.y(), before.y(), 1e-9);
}

TEST(ClimbingMachine, InverseKinematicsPutsTheFootWhereAsked) {
  const ClimbingMachine& m = climber();
  const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, 12.0));
  const std::vector<double> q0 = m.robot->zero();
  for (int u = 0; u < 4; ++u) {
    const Eigen::Vector3d mount =
        m.robot->link_poses(platform, q0)[m.units[u].foot_link].translation();
    const Eigen::Vector3d target = mount + Eigen::Vector3d(0.7, u < 2 ? 1.1 : -1.1, -3.0);
    const auto pose = m.unit_ik(u, platform, q0, target, Eigen::Vector2d(0, u < 2 ? 1 : -1), 0.1);
    ASSERT_TRUE(pose) << m.units[u].name;
    EXPECT_TRUE(m.unit_within_limits(u, *pose)) << m.units[u].name;
    std::vector<double> q = q0;
    m.set_unit(u, *pose, q);
    const auto poses = m.robot->link_poses(platform, q);
    EXPECT_LT((poses[m.units[u].foot_link].translation() - target).norm(), 1e-9) << m.units[u].name;
    EXPECT_NEAR((*pose)[4], 0.1, 1e-12);
    // The pin points where asked: its joint's axis (x of the foot) in the world.
    const Eigen::Vector3d pin_axis =
        poses[m.units[u].foot_link].linear() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(pin_axis.y(), u < 2 ? 1.0 : -1.0, 1e-9) << m.units[u].name;
  }
}

TEST(ClimbingMachine, TheStrokeKeepsItsMarginAtBothEnds) {
  const ClimbingMachine& m = climber();
  const JointInfo& stroke = m.robot->joint_info(m.units[1].joints[3]);
  UnitPose pose = m.get_unit(1, m.robot->zero());
  pose[1] = 1.0;  // reach within its limits
  for (const double s : {stroke.lower + 0.015, stroke.upper - 0.015}) {
    pose[3] = s;
    EXPECT_TRUE(m.unit_within_limits(1, pose)) << s;
  }
  for (const double s : {stroke.lower + 0.0149, stroke.upper - 0.0149}) {
    pose[3] = s;
    EXPECT_FALSE(m.unit_within_limits(1, pose)) << s;
  }
  // Other joints have no margin: the reach at its very ends is within.
  pose[3] = 3.0;
  const JointInfo& reach = m.robot->joint_info(m.units[1].joints[1]);
  for (const double r : {reach.lower, reach.upper}) {
    pose[1] = r;
    EXPECT_TRUE(m.unit_within_limits(1, pose)) << r;
  }
  pose[1] = reach.upper + 1e-6;
  EXPECT_FALSE(m.unit_within_limits(1, pose));
}

}  // namespace
}  // namespace ccbuild::machine
