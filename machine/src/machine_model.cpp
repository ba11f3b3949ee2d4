#include "ccbuild/machine/machine_model.hpp"

#include <cmath>
#include <limits>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/urdf_adapter.hpp"

namespace ccbuild::machine {
namespace fs = std::filesystem;

MachineModel MachineModel::defaults() {
  MachineModel m;
  m.x = {0.0, 50.0, 0.5};
  m.y = {0.0, 50.0, 0.5};
  m.z = {0.0, 10.0, 0.1};
  return m;
}

namespace {

double positive(const Field& field) {
  const double value = field.as_number();
  if (value <= 0.0) field.fail("must be positive, got " + field.node().text);
  return value;
}

double non_negative(const Field& field) {
  const double value = field.as_number();
  if (value < 0.0) field.fail("must be zero or more, got " + field.node().text);
  return value;
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
  const double norm =
      std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
  if (norm <= 0.0 || std::abs(j.axis[axis]) / norm < 0.999)
    field.fail(label + " does not move along " + std::string(1, "xyz"[axis]) +
               " (check its <axis>)");
  if (j.velocity <= 0.0)
    field.fail(label + " has velocity limit " + std::to_string(j.velocity) + ", expected > 0");
  if (j.upper <= j.lower) field.fail(label + " has an empty travel range (upper <= lower)");
  return AxisLimits{j.lower, j.upper, j.velocity};
}

}  // namespace

MachineModel load_machine(const fs::path& profile_path) {
  const Document doc = load_document(profile_path);
  const Field root = Field::root(doc);
  MapReader map(root, {"name", "description", "urdf", "joints", "deposition_speed_m_s",
                       "travel_speed_m_s", "rotate_while_moving", "accel_delay_s", "lift_height_m",
                       "lift_time_s", "lower_time_s", "nozzle_idle_limit_s", "nozzle_width_m"});
  map.reject_unknown();

  MachineModel m;
  m.source_file = profile_path.string();
  m.name = map.required("name").as_string();

  const Field urdf_field = map.required("urdf");
  const fs::path base = profile_path.has_parent_path() ? profile_path.parent_path() : fs::path(".");
  const fs::path urdf_path = (base / urdf_field.as_string()).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(urdf_path, ec))
    urdf_field.fail("URDF file '" + urdf_field.as_string() + "' not found (looked for " +
                    urdf_path.string() + ")");
  const UrdfInfo urdf = read_urdf(urdf_path.string());

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
    if (!j.has_limits || j.velocity <= 0.0)
      field.fail(label + " needs a <limit> with velocity > 0 (the nozzle's rotation speed)");
    m.rotation_speed_rad_s = j.velocity;
    if (j.type == "revolute") {
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

  m.deposition_speed_m_s = positive(map.required("deposition_speed_m_s"));
  m.travel_speed_m_s = positive(map.required("travel_speed_m_s"));
  m.rotate_while_moving = map.required("rotate_while_moving").as_bool();
  m.accel_delay_s = non_negative(map.required("accel_delay_s"));
  m.nozzle_idle_limit_s = positive(map.required("nozzle_idle_limit_s"));
  if (auto width = map.optional("nozzle_width_m")) m.nozzle_width_m = positive(*width);

  // Lift either from a height (the z joint's speed gives the time) or from two times.
  const auto height = map.optional("lift_height_m");
  const auto lift = map.optional("lift_time_s");
  const auto lower = map.optional("lower_time_s");
  if (height && (lift || lower))
    (lift ? *lift : *lower)
        .fail("give either lift_height_m or lift_time_s and lower_time_s, not both");
  if (height) {
    const double h = non_negative(*height);
    m.lift_time_s = m.lower_time_s = h / m.z.speed_m_s;
  } else if (lift && lower) {
    m.lift_time_s = non_negative(*lift);
    m.lower_time_s = non_negative(*lower);
  } else {
    root.fail("missing lift: give lift_height_m, or lift_time_s and lower_time_s");
  }
  return m;
}

}  // namespace ccbuild::machine
