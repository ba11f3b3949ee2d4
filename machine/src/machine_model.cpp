#include "ccbuild/machine/machine_model.hpp"

#include <cmath>
#include <limits>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/climbing_machine.hpp"
#include "ccbuild/machine/urdf_adapter.hpp"
#include "climbing_internal.hpp"

namespace ccbuild::machine {

std::string to_string(RailAxis axis) {
  return axis == RailAxis::kX ? "x" : "y";
}

std::optional<RailAxis> rail_axis_named(const std::string& name) {
  if (name == "x") return RailAxis::kX;
  if (name == "y") return RailAxis::kY;
  return std::nullopt;
}
namespace fs = std::filesystem;

MachineModel MachineModel::defaults() {
  MachineModel m;
  m.x = {0.0, 50.0, 0.5};
  m.y = {0.0, 50.0, 0.5};
  m.z = {0.0, 10.0, 0.1};
  m.lift_height_m = m.lift_time_s * m.z.speed_m_s;
  return m;
}

namespace {

// Plausible ranges (docs/formats.md): beyond them a value is a typo, not a machine.
const Range kDepositionSpeed_m_s = Range::above(0.0, 2.0);
const Range kTravelSpeed_m_s = Range::above(0.0, 10.0);
const Range kAccelDelay_s = Range::closed(0.0, 60.0);
const Range kLiftHeight_m = Range::closed(0.0, 5.0);
const Range kLiftTime_s = Range::closed(0.0, 600.0);
const Range kIdleLimit_s = Range::above(0.0, 86'400.0);
const Range kNozzleWidth_m = Range::closed(0.005, 1.0);
const Range kGantryWidth_m = Range::above(0.0, 20.0);
const Range kPurge_s = Range::closed(0.0, 3'600.0);
// URDF joints.
const Range kAxisPosition_m = Range::closed(-1000.0, 1000.0);
const Range kAxisSpeed_m_s = Range::above(0.0, 10.0);
const Range kRotationSpeed_rad_s = Range::above(0.0, 20.0);
const Range kStopper_rad = Range::closed(-20.0 * M_PI, 20.0 * M_PI);

// A URDF value out of range: the URDF and the joint's element are named.
void check_joint_value(const Field& field, const std::string& urdf_file, const JointInfo& j,
                       const char* attribute, double value, const Range& range, const char* unit) {
  const std::string wrong = range.violation(value, plain_number(value) + " " + unit, unit);
  if (!wrong.empty())
    throw InputError(urdf_file, j.line, "joint[" + j.name + "].limit." + attribute,
                     wrong + " (joint used as " + field.path() + " in " + field.file() + ")");
}

std::string joint_list(const UrdfInfo& urdf) {
  std::string list;
  for (const auto& j : urdf.joints) list += (list.empty() ? "" : ", ") + j.name;
  return list;
}

const JointInfo& find_joint(const Field& field, const UrdfInfo& urdf,
                            const std::string& urdf_file) {
  const std::string name = field.as_string();
  const JointInfo* joint = urdf.find(name);
  if (joint == nullptr)
    field.fail("URDF " + urdf_file + " has no joint '" + name + "' (it has: " + joint_list(urdf) +
               ")");
  return *joint;
}

// A prismatic joint moving along `axis` (0 = x, 1 = y, 2 = z), with limits.
AxisLimits read_axis(const Field& field, const UrdfInfo& urdf, const std::string& urdf_file,
                     int axis) {
  const JointInfo& j = find_joint(field, urdf, urdf_file);
  const std::string label = "joint '" + j.name + "' in " + urdf_file;
  if (j.type != "prismatic") field.fail(label + " is " + j.type + ", expected prismatic");
  if (!j.has_limits) field.fail(label + " has no <limit>; travel range and speed come from it");
  const double norm = j.axis.norm();
  if (norm <= 0.0 || std::abs(j.axis[axis]) / norm < 0.999)
    field.fail(label + " does not move along " + std::string(1, "xyz"[axis]) +
               " (check its <axis>)");
  check_joint_value(field, urdf_file, j, "velocity", j.velocity, kAxisSpeed_m_s, "m/s");
  check_joint_value(field, urdf_file, j, "lower", j.lower, kAxisPosition_m, "m");
  check_joint_value(field, urdf_file, j, "upper", j.upper, kAxisPosition_m, "m");
  if (j.upper <= j.lower) field.fail(label + " has an empty travel range (upper <= lower)");
  return AxisLimits{j.lower, j.upper, j.velocity};
}

// `bead_width_m: [narrowest, widest]`, the nozzle's own width within it (a thick wall's
// skins are laid at that width).
std::pair<double, double> read_bead_widths(const Field& field, double nozzle_width_m) {
  const auto items = field.items();
  if (items.size() != 2)
    field.fail("expected [narrowest, widest] bead, m, got " + std::to_string(items.size()) +
               " values");
  const double low = items[0].as_number_in(kNozzleWidth_m, "m");
  const double high = items[1].as_number_in(kNozzleWidth_m, "m");
  if (low > high)
    field.fail("the range is the wrong way round: " + plain_number(low) + " is above " +
               plain_number(high));
  if (nozzle_width_m < low || nozzle_width_m > high)
    field.fail("the nozzle's own width, nozzle_width_m " + plain_number(nozzle_width_m) +
               " m, must lie in the range [" + plain_number(low) + ", " + plain_number(high) +
               "] (a thick wall's skins are laid at it)");
  return {low, high};
}

}  // namespace

MachineModel load_machine(const fs::path& profile_path) {
  return load_machine_profile(profile_path).gantry;
}

namespace detail {

std::vector<std::string> with_gantry_process_keys(std::vector<std::string> more) {
  for (const char* key :
       {"deposition_speed_m_s", "travel_speed_m_s", "rotate_while_moving", "accel_delay_s",
        "lift_height_m", "lift_time_s", "lower_time_s", "nozzle_idle_limit_s", "nozzle_width_m",
        "bead_width_m", "nozzles", "gantry_width_m", "rail_axis", "purge_s", "pump_capacity_m3_h"})
    more.emplace_back(key);
  return more;
}

}  // namespace detail

MachineProfile load_machine_profile(const fs::path& profile_path) {
  auto doc = std::make_shared<Document>(load_document(profile_path));
  if (is_climbing_family(*doc)) {
    MachineProfile profile;
    profile.family = std::make_shared<const ClimbingFamily>(read_climbing_family(doc));
    profile.gantry.name = profile.family->name;
    profile.gantry.source_file = profile_path.string();
    profile.gantry.files_read.push_back(profile_path);
    return profile;
  }
  return load_machine_profile(*doc, profile_path, nullptr);
}

MachineProfile load_machine_profile(const Document& doc, const fs::path& profile_path,
                                    const std::string* urdf_xml) {
  const Field root = Field::root(doc);
  MapReader map(root, detail::with_gantry_process_keys(
                          {"name", "description", "urdf", "joints", "climbing"}));
  map.reject_unknown();

  MachineModel m;
  m.source_file = profile_path.string();
  m.files_read.push_back(profile_path);
  m.name = map.required("name").as_string();

  const Field urdf_field = map.required("urdf");
  const fs::path base = profile_path.has_parent_path() ? profile_path.parent_path() : fs::path(".");
  const fs::path urdf_path = (base / urdf_field.as_string()).lexically_normal();
  std::error_code ec;
  if (!urdf_xml && !fs::is_regular_file(urdf_path, ec))
    urdf_field.fail("URDF file '" + urdf_field.as_string() + "' not found (looked for " +
                    urdf_path.string() + ")");
  const UrdfInfo urdf =
      urdf_xml ? read_urdf_text(*urdf_xml, urdf_path.string()) : read_urdf(urdf_path.string());
  if (!urdf_xml) m.files_read.push_back(urdf_path);

  MapReader joints(map.required("joints"), {"x", "y", "z", "nozzle"});
  joints.reject_unknown();
  m.x = read_axis(joints.required("x"), urdf, urdf_path.string(), 0);
  m.y = read_axis(joints.required("y"), urdf, urdf_path.string(), 1);
  m.z = read_axis(joints.required("z"), urdf, urdf_path.string(), 2);
  {
    const Field field = joints.required("nozzle");
    const JointInfo& j = find_joint(field, urdf, urdf_path.string());
    const std::string label = "joint '" + j.name + "' in " + urdf_path.string();
    if (j.type != "revolute" && j.type != "continuous")
      field.fail(label + " is " + j.type +
                 ", expected revolute (its limits are the stopper) or continuous");
    if (!j.has_limits)
      field.fail(label + " needs a <limit> with a velocity (the nozzle's rotation speed)");
    check_joint_value(field, urdf_path.string(), j, "velocity", j.velocity, kRotationSpeed_rad_s,
                      "rad/s");
    m.rotation_speed_rad_s = j.velocity;
    if (j.type == "revolute") {
      check_joint_value(field, urdf_path.string(), j, "lower", j.lower, kStopper_rad, "rad");
      check_joint_value(field, urdf_path.string(), j, "upper", j.upper, kStopper_rad, "rad");
      if (!(j.lower <= 0.0 && j.upper >= 0.0) || j.upper - j.lower < 2.0 * M_PI - 1e-9)
        field.fail(label +
                   " must span at least one full turn around 0 (lower <= 0 <= upper, upper - lower "
                   ">= 2 pi)");
      m.stopper_min_rad = j.lower;
      m.stopper_max_rad = j.upper;
    } else {
      m.stopper_min_rad = -std::numeric_limits<double>::infinity();
      m.stopper_max_rad = std::numeric_limits<double>::infinity();
    }
  }

  m.deposition_speed_m_s =
      map.required("deposition_speed_m_s").as_number_in(kDepositionSpeed_m_s, "m/s");
  m.travel_speed_m_s = map.required("travel_speed_m_s").as_number_in(kTravelSpeed_m_s, "m/s");
  m.rotate_while_moving = map.required("rotate_while_moving").as_bool();
  m.accel_delay_s = map.required("accel_delay_s").as_number_in(kAccelDelay_s, "s");
  m.nozzle_idle_limit_s = map.required("nozzle_idle_limit_s").as_number_in(kIdleLimit_s, "s");
  if (auto width = map.optional("nozzle_width_m"))
    m.nozzle_width_m = width->as_number_in(kNozzleWidth_m, "m");
  if (auto range = map.optional("bead_width_m"))
    m.bead_width_range_m = read_bead_widths(*range, m.nozzle_width_m);
  if (auto n = map.optional("nozzles")) {
    m.nozzles = static_cast<int>(n->as_count());
    if (m.nozzles < 1 || m.nozzles > 16) n->fail("must be from 1 to 16 (gantries on the rails)");
  }
  if (auto width = map.optional("gantry_width_m"))
    m.gantry_width_m = width->as_number_in(kGantryWidth_m, "m");
  if (auto axis = map.optional("rail_axis")) {
    const std::string text = axis->as_string();
    const auto named = rail_axis_named(text);
    if (!named) axis->fail("must be x or y, got '" + echoed(text) + "'");
    m.rail_axis = *named;
  }
  if (auto purge = map.optional("purge_s")) m.purge_s = purge->as_number_in(kPurge_s, "s");
  if (auto pump = map.optional("pump_capacity_m3_h"))
    m.pump_capacity_m3_s = pump->as_number_in(Range::above(0.0, 1000.0), "m3/h") / 3600.0;

  // Lift either from a height (the z joint's speed gives the time) or from two times.
  const auto height = map.optional("lift_height_m");
  const auto lift = map.optional("lift_time_s");
  const auto lower = map.optional("lower_time_s");
  if (height && (lift || lower))
    (lift ? *lift : *lower)
        .fail("give either lift_height_m or lift_time_s and lower_time_s, not both");
  if (height) {
    m.lift_height_m = height->as_number_in(kLiftHeight_m, "m");
    m.lift_time_s = m.lower_time_s = m.lift_height_m / m.z.speed_m_s;
  } else if (lift && lower) {
    m.lift_time_s = lift->as_number_in(kLiftTime_s, "s");
    m.lower_time_s = lower->as_number_in(kLiftTime_s, "s");
    // The z joint at its velocity limit, for as long as the faster of the two.
    m.lift_height_m = m.z.speed_m_s * std::min(m.lift_time_s, m.lower_time_s);
  } else {
    root.fail("missing lift: give lift_height_m, or lift_time_s and lower_time_s");
  }
  MachineProfile profile;
  if (auto climbing = map.optional("climbing")) {
    std::array<std::string, 4> gantry_joints;
    for (int k = 0; k < 4; ++k)
      gantry_joints[k] = joints.required(k == 0   ? "x"
                                         : k == 1 ? "y"
                                         : k == 2 ? "z"
                                                  : "nozzle")
                             .as_string();
    profile.climbing = detail::read_climbing(*climbing, urdf, m, gantry_joints);
  }
  profile.gantry = std::move(m);
  return profile;
}

}  // namespace ccbuild::machine
