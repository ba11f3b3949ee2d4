// Climbing: hand-built scenes where a unit must detour round a wall (one standing only in
// the last layer printed among them), where it is boxed in, where the platform would tip
// or stands within its stability margin; the apartment's climbs (a setback on its top
// floors) all planned, re-checked and repeatable; stages and pipes placed as the rules say.

#include "ccbuild/climb/climb.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "test_support.hpp"

namespace ccbuild::climb {
namespace {
namespace fs = std::filesystem;
using testing::contains;

using testing::slurp;

const machine::ClimbingMachine& climber() {
  static const machine::MachineProfile profile =
      machine::load_machine_profile(testing::source_path("config/machines/cc-climber.yaml"));
  return *profile.climbing;
}

// A one-floor building the climber straddles: a 30 m x 15.85 m rectangle (walls 1-4) and
// `extra` walls (YAML list items), in a temporary folder.
class Scene {
 public:
  explicit Scene(const std::string& extra_vertices = "", const std::string& extra_walls = "",
                 const std::string& openings = "", double height_m = 3.0)
      : dir_(fs::temp_directory_path() / ("ccbuild_climb_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
    const std::string config = testing::source_path("config").string();
    std::ofstream(dir_ / "b.yaml")
        << "units: m\nlayer_height: 0.1\nmaterial: " << config
        << "/materials/standard-mix.yaml\nmachine: " << config
        << "/machines/cc-climber.yaml\nfloors:\n  - height: " << height_m
        << "\n    plan:\n      vertices:\n"
           "        - {id: 1, x: 0, y: 0}\n        - {id: 2, x: 30, y: 0}\n"
           "        - {id: 3, x: 30, y: 15.85}\n        - {id: 4, x: 0, y: 15.85}\n"
        << extra_vertices
        << "      walls:\n        - {id: 1, start: 1, end: 2}\n        - {id: 2, start: 2, end: "
           "3}\n"
           "        - {id: 3, start: 3, end: 4}\n        - {id: 4, start: 4, end: 1}\n"
        << extra_walls << (openings.empty() ? "" : "      openings:\n" + openings);
    building_ = floors::load_building(dir_ / "b.yaml");
  }
  ~Scene() { fs::remove_all(dir_); }
  const floors::Building& building() const { return building_; }

 private:
  fs::path dir_;
  floors::Building building_;
};

// A pipe through wall 1 (y = 0) or wall 3 (y = 15.85) at x, height z.
Anchor pipe(int unit, double x, double z, std::int64_t wall = 0) {
  Anchor a;
  a.unit = unit;
  a.floor = 0;
  const bool near_side = unit == 0 || unit == 1;
  a.wall_id = wall ? wall : (near_side ? 1 : 3);
  a.centre_m = Eigen::Vector3d(x, near_side ? 0.0 : 15.85, z);
  a.outward = Eigen::Vector2d(0.0, near_side ? -1.0 : 1.0);
  a.wall_thickness_m = 0.15;
  a.id = std::string("P").append(std::to_string(unit + 1));
  return a;
}

// Stage 0 at 3.5 m holding pipes at 0.45 m; stage 1 at 4.5 m on pipes at 1.45 m: U1
// moves from x = `u1_from` to x = `u1_to`, the others straight up.
std::pair<ClimbStage, ClimbStage> stages(double u1_from, double u1_to) {
  ClimbStage from, to;
  from.index = 0;
  from.platform_z_m = 3.5;
  from.last = {0, 29};
  from.top_m = 3.0;
  to.index = 1;
  to.platform_z_m = 4.5;
  const double xs[] = {u1_from, 29.6, 29.6, 0.6};
  for (int u = 0; u < 4; ++u) {
    from.anchors.push_back(pipe(u, xs[u], 0.45));
    to.anchors.push_back(pipe(u, u == 0 ? u1_to : xs[u], 1.45));
  }
  return {from, to};
}

const ClimbPhase* phase_of(const ClimbPlan& plan, ClimbPhase::Kind kind, int unit) {
  for (const auto& p : plan.phases)
    if (p.kind == kind && p.unit == unit) return &p;
  return nullptr;
}

TEST(Climb, AUnitDetoursRoundAWallInItsWay) {
  // A fin sticks 0.7 m out of wall 1 at x = 1.2 m, up to 2 m high (an opening takes its
  // top): U1's leg, hanging 1.15 m to 2.75 m from the ground, must go round its end.
  const Scene scene("        - {id: 5, x: 1.2, y: 0}\n        - {id: 6, x: 1.2, y: -0.7}\n",
                    "        - {id: 5, start: 5, end: 6}\n",
                    "        - {wall: 5, offset: 0, width: 0.7, sill: 2.0, head: 3.0}\n");
  const auto [from, to] = stages(0.6, 2.0);
  const ClimbPlan plan = plan_climb(climber(), scene.building(), from, to);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  const ClimbPhase* transit = phase_of(plan, ClimbPhase::Kind::kTransit, 0);
  ASSERT_NE(transit, nullptr);
  EXPECT_GE(transit->path.size(), 3u);  // not the straight line
  // The straight motion (in joint space) would have hit a wall: the same climb with it
  // is refused.
  ClimbPlan straight = plan;
  for (auto& p : straight.phases)
    if (p.kind == ClimbPhase::Kind::kTransit && p.unit == 0)
      p.path = {p.path.front(), p.path.back()};
  const ClimbStatus refused = verify_climb(climber(), scene.building(), from, to, straight);
  EXPECT_EQ(refused.code(), ClimbStatus::Code::kBlocked);
  EXPECT_TRUE(contains(refused.reason(), "phase 12 (transit): U1's link")) << refused.to_string();
  // The motion planned without the fin goes through it: the fin made the detour.
  const Scene bare;
  const ClimbPlan unaware = plan_climb(climber(), bare.building(), from, to);
  ASSERT_TRUE(unaware.status) << unaware.status.to_string();
  const ClimbStatus through = verify_climb(climber(), scene.building(), from, to, unaware);
  EXPECT_TRUE(contains(through.reason(), "wall 5 of floor 0")) << through.to_string();
  // The planned one passes the independent re-check at 5 mm.
  EXPECT_TRUE(verify_climb(climber(), scene.building(), from, to, plan))
      << verify_climb(climber(), scene.building(), from, to, plan).to_string();
}

TEST(Climb, TheLastPrintedLayerIsInTheScene) {
  // A 0.5 m fin of wall 5 stands only in the last layer printed from the stage (2.9 m to
  // 3 m; a door takes the rest of it), where U1's boom (2.75 m to 3 m from the ground)
  // swings on its way from x = 0.6 m to 2 m. Planned without the fin, the boom goes
  // through it; planned with it, round it.
  const std::string fin_vertices =
      "        - {id: 5, x: 1.2, y: 0}\n        - {id: 6, x: 1.2, y: -0.5}\n";
  const std::string fin_wall = "        - {id: 5, start: 5, end: 6}\n";
  const Scene scene(fin_vertices, fin_wall,
                    "        - {wall: 5, offset: 0, width: 0.5, sill: 0, head: 2.9}\n");
  const auto [from, to] = stages(0.6, 2.0);
  ASSERT_EQ(from.last.layer, 29);  // 2.9 m to 3 m
  const Scene bare;
  const ClimbPlan unaware = plan_climb(climber(), bare.building(), from, to);
  ASSERT_TRUE(unaware.status) << unaware.status.to_string();
  const ClimbStatus through = verify_climb(climber(), scene.building(), from, to, unaware);
  EXPECT_EQ(through.code(), ClimbStatus::Code::kBlocked) << through.to_string();
  EXPECT_TRUE(contains(through.reason(), "U1's link u1_boom touches wall 5 of floor 0"))
      << through.to_string();
  const ClimbPlan plan = plan_climb(climber(), scene.building(), from, to);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  EXPECT_TRUE(verify_climb(climber(), scene.building(), from, to, plan))
      << verify_climb(climber(), scene.building(), from, to, plan).to_string();
  // From a stage whose last layer is the one below, the fin is not built yet.
  ClimbStage earlier = from;
  earlier.last = {0, 28};
  earlier.top_m = 2.9;
  EXPECT_TRUE(verify_climb(climber(), scene.building(), earlier, to, unaware))
      << verify_climb(climber(), scene.building(), earlier, to, unaware).to_string();
}

TEST(Climb, AUnitBoxedInIsInfeasibleWithItsReason) {
  // The fin runs out past U1's mount: there is no way round it.
  const Scene scene("        - {id: 5, x: 1.2, y: 0}\n        - {id: 6, x: 1.2, y: -3.0}\n",
                    "        - {id: 5, start: 5, end: 6}\n",
                    "        - {wall: 5, offset: 0, width: 3.0, sill: 2.0, head: 3.0}\n");
  const auto [from, to] = stages(0.6, 2.0);
  const ClimbPlan plan = plan_climb(climber(), scene.building(), from, to);
  EXPECT_FALSE(plan.status);
  EXPECT_EQ(plan.status.code(), ClimbStatus::Code::kBlocked) << plan.status.to_string();
  EXPECT_TRUE(contains(plan.status.reason(), "transit of unit U1 to P1"))
      << plan.status.to_string();
  // The fin is named among what refused the planner's states.
  EXPECT_TRUE(contains(plan.status.reason(), "refused most by")) << plan.status.to_string();
  EXPECT_TRUE(contains(plan.status.reason(), "wall 5 of floor 0")) << plan.status.to_string();
  // What was planned before it is kept, and nothing after it.
  ASSERT_FALSE(plan.phases.empty());
  EXPECT_EQ(plan.phases.back().kind, ClimbPhase::Kind::kRelease);
}

TEST(Climb, ATransferThatWouldTipThePlatformIsRefused) {
  // Demand 3 m of stability margin: no place of the gantry gives it with one unit away.
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_tip_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string text = slurp(testing::source_path("config/machines/cc-climber.yaml"));
  text.replace(text.find("urdf: cc_climber.urdf"), 21,
               "urdf: " + testing::source_path("config/machines/cc_climber.urdf").string());
  text.replace(text.find("stability_margin_m: 0.3"), 23, "stability_margin_m: 3.0");
  std::ofstream(dir / "tippy.yaml") << text;
  const auto tippy = machine::load_machine_profile(dir / "tippy.yaml");
  fs::remove_all(dir);
  const Scene scene;
  const auto [from, to] = stages(0.6, 0.6);
  const ClimbPlan plan = plan_climb(*tippy.climbing, scene.building(), from, to);
  EXPECT_EQ(plan.status.code(), ClimbStatus::Code::kUnstable) << plan.status.to_string();
  EXPECT_TRUE(contains(plan.status.reason(), "with the gantry as counterweight"));
  // The default margin is met by moving the gantry: every transfer is preceded by it.
  const ClimbPlan fine = plan_climb(climber(), scene.building(), from, to);
  ASSERT_TRUE(fine.status) << fine.status.to_string();
  int balances = 0;
  for (const auto& p : fine.phases) balances += p.kind == ClimbPhase::Kind::kBalance;
  EXPECT_EQ(balances, 4);
}

// Signed distance from `p` to the edges of the triangle a, b, c (counter-clockwise),
// positive inside, m.
double inside_triangle_m(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  double inside = std::numeric_limits<double>::infinity();
  for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const Eigen::Vector2d d = (to - from).normalized();
    inside = std::min(inside, d.x() * (p - from).y() - d.y() * (p - from).x());
  }
  return inside;
}

TEST(Climb, TheReCheckKeepsTheCentreOfMassTheMarginInsideThePins) {
  // U1 out of its pipe: the platform stands on U2, U3 and U4, whose pins make a triangle
  // with its long edge from U4 (0.6, 15.85) to U2 (29.6, 0) across the middle of the
  // building. The gantry, parked, is placed along x so that the centre of mass is the
  // stability margin (0.3 m) inside that triangle plus or minus a millimetre; then U1's
  // pin is released. A millimetre inside the margin is refused as unstable, although the
  // centre of mass is inside the polygon.
  const machine::ClimbingMachine& m = climber();
  const machine::Kinematics& robot = *m.robot;
  ASSERT_DOUBLE_EQ(m.stability_margin_m, 0.3);
  const Scene scene;
  const auto [from, to] = stages(0.6, 0.6);
  const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, from.platform_z_m));
  // The machine as the re-check starts it: every unit's pin engaged in its pipe.
  std::vector<double> q = robot.zero();
  for (int u = 0; u < 4; ++u) {
    const Anchor& a = from.anchors[u];
    Eigen::Vector3d foot = a.centre_m;
    foot.head<2>() += a.outward * (0.5 * a.wall_thickness_m + m.pin_gap_m + m.foot_to_pin_m());
    const auto pose = m.unit_ik(u, platform, q, foot, -a.outward,
                                0.5 * a.wall_thickness_m + m.pin_gap_m + m.pin_past_centre_m);
    ASSERT_TRUE(pose);
    m.set_unit(u, *pose, q);
  }
  const int gx = m.gantry_joints[0], gy = m.gantry_joints[1], gz = m.gantry_joints[2];
  q[gz] = robot.joint_info(gz).upper;
  q[gy] = 0.5 * (robot.joint_info(gy).lower + robot.joint_info(gy).upper);
  const Eigen::Vector2d u2 = from.anchors[1].centre_m.head<2>(),
                        u3 = from.anchors[2].centre_m.head<2>(),
                        u4 = from.anchors[3].centre_m.head<2>();
  auto inside_at = [&](double x) {
    std::vector<double> at = q;
    at[gx] = x;
    const Eigen::Vector3d com = robot.centre_of_mass(robot.link_poses(platform, at));
    return inside_triangle_m(com.head<2>(), u2, u3, u4);
  };
  // The centre of mass moves linearly with the gantry: where is it the margin inside?
  const double x0 = q[gx], x1 = x0 + 1.0;
  const double per_m = inside_at(x1) - inside_at(x0);
  ASSERT_GT(per_m, 0.01);
  auto plan_at = [&](double inside_m) {
    const double x = x0 + (inside_m - inside_at(x0)) / per_m;
    EXPECT_NEAR(inside_at(x), inside_m, 1e-9);
    EXPECT_GE(x, robot.joint_info(gx).lower);
    EXPECT_LE(x, robot.joint_info(gx).upper);
    ClimbPlan plan;
    auto phase = [&](ClimbPhase::Kind kind, int unit, const std::vector<int>& joints,
                     const std::vector<double>& state) {
      ClimbPhase p;
      p.kind = kind;
      p.unit = unit;
      for (int j : joints) p.joints.push_back(robot.joint_info(j).name);
      p.path = {state, state};
      p.t_s = {0.0, 1.0};
      plan.phases.push_back(p);
    };
    const int pin = m.units[0].joints[4];
    phase(ClimbPhase::Kind::kPark, -1, {gz}, {q[gz]});
    phase(ClimbPhase::Kind::kBalance, 0, {gx, gy}, {x, q[gy]});
    phase(ClimbPhase::Kind::kRelease, 0, {pin}, {q[pin]});
    return plan;
  };
  const ClimbStatus outside_margin =
      verify_climb(m, scene.building(), from, to, plan_at(0.3 + 1e-3));
  EXPECT_TRUE(outside_margin) << outside_margin.to_string();
  const ClimbStatus within_margin =
      verify_climb(m, scene.building(), from, to, plan_at(0.3 - 1e-3));
  EXPECT_EQ(within_margin.code(), ClimbStatus::Code::kUnstable) << within_margin.to_string();
  EXPECT_TRUE(contains(within_margin.reason(),
                       "phase 3 (release): unstable: the centre of mass is 0.30 m inside the "
                       "holding pins' polygon (the margin is 0.30 m)"))
      << within_margin.to_string();
}

TEST(Climb, APinGoesIntoAWallOnlyAlongItsPipe) {
  // A planned climb re-checked with U1's new pipe declared a few millimetres along the
  // wall from where its pin goes in: within 5 mm of the pipe's axis the pin enters it,
  // further off it goes into solid wall.
  const Scene scene;
  const auto [from, to] = stages(0.6, 0.6);
  const ClimbPlan plan = plan_climb(climber(), scene.building(), from, to);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  for (const double off_m : {0.004, 0.006}) {
    ClimbStage moved = to;
    moved.anchors[0].centre_m.x() += off_m;
    const ClimbStatus checked = verify_climb(climber(), scene.building(), from, moved, plan);
    if (off_m < 0.005) {
      EXPECT_TRUE(checked) << off_m << ": " << checked.to_string();
    } else {
      EXPECT_EQ(checked.code(), ClimbStatus::Code::kBlocked) << off_m;
      EXPECT_TRUE(
          contains(checked.reason(), "(insert): U1's link u1_pin touches wall 1 of floor 0"))
          << checked.to_string();
    }
  }
}

class Apartment : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    building_ = new floors::Building(
        floors::load_building(testing::source_path("config/buildings/apartment.yaml")));
    stages_ = new StagePlan(climb_stages(*building_, climber()));
  }
  static void TearDownTestSuite() {
    delete building_;
    delete stages_;
  }
  static floors::Building* building_;
  static StagePlan* stages_;
};
floors::Building* Apartment::building_ = nullptr;
StagePlan* Apartment::stages_ = nullptr;

TEST_F(Apartment, EveryClimbPlansAndPassesTheFineReCheck) {
  ASSERT_TRUE(stages_->status) << stages_->status.to_string();
  const auto& stages = stages_->stages;
  ASSERT_EQ(stages.size(), 5u);
  EXPECT_EQ(stages.back().last.floor, 4);  // the whole building is printed
  for (std::size_t k = 0; k + 1 < stages.size(); ++k) {
    const ClimbPlan plan = plan_climb(climber(), *building_, stages[k], stages[k + 1]);
    ASSERT_TRUE(plan.status) << "climb " << k << ": " << plan.status.to_string();
    EXPECT_EQ(plan.phases.size(), 18u);  // park, 4 x (balance, release, transit, insert), lift
    const ClimbStatus checked = verify_climb(climber(), *building_, stages[k], stages[k + 1], plan);
    EXPECT_TRUE(checked) << "climb " << k << ": " << checked.to_string();
    // Lifts at the loaded stroke speed: 20 to 30 minutes, as climbing formwork.
    const ClimbPhase& lift = plan.phases.back();
    EXPECT_EQ(lift.kind, ClimbPhase::Kind::kLift);
    EXPECT_GE(lift.duration_s, 20 * 60.0);
    EXPECT_LE(lift.duration_s, 30 * 60.0);
    EXPECT_EQ(
        lift.strokes,
        static_cast<int>(std::ceil((stages[k + 1].platform_z_m - stages[k].platform_z_m) / 0.5)));
  }
}

TEST_F(Apartment, TheReCheckRefusesAPathBeyondALimitOrThroughAWall) {
  const auto& stages = stages_->stages;
  ASSERT_GE(stages.size(), 2u);
  const ClimbPlan plan = plan_climb(climber(), *building_, stages[1], stages[2]);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  const machine::ClimbingMachine& m = climber();
  // A release that draws U1's pin 1 cm further back than its joint allows (away from the
  // wall: nothing else is wrong with it).
  ClimbPlan beyond = plan;
  for (auto& p : beyond.phases)
    if (p.kind == ClimbPhase::Kind::kRelease && p.unit == 0)
      p.path.insert(p.path.end() - 1, {-0.01});
  const ClimbStatus refused = verify_climb(m, *building_, stages[1], stages[2], beyond);
  EXPECT_FALSE(refused);
  EXPECT_TRUE(contains(refused.reason(), "joint u1_pin_slide leaves its limits"))
      << refused.to_string();
  // To its very end (0) is within.
  ClimbPlan at_end = plan;
  for (auto& p : at_end.phases)
    if (p.kind == ClimbPhase::Kind::kRelease && p.unit == 0) p.path.insert(p.path.end() - 1, {0.0});
  EXPECT_TRUE(verify_climb(m, *building_, stages[1], stages[2], at_end));
  // The stroke run down to the ground: the foot goes through the floor's walls or beyond
  // the stroke's margin, either way refused.
  ClimbPlan down = plan;
  for (auto& p : down.phases)
    if (p.kind == ClimbPhase::Kind::kTransit && p.unit == 0) {
      std::vector<double> mid = p.path.front();
      mid[3] = m.robot->joint_info(m.units[0].joints[3]).upper;
      p.path.insert(p.path.begin() + 1, mid);
    }
  EXPECT_FALSE(verify_climb(m, *building_, stages[1], stages[2], down));
}

TEST_F(Apartment, TheSetbackIsClimbedWithSwingAndReach) {
  // The top floors end at 96 ft: U2 and U3 move from pipes at 97 ft to pipes at 94 ft.
  const auto& stages = stages_->stages;
  ASSERT_EQ(stages.size(), 5u);
  const ClimbStage& from = stages[3];
  const ClimbStage& to = stages[4];
  EXPECT_NEAR(from.anchors[1].centre_m.x() - to.anchors[1].centre_m.x(), 3 * 0.3048, 1e-6);
  const ClimbPlan plan = plan_climb(climber(), *building_, from, to);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  const ClimbPhase* transit = phase_of(plan, ClimbPhase::Kind::kTransit, 1);
  ASSERT_NE(transit, nullptr);
  // Swing and reach change on the way (joints: swing, reach, wrist, stroke).
  EXPECT_GT(std::abs(transit->path.back()[0] - transit->path.front()[0]), 0.1);
  EXPECT_GT(std::abs(transit->path.back()[1] - transit->path.front()[1]), 0.1);
}

TEST_F(Apartment, TheSameSeedGivesTheSameMotions) {
  const auto& stages = stages_->stages;
  ASSERT_GE(stages.size(), 5u);
  const ClimbPlan a = plan_climb(climber(), *building_, stages[3], stages[4], {7, 10.0});
  const ClimbPlan b = plan_climb(climber(), *building_, stages[3], stages[4], {7, 10.0});
  ASSERT_EQ(a.phases.size(), b.phases.size());
  for (std::size_t k = 0; k < a.phases.size(); ++k) EXPECT_EQ(a.phases[k].path, b.phases[k].path);
  EXPECT_EQ(a.duration_s, b.duration_s);
}

TEST_F(Apartment, PipesAreAsLowAsTheLegsAllowAndOnSolidWall) {
  const auto& stages = stages_->stages;
  const machine::ClimbingMachine& m = climber();
  const auto& stroke = m.robot->joint_info(m.units[0].joints[3]);
  const double foot_at_zero =
      m.robot->link_poses(Eigen::Isometry3d::Identity(), m.robot->zero())[m.units[0].foot_link]
          .translation()
          .z();
  const double layer = building_->layer_height_m;
  for (std::size_t k = 1; k < stages.size(); ++k) {
    // The lowest a pipe may be: the legs at full stroke after the lift.
    const double low =
        stages[k].platform_z_m + foot_at_zero - (stroke.upper - m.stroke_end_margin_m);
    for (const auto& a : stages[k].anchors) {
      EXPECT_GE(a.centre_m.z(), low - 1e-9) << a.id;
      EXPECT_LT(a.centre_m.z() - layer, low) << a.id << ": a layer lower would do";
      // Cast in a layer printed before the climb.
      const auto& last = stages[k - 1].last;
      EXPECT_TRUE(a.floor < last.floor || (a.floor == last.floor && a.layer <= last.layer));
    }
  }
}

// The apartment without its anchor points (a copy of config/, the anchors taken out of
// the building file), so that the default rule places the pipes.
floors::Building apartment_without_anchors() {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_rule_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(testing::source_path("config"), dir / "config", fs::copy_options::recursive);
  const fs::path file = dir / "config" / "buildings" / "apartment.yaml";
  std::istringstream in(slurp(file));
  std::string kept, line;
  while (std::getline(in, line))
    if (line.find("anchors:") == std::string::npos && line.rfind("      - {id: A", 0) != 0)
      kept += line + "\n";
  std::ofstream(file) << kept;
  floors::Building bare = floors::load_building(file);
  fs::remove_all(dir);
  return bare;
}

// The bundled climber with four more units (copies of U1 and U4 mounted further along
// the long beams), in a temporary folder.
machine::MachineProfile eight_unit_climber() {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_eight_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string urdf = slurp(testing::source_path("config/machines/cc_climber.urdf"));
  std::string profile = slurp(testing::source_path("config/machines/cc-climber.yaml"));
  // A unit's block: its lines, from its base link to its pin's joint.
  auto block_of = [&](const std::string& unit) {
    const auto begin = urdf.rfind('\n', urdf.find("<link name=\"" + unit + "_base\"")) + 1;
    const auto end = urdf.find('\n', urdf.find("<joint name=\"" + unit + "_pin_slide\"")) + 1;
    return urdf.substr(begin, end - begin);
  };
  const std::string u1 = block_of("u1"), u4 = block_of("u4");
  std::string more, units;
  const struct {
    const char* name;
    const std::string* from;
    const char* from_xyz;
    const char* xyz;
  } added[] = {{"u5", &u1, "0.6 -1.2 0", "10.6 -1.2 0"},
               {"u6", &u4, "0.6 17.05 0", "10.6 17.05 0"},
               {"u7", &u1, "0.6 -1.2 0", "20.1 -1.2 0"},
               {"u8", &u4, "0.6 17.05 0", "20.1 17.05 0"}};
  for (const auto& a : added) {
    std::string b = *a.from;
    const std::string old_name = a.from == &u1 ? "u1_" : "u4_";
    for (auto at = b.find(old_name); at != std::string::npos; at = b.find(old_name, at))
      b.replace(at, old_name.size(), std::string(a.name) + "_");
    b.replace(b.find(a.from_xyz), std::string(a.from_xyz).size(), a.xyz);
    more += b;
    const std::string n = a.name;
    units += "    - {name: U" + n.substr(1) + ", swing: " + n + "_swing, reach: " + n +
             "_reach, wrist: " + n + "_wrist_yaw, stroke: " + n + "_stroke, pin: " + n +
             "_pin_slide}\n";
  }
  urdf.insert(urdf.find("</robot>"), more);
  profile.insert(profile.find("  units_per_transfer:"), units);
  std::ofstream(dir / "cc_climber.urdf") << urdf;
  std::ofstream(dir / "cc-climber.yaml") << profile;
  machine::MachineProfile out = machine::load_machine_profile(dir / "cc-climber.yaml");
  fs::remove_all(dir);
  return out;
}

TEST(Climb, EightUnitsClimbInTheirMostStableOrder) {
  // 8! orders are too many to try: the units go one by one, the most stable next.
  const machine::MachineProfile eight = eight_unit_climber();
  ASSERT_EQ(eight.climbing->units.size(), 8u);
  const floors::Building bare = apartment_without_anchors();
  const StagePlan stages = climb_stages(bare, *eight.climbing);
  ASSERT_TRUE(stages.status) << stages.status.to_string();
  ASSERT_GE(stages.stages.size(), 2u);
  const ClimbPlan plan = plan_climb(*eight.climbing, bare, stages.stages[0], stages.stages[1]);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  std::vector<int> transferred;
  for (const auto& p : plan.phases)
    if (p.kind == ClimbPhase::Kind::kTransit) transferred.push_back(p.unit);
  std::sort(transferred.begin(), transferred.end());
  EXPECT_EQ(transferred, std::vector<int>({0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_TRUE(verify_climb(*eight.climbing, bare, stages.stages[0], stages.stages[1], plan));
}

TEST(Climb, TheDefaultRuleKeepsPipesClearOfAWindowAbove) {
  // A 6 m storey, one climb; windows (sills at 2 m) in walls 1 and 4 up to 1.5 m from
  // their corner, right where U1's nearest pipe would be: the pipe goes 0.3 m past the
  // window's edge.
  const Scene scene("", "",
                    "        - {wall: 1, offset: 0.3, width: 1.2, sill: 2.0, head: 3.0}\n"
                    "        - {wall: 4, offset: 14.35, width: 1.2, sill: 2.0, head: 3.0}\n",
                    6.0);
  const StagePlan plan = climb_stages(scene.building(), climber());
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  ASSERT_GE(plan.stages.size(), 2u);
  const Anchor& u1 = plan.stages[1].anchors[0];
  EXPECT_EQ(u1.wall_id, 1);
  EXPECT_LT(u1.centre_m.z(), 2.0);  // below the sill: the layer itself is solid there
  EXPECT_GE(u1.centre_m.x(), 1.5 + 0.3 - 1e-9);
  EXPECT_LT(u1.centre_m.x(), 1.5 + 0.3 + 0.05);  // the nearest allowed, on the 5 cm grid
}

TEST(Climb, TheDefaultRuleKeepsPipesOnSolidWallAwayFromEnds) {
  // The apartment without anchor points: the rule places them.
  const floors::Building bare = apartment_without_anchors();
  for (const auto& f : bare.floors) ASSERT_TRUE(f.anchors.empty());
  const StagePlan plan = climb_stages(bare, climber());
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  int checked = 0;
  for (const auto& stage : plan.stages) {
    for (const auto& a : stage.anchors) {
      if (a.floor < 0) continue;
      EXPECT_TRUE(a.by_default_rule);
      // On a piece of that layer, at least 0.3 m from its ends (wall ends, corners,
      // openings' edges).
      const auto layers = floors::slice_floor(bare.floors[a.floor], bare.layer_height_m);
      const floors::Layer& layer = layers[a.layer];
      bool on_solid = false;
      for (const auto& s : layer.segments) {
        if (s.wall_id != a.wall_id) continue;
        const Eigen::Vector2d p = layer.start_m(s), q = layer.end_m(s);
        const double t = (a.centre_m.head<2>() - p).dot((q - p).normalized());
        const double off = std::abs((q - p).normalized().x() * (a.centre_m.y() - p.y()) -
                                    (q - p).normalized().y() * (a.centre_m.x() - p.x()));
        if (off < 1e-6 && t >= 0.3 - 1e-9 && t <= s.length_m - 0.3 + 1e-9) on_solid = true;
      }
      EXPECT_TRUE(on_solid) << a.id;
      // And clear of every opening's width on that wall, windows above it included.
      const floors::FloorPlan& plan = bare.floors[a.floor].plan;
      const double along =
          (a.centre_m.head<2>() - plan.wall_start_m(*plan.find_wall(a.wall_id))).norm();
      for (const auto& o : plan.openings) {
        if (o.wall_id != a.wall_id) continue;
        EXPECT_TRUE(along <= o.offset_m - 0.3 + 1e-9 ||
                    along >= o.offset_m + o.width_m + 0.3 - 1e-9)
            << a.id << " under opening " << o.id;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 16);  // 4 climbs, 4 pipes each
}

}  // namespace
}  // namespace ccbuild::climb

namespace ccbuild::climb {
namespace {

// Climbs between floors by default: every stage but the last ends at a floor's top layer;
// a building asking for climbs within a storey gets stages as high as the legs allow, one
// of which ends part-way up a floor, and fewer or as many climbs.
TEST(Stages, BetweenFloorsByDefaultWithinAStoreyWhenAsked) {
  floors::Building b =
      floors::load_building(testing::source_path("config/buildings/apartment.yaml"));
  ASSERT_FALSE(b.climbs_within_storey);
  const StagePlan between = climb_stages(b, climber());
  ASSERT_TRUE(between.status) << between.status.to_string();
  std::map<int, int> top_layer;
  for (const auto& floor : b.floors)
    top_layer[floor.index] =
        static_cast<int>(floors::slice_floor(floor, b.layer_height_m).size()) - 1;
  for (std::size_t s = 0; s + 1 < between.stages.size(); ++s)
    EXPECT_EQ(between.stages[s].last.layer, top_layer[between.stages[s].last.floor])
        << "stage " << s;
  b.climbs_within_storey = true;
  const StagePlan within = climb_stages(b, climber());
  ASSERT_TRUE(within.status) << within.status.to_string();
  bool part_way = false;
  for (std::size_t s = 0; s + 1 < within.stages.size(); ++s)
    part_way |= within.stages[s].last.layer != top_layer[within.stages[s].last.floor];
  EXPECT_TRUE(part_way);
  EXPECT_LE(within.stages.size(), between.stages.size());
}

TEST(Stages, TheClimbsKeyTakesTwoValues) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_climbs_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string config = testing::source_path("config").string();
  auto building =
      [&](const std::string& climbs) {
        std::ofstream(dir / "b.yaml")
            << "units: m\nlayer_height: 0.5\nclimbs: " << climbs << "\nmaterial: " << config
            << "/materials/standard-mix.yaml\nmachine: " << config
            << "/machines/cc-climber.yaml\nfloors:\n  - height: 3\n    plan:\n"
               "      vertices: [{id: 1, x: 0, y: 0}, {id: 2, x: 4, y: 0}]\n"
               "      walls: [{id: 1, start: 1, end: 2}]\n";
        return floors::load_building(dir / "b.yaml");
      };
  EXPECT_TRUE(building("within-storey").climbs_within_storey);
  EXPECT_FALSE(building("between-floors").climbs_within_storey);
  try {
    building("whenever");
    ADD_FAILURE() << "accepted climbs: whenever";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "b.yaml:3")) << e.what();
    EXPECT_TRUE(contains(e.what(), "expected between-floors")) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::climb
