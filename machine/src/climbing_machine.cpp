#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/climbing_machine.hpp"
#include "climbing_internal.hpp"

namespace ccbuild::machine {
namespace {

// Plausible ranges of the climbing section (docs/formats.md).
const Range kStrokeMargin_m = Range::closed(0.0, 0.2);
const Range kLoadedSpeed_m_s = Range::above(0.0, 0.05);
const Range kStroke_m = Range::above(0.0, 5.0);
const Range kTime_s = Range::closed(0.0, 3600.0);
const Range kShort_m = Range::closed(0.0, 1.0);
const Range kReach_m = Range::closed(0.0, 20.0);
const Range kMargin_m = Range::closed(0.0, 5.0);
const Range kLinkMass_kg = Range::above(0.0, 1.0e6);
const Range kJointSpeed = Range::above(0.0, 20.0);  // m/s or rad/s
constexpr int kMaxUnits = 16;

double wrap(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

struct Reader {
  const UrdfInfo& urdf;
  const Kinematics& robot;
  std::string file() const { return urdf.source_file; }

  // A joint the profile names: it exists, has the type and axis expected, and limits the
  // right way round.
  int joint(const Field& field, const char* role, const std::vector<std::string>& types,
            const Eigen::Vector3d& axis) const {
    const std::string name = field.as_string();
    const int j = robot.joint(name);
    if (j < 0) field.fail("URDF " + file() + " has no joint '" + name + "' (the " + role + ")");
    const JointInfo& info = robot.joint_info(j);
    std::string label = "joint '" + name + "' in " + file();
    if (info.line > 0) label.append(":").append(std::to_string(info.line));
    bool type_ok = false;
    for (const auto& t : types) type_ok |= info.type == t;
    if (!type_ok)
      field.fail(label + " is " + info.type + ", expected " + types.front() + " (the " + role +
                 ")");
    const Eigen::Vector3d a =
        info.axis.norm() > 0 ? info.axis.normalized() : Eigen::Vector3d::Zero();
    if (a.dot(axis) < 0.999)
      field.fail(label + " moves along (" + plain_number(a.x()) + ", " + plain_number(a.y()) +
                 ", " + plain_number(a.z()) + "), expected (" + plain_number(axis.x()) + ", " +
                 plain_number(axis.y()) + ", " + plain_number(axis.z()) + ") for the " + role);
    if (!info.has_limits)
      field.fail(label + " has no <limit>; the " + role + "'s range and speed come from it");
    if (info.lower > info.upper)
      throw InputError(file(), info.line, "joint[" + name + "].limit",
                       "limits the wrong way round: lower " + plain_number(info.lower) +
                           " is above upper " + plain_number(info.upper) + " (the " + role +
                           " of " + field.path() + ")");
    const bool revolute = info.type == "revolute";
    const Range range =
        revolute ? Range::closed(-20.0 * M_PI, 20.0 * M_PI) : Range::closed(-100.0, 100.0);
    for (const double limit : {info.lower, info.upper}) {
      const std::string wrong = range.violation(limit, plain_number(limit), revolute ? "rad" : "m");
      if (!wrong.empty())
        throw InputError(file(), info.line, "joint[" + name + "].limit",
                         wrong + " (the " + role + ")");
    }
    const std::string slow = kJointSpeed.violation(info.velocity, plain_number(info.velocity), "");
    if (!slow.empty())
      throw InputError(file(), info.line, "joint[" + name + "].limit.velocity", slow);
    return j;
  }
};

}  // namespace

namespace detail {

std::shared_ptr<const ClimbingMachine> read_climbing(
    const Field& field, const UrdfInfo& urdf, const MachineModel& gantry,
    const std::array<std::string, 4>& gantry_joints) {
  MapReader map(
      field, {"platform", "units", "units_per_transfer", "nozzle_reach_below_m",
              "nozzle_reach_above_m", "stroke_end_margin_m", "stroke_speed_loaded_m_s",
              "lift_per_stroke_m", "stroke_reset_s", "pin_insert_s", "pin_release_s", "pin_gap_m",
              "pin_past_centre_m", "anchor_strength_mpa", "anchor_clearance_m", "pipe_embed_s",
              "foundation_anchor_depth_m", "stability_margin_m", "climb_wind_limit_m_s"});
  map.reject_unknown();
  auto machine = std::make_shared<ClimbingMachine>();
  ClimbingMachine& m = *machine;
  m.name = gantry.name;
  m.gantry = gantry;
  m.files_read = gantry.files_read;
  m.robot = std::make_shared<const Kinematics>(urdf);
  const Kinematics& robot = *m.robot;
  const Reader reader{urdf, robot};

  const Field platform = map.required("platform");
  if (platform.as_string() != urdf.root_link)
    platform.fail("the platform must be the URDF's root link '" + urdf.root_link + "', got '" +
                  echoed(platform.as_string()) + "'");
  for (int k = 0; k < 4; ++k) m.gantry_joints[k] = robot.joint(gantry_joints[k]);
  const int bridge = robot.link(robot.joint_info(m.gantry_joints[0]).child_link);
  for (int l = 0; l < robot.link_count(); ++l)
    if (robot.is_ancestor(bridge, l)) m.gantry_links.push_back(l);

  // Every link of the machine must have collision geometry: what has none cannot be
  // checked against the walls.
  // And a mass: the statics of every transfer sum them.
  for (const auto& link : urdf.links) {
    if (link.collisions.empty())
      throw InputError(urdf.source_file, link.line, "link[" + link.name + "]",
                       "has no collision geometry (box, cylinder or sphere); every link of a "
                       "climbing machine is checked against the walls");
    const std::string light =
        kLinkMass_kg.violation(link.mass_kg, plain_number(link.mass_kg) + " kg", "kg");
    if (!light.empty())
      throw InputError(urdf.source_file, link.line, "link[" + link.name + "].inertial.mass",
                       light +
                           " (no <inertial> counts as 0); the platform's statics weigh every "
                           "link of a climbing machine");
  }

  const Field units = map.required("units");
  const auto items = units.items();
  if (items.size() < 3 || items.size() > static_cast<std::size_t>(kMaxUnits))
    units.fail("a climbing machine has 3 to " + std::to_string(kMaxUnits) + " units, got " +
               std::to_string(items.size()));
  // Each unit is its own chain: a name or joint used twice would make two units one.
  std::map<int, std::string> joint_owner;
  for (int k = 0; k < 4; ++k) joint_owner[m.gantry_joints[k]] = "the printing gantry";
  for (const Field& item : items) {
    MapReader um(item, {"name", "swing", "reach", "wrist", "stroke", "pin"});
    um.reject_unknown();
    ClimbingUnit unit;
    unit.name = um.required("name").as_string();
    for (const auto& other : m.units)
      if (other.name == unit.name)
        um.required("name").fail("unit name '" + unit.name +
                                 "' is used twice; each unit has its own");
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), x = Eigen::Vector3d::UnitX();
    unit.joints = {reader.joint(um.required("swing"), "swing", {"revolute"}, z),
                   reader.joint(um.required("reach"), "reach", {"prismatic"}, x),
                   reader.joint(um.required("wrist"), "wrist", {"revolute"}, z),
                   reader.joint(um.required("stroke"), "stroke", {"prismatic"}, -z),
                   reader.joint(um.required("pin"), "pin", {"prismatic"}, x)};
    static const char* roles[] = {"swing", "reach", "wrist", "stroke", "pin"};
    for (int k = 0; k < 5; ++k) {
      const auto [it, fresh] = joint_owner.emplace(unit.joints[k], "unit " + unit.name);
      if (!fresh)
        um.required(roles[k]).fail("joint '" + robot.joint_info(unit.joints[k]).name +
                                   "' is already " + it->second +
                                   "'s; each unit moves joints of its own");
    }
    // A chain: each joint's child link is the next one's parent.
    for (int k = 0; k + 1 < 5; ++k) {
      const JointInfo& a = robot.joint_info(unit.joints[k]);
      const JointInfo& b = robot.joint_info(unit.joints[k + 1]);
      if (a.child_link != b.parent_link)
        um.required(roles[k + 1])
            .fail("joint '" + b.name + "' hangs from link '" + b.parent_link + "', not from the " +
                  roles[k] + "'s link '" + a.child_link +
                  "': a unit is a chain swing, reach, wrist, stroke, pin");
    }
    // The reach, wrist and stroke are mounted along the boom and the leg, without a
    // sideways offset; the pin leaves the foot along its own axis.
    for (int k : {1, 2}) {
      const Eigen::Vector3d o = robot.joint_info(unit.joints[k]).origin.translation();
      if (std::abs(o.y()) > 1e-9)
        um.required(roles[k]).fail("joint '" + robot.joint_info(unit.joints[k]).name +
                                   "' is offset sideways from the boom (origin y " +
                                   plain_number(o.y()) + " m); ccbuild solves chains without");
    }
    const Eigen::Vector3d stroke_origin = robot.joint_info(unit.joints[3]).origin.translation();
    if (stroke_origin.head<2>().norm() > 1e-9)
      um.required("stroke").fail("the leg must hang straight below the wrist (origin x, y = 0)");
    const Eigen::Isometry3d pin_origin = robot.joint_info(unit.joints[4]).origin;
    if (std::abs(pin_origin.translation().y()) > 1e-9 ||
        std::abs(pin_origin.translation().z()) > 1e-9)
      um.required("pin").fail(
          "the pin must slide out of the foot along its x axis (origin y, z = 0)");
    m.foot_to_pin_m_ = pin_origin.translation().x();
    unit.foot_link = robot.link(robot.joint_info(unit.joints[3]).child_link);
    unit.pin_link = robot.link(robot.joint_info(unit.joints[4]).child_link);
    const int turret = robot.link(robot.joint_info(unit.joints[0]).child_link);
    for (int l = 0; l < robot.link_count(); ++l)
      if (robot.is_ancestor(turret, l)) unit.links.push_back(l);
    m.units.push_back(unit);
  }

  if (auto v = map.optional("units_per_transfer")) {
    m.units_per_transfer = static_cast<int>(v->as_count());
    if (m.units_per_transfer < 1 || m.units_per_transfer > static_cast<int>(m.units.size()) - 3)
      v->fail("must be from 1 to " + std::to_string(m.units.size() - 3) + " for " +
              std::to_string(m.units.size()) + " units" +
              " (at least 3 units hold the platform while the others move)");
  }
  m.nozzle_reach_below_m = map.required("nozzle_reach_below_m").as_number_in(kReach_m, "m");
  m.nozzle_reach_above_m =
      map.required("nozzle_reach_above_m").as_number_in(Range::closed(-20.0, 20.0), "m");
  // The printing window must lie within the nozzle's z travel (relative to the platform).
  if (-m.nozzle_reach_below_m < gantry.z.min_m - 1e-9 ||
      m.nozzle_reach_above_m > gantry.z.max_m + 1e-9 ||
      m.nozzle_reach_above_m <= -m.nozzle_reach_below_m)
    map.required("nozzle_reach_below_m")
        .fail("the printing window " + plain_number(-m.nozzle_reach_below_m) + " to " +
              plain_number(m.nozzle_reach_above_m) + " m must lie within the z joint's travel " +
              plain_number(gantry.z.min_m) + " to " + plain_number(gantry.z.max_m) +
              " m (relative to the platform)");
  auto number = [&](const char* key, double& out, const Range& range, const char* unit) {
    if (auto f = map.optional(key)) out = f->as_number_in(range, unit);
  };
  number("stroke_end_margin_m", m.stroke_end_margin_m, kStrokeMargin_m, "m");
  m.stroke_speed_loaded_m_s =
      map.required("stroke_speed_loaded_m_s").as_number_in(kLoadedSpeed_m_s, "m/s");
  number("lift_per_stroke_m", m.lift_per_stroke_m, kStroke_m, "m");
  number("stroke_reset_s", m.stroke_reset_s, kTime_s, "s");
  m.pin_insert_s = map.required("pin_insert_s").as_number_in(kTime_s, "s");
  m.pin_release_s = map.required("pin_release_s").as_number_in(kTime_s, "s");
  number("pin_gap_m", m.pin_gap_m, kShort_m, "m");
  number("pin_past_centre_m", m.pin_past_centre_m, kShort_m, "m");
  number("anchor_strength_mpa", m.anchor_strength_mpa, kAnchorStrength_mpa, "MPa");
  number("anchor_clearance_m", m.anchor_clearance_m, kShort_m, "m");
  number("pipe_embed_s", m.pipe_embed_s, kTime_s, "s");
  number("foundation_anchor_depth_m", m.foundation_anchor_depth_m, kShort_m, "m");
  number("stability_margin_m", m.stability_margin_m, kMargin_m, "m");
  number("climb_wind_limit_m_s", m.climb_wind_limit_m_s, Range::above(0.0, 60.0), "m/s");

  // Every unit's chain must solve: a round trip through its inverse kinematics at a pose
  // within its limits proves the chain is the shape ccbuild assumes.
  const std::vector<double> q0 = robot.zero();
  for (int u = 0; u < static_cast<int>(m.units.size()); ++u) {
    std::vector<double> q = q0;
    UnitPose mid{};
    for (int k = 0; k < 5; ++k) {
      const JointInfo& j = robot.joint_info(m.units[u].joints[k]);
      mid[k] = 0.5 * (j.lower + j.upper);
    }
    m.set_unit(u, mid, q);
    const auto poses = robot.link_poses(Eigen::Isometry3d::Identity(), q);
    const Eigen::Isometry3d& foot = poses[m.units[u].foot_link];
    const Eigen::Vector3d axis = foot.linear() * Eigen::Vector3d::UnitX();
    const auto solved = m.unit_ik(u, Eigen::Isometry3d::Identity(), q, foot.translation(),
                                  axis.head<2>().normalized(), mid[4]);
    bool same = solved.has_value();
    for (int k = 0; same && k < 5; ++k)
      same =
          std::abs(k == 0 || k == 2 ? wrap((*solved)[k] - mid[k]) : (*solved)[k] - mid[k]) < 1e-6;
    if (!same)
      units.fail("unit '" + m.units[u].name +
                 "': its joints do not form the chain ccbuild solves (swing about z, reach "
                 "along the boom, wrist about z, stroke straight down, pin along the foot)");
  }
  return machine;
}

}  // namespace detail

void ClimbingMachine::set_unit(int u, const UnitPose& pose, std::vector<double>& q) const {
  for (int k = 0; k < 5; ++k) q[units[u].joints[k]] = pose[k];
}

UnitPose ClimbingMachine::get_unit(int u, const std::vector<double>& q) const {
  UnitPose pose{};
  for (int k = 0; k < 5; ++k) pose[k] = q[units[u].joints[k]];
  return pose;
}

std::pair<double, double> ClimbingMachine::usable_range(int joint) const {
  const JointInfo& j = robot->joint_info(joint);
  double margin = 0.0;
  for (const auto& unit : units)
    if (unit.joints[3] == joint) margin = stroke_end_margin_m;
  return {j.lower + margin, j.upper - margin};
}

bool ClimbingMachine::unit_within_limits(int u, const UnitPose& pose) const {
  for (int k = 0; k < 5; ++k) {
    const auto [lower, upper] = usable_range(units[u].joints[k]);
    if (pose[k] < lower - 1e-12 || pose[k] > upper + 1e-12) return false;
  }
  return true;
}

std::optional<UnitPose> ClimbingMachine::unit_ik(int u, const Eigen::Isometry3d& platform,
                                                 const std::vector<double>& q_in,
                                                 const Eigen::Vector3d& foot_m,
                                                 const Eigen::Vector2d& pin_direction,
                                                 double pin_m) const {
  const ClimbingUnit& unit = units[u];
  const Kinematics& k = *robot;
  std::vector<double> q = q_in;
  set_unit(u, {0.0, 0.0, 0.0, 0.0, pin_m}, q);
  const auto poses = k.link_poses(platform, q);
  const JointInfo& swing = k.joint_info(unit.joints[0]);
  const Eigen::Isometry3d swing_frame = poses[k.link(swing.parent_link)] * swing.origin;
  const Eigen::Vector3d s = swing_frame.translation();
  // At zero: where the wrist's axis is, and where the pin points.
  const JointInfo& wrist = k.joint_info(unit.joints[2]);
  const Eigen::Vector3d w0 = (poses[k.link(wrist.parent_link)] * wrist.origin).translation();
  const Eigen::Vector3d boom = swing_frame.linear() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d pin0 = poses[unit.foot_link].linear() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d foot0 = poses[unit.foot_link].translation();
  const Eigen::Vector2d boom_h = boom.head<2>();
  if (boom_h.norm() < 1e-9 || pin_direction.norm() < 1e-9) return std::nullopt;
  const double along0 = (w0 - s).head<2>().dot(boom_h.normalized());
  const Eigen::Vector2d to_foot = foot_m.head<2>() - s.head<2>();
  UnitPose pose{};
  pose[0] = wrap(std::atan2(to_foot.y(), to_foot.x()) - std::atan2(boom_h.y(), boom_h.x()));
  pose[1] = to_foot.norm() - along0;
  pose[2] = wrap(std::atan2(pin_direction.y(), pin_direction.x()) - std::atan2(pin0.y(), pin0.x()) -
                 pose[0]);
  pose[3] = foot0.z() - foot_m.z();
  pose[4] = pin_m;
  // Confirm by forward kinematics.
  set_unit(u, pose, q);
  const auto check = k.link_poses(platform, q);
  const Eigen::Vector3d foot = check[unit.foot_link].translation();
  const Eigen::Vector3d axis = check[unit.foot_link].linear() * Eigen::Vector3d::UnitX();
  if ((foot - foot_m).norm() > 1e-6 ||
      axis.head<2>().normalized().dot(pin_direction.normalized()) < 1.0 - 1e-9)
    return std::nullopt;
  return pose;
}

std::shared_ptr<const ClimbingMachine> with_longer_legs(const ClimbingMachine& m, double extra_m) {
  UrdfInfo urdf = m.robot->urdf();
  for (const auto& unit : m.units) urdf.joints[unit.joints[3]].upper += extra_m;
  auto longer = std::make_shared<ClimbingMachine>(m);
  longer->robot = std::make_shared<const Kinematics>(std::move(urdf));
  return longer;
}

}  // namespace ccbuild::machine
