#include "ccbuild/machine/climbing_family.hpp"

#include <cmath>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "climbing_internal.hpp"

namespace ccbuild::machine {
namespace {

// Plausible ranges of a family's keys (docs/formats.md).
const Range kPlatform_m = Range::above(1.0, 200.0);
const Range kClearance_m = Range::closed(0.3, 5.0);
const Range kSection_m = Range::above(0.05, 2.0);
const Range kMassPerLength_kg_m = Range::above(0.0, 10'000.0);
const Range kStep_m = Range::closed(0.05, 5.0);
const Range kShort_m = Range::closed(0.0, 5.0);
const Range kSwing_deg = Range::above(0.0, 170.0);
const Range kReach_m = Range::closed(0.1, 10.0);
const Range kStroke_m = Range::closed(0.5, 20.0);
const Range kNozzle_m = Range::closed(-20.0, 5.0);
constexpr int kMaxUnits = 16;

// The unit's links (config/machines/cc_climber.urdf): base, turret, boom, wrist, foot, pin.
constexpr double kBaseMass_kg = 250, kTurretMass_kg = 100, kBoomMass_kg = 400, kWristMass_kg = 300,
                 kFootMass_kg = 350, kPinMass_kg = 20;
constexpr double kCarriageMass_kg = 300, kSlideMass_kg = 150, kNozzleMass_kg = 40;

// A [low, high] pair in a range, low below high.
std::pair<double, double> read_span(const Field& field, const Range& range, const char* unit) {
  const auto items = field.items();
  if (items.size() != 2)
    field.fail("expected [lowest, highest], got " + std::to_string(items.size()) + " values");
  const double low = items[0].as_number_in(range, unit), high = items[1].as_number_in(range, unit);
  if (low > high)
    field.fail("the range is the wrong way round: " + plain_number(low) + " is above " +
               plain_number(high));
  return {low, high};
}

DocNode scalar(std::string text, bool quoted = false) {
  DocNode n;
  n.kind = DocNode::Kind::kScalar;
  n.text = std::move(text);
  n.quoted = quoted;
  return n;
}
DocNode map_node(std::vector<std::pair<std::string, DocNode>> entries) {
  DocNode n;
  n.kind = DocNode::Kind::kMap;
  n.entries = std::move(entries);
  return n;
}
// A number as the generated files write it: enough digits to come back the same.
std::string number(double value) {
  return printf_string("%.9g", value);
}

// --- The URDF, as scripts/make_climber.py wrote it for the apartment.
std::string box(const Eigen::Vector3d& size, const Eigen::Vector3d& xyz) {
  return printf_string(
      "<collision><origin xyz=\"%s %s %s\" rpy=\"0 0 0\"/><geometry><box size=\"%s %s %s\"/>"
      "</geometry></collision>",
      number(xyz.x()).c_str(), number(xyz.y()).c_str(), number(xyz.z()).c_str(),
      number(size.x()).c_str(), number(size.y()).c_str(), number(size.z()).c_str());
}
std::string cylinder(double radius_m, double length_m, const Eigen::Vector3d& xyz,
                     double pitch_rad = 0.0) {
  return printf_string(
      "<collision><origin xyz=\"%s %s %s\" rpy=\"0 %s 0\"/><geometry><cylinder radius=\"%s\" "
      "length=\"%s\"/></geometry></collision>",
      number(xyz.x()).c_str(), number(xyz.y()).c_str(), number(xyz.z()).c_str(),
      number(pitch_rad).c_str(), number(radius_m).c_str(), number(length_m).c_str());
}
std::string inertial(double mass_kg, const Eigen::Vector3d& xyz) {
  return printf_string(
      "<inertial><origin xyz=\"%s %s %s\"/><mass value=\"%s\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>",
      number(xyz.x()).c_str(), number(xyz.y()).c_str(), number(xyz.z()).c_str(),
      number(mass_kg).c_str());
}
std::string link(const std::string& name, const std::string& parts) {
  return "  <link name=\"" + name + "\">" + parts + "</link>\n";
}
struct Limit {
  double lower, upper, velocity, effort;
};
std::string joint(const std::string& name, const char* type, const std::string& parent,
                  const std::string& child, const Eigen::Vector3d& xyz, double yaw_rad,
                  const Eigen::Vector3d* axis, const Limit* limit) {
  std::string out =
      "  <joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
      "\"/><child link=\"" + child + "\"/>" +
      printf_string("<origin xyz=\"%s %s %s\" rpy=\"0 0 %s\"/>", number(xyz.x()).c_str(),
                    number(xyz.y()).c_str(), number(xyz.z()).c_str(), number(yaw_rad).c_str());
  if (axis)
    out += printf_string("<axis xyz=\"%s %s %s\"/>", number(axis->x()).c_str(),
                         number(axis->y()).c_str(), number(axis->z()).c_str());
  if (limit)
    out += printf_string("<limit lower=\"%s\" upper=\"%s\" velocity=\"%s\" effort=\"%s\"/>",
                         number(limit->lower).c_str(), number(limit->upper).c_str(),
                         number(limit->velocity).c_str(), number(limit->effort).c_str());
  return out + "</joint>\n";
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::string to_string(UnitMount::Beam beam) {
  switch (beam) {
    case UnitMount::Beam::kSouth:
      return "south";
    case UnitMount::Beam::kNorth:
      return "north";
    case UnitMount::Beam::kWest:
      return "west";
    case UnitMount::Beam::kEast:
      return "east";
  }
  return "?";
}

UnitMount mount_on(UnitMount::Beam beam, Eigen::Vector2d position_m, std::string name) {
  UnitMount m;
  m.name = std::move(name);
  m.beam = beam;
  m.position_m = position_m;
  m.boom_yaw_rad = beam == UnitMount::Beam::kSouth   ? M_PI / 2
                   : beam == UnitMount::Beam::kNorth ? -M_PI / 2
                   : beam == UnitMount::Beam::kWest  ? 0.0
                                                     : M_PI;
  return m;
}

double FittedPlatform::length_m() const {
  return x_max_m - x_min_m;
}
double FittedPlatform::width_m() const {
  return y_max_m - y_min_m;
}

double FittedPlatform::mass_kg(const ClimbingFamily& f) const {
  const double beams_m =
      2.0 * (length_m() + f.beam_section_m) + 2.0 * (width_m() + f.beam_section_m);
  return f.beam_mass_kg_per_m * beams_m + f.bridge_mass_kg_per_m * (width_m() + f.beam_section_m) +
         kCarriageMass_kg + kSlideMass_kg + kNozzleMass_kg +
         f.unit_mass_kg * static_cast<double>(units.size());
}

bool is_climbing_family(const Document& profile) {
  if (profile.root.kind != DocNode::Kind::kMap) return false;
  for (const auto& [key, value] : profile.root.entries)
    if (key == "family") return true;
  return false;
}

ClimbingFamily read_climbing_family(std::shared_ptr<const Document> profile) {
  const Field root = Field::root(*profile);
  ClimbingFamily f;
  f.document = profile;
  f.source_file = profile->file;
  MapReader map(root, detail::with_gantry_process_keys(
                          {"name", "description", "family", "climbing", "urdf", "joints"}));
  map.reject_unknown();
  for (const char* written : {"urdf", "joints"})
    if (auto given = map.optional(written))
      given->fail(std::string("a family has no ") + written +
                  ": `ccbuild fit` writes the URDF and its joints for each building");
  f.name = map.required("name").as_string();
  if (auto rail = map.optional("rail_axis"); rail && rail->as_string() != "x")
    rail->fail("a climbing family's gantry runs along x (the platform's long beams)");
  {
    MapReader climbing(map.required("climbing"), {});
    for (const char* written : {"platform", "units"})
      if (climbing.has(written))
        climbing.required(written).fail(
            std::string("a family's units and platform are chosen by `ccbuild fit`; remove `") +
            written + ":`");
  }
  const Field family_field = map.required("family");
  MapReader family(family_field, {"platform", "units", "nozzle_m"});
  family.reject_unknown();
  {
    MapReader p(family.required("platform"),
                {"length_m", "width_m", "beam_clearance_m", "beam_section_m", "beam_mass_kg_per_m",
                 "bridge_mass_kg_per_m"});
    p.reject_unknown();
    std::tie(f.length_min_m, f.length_max_m) = read_span(p.required("length_m"), kPlatform_m, "m");
    std::tie(f.width_min_m, f.width_max_m) = read_span(p.required("width_m"), kPlatform_m, "m");
    if (auto v = p.optional("beam_clearance_m"))
      f.beam_clearance_m = v->as_number_in(kClearance_m, "m");
    if (auto v = p.optional("beam_section_m")) f.beam_section_m = v->as_number_in(kSection_m, "m");
    if (auto v = p.optional("beam_mass_kg_per_m"))
      f.beam_mass_kg_per_m = v->as_number_in(kMassPerLength_kg_m, "kg/m");
    if (auto v = p.optional("bridge_mass_kg_per_m"))
      f.bridge_mass_kg_per_m = v->as_number_in(kMassPerLength_kg_m, "kg/m");
  }
  {
    const Field units_field = family.required("units");
    MapReader u(units_field, {"count", "mount_step_m", "mount_end_clearance_m", "mount_spacing_m",
                              "swing_limit_deg", "reach_m", "stroke_m"});
    u.reject_unknown();
    const Field count = u.required("count");
    const auto items = count.items();
    if (items.size() != 2) count.fail("expected [fewest, most] units");
    f.units_min = static_cast<int>(std::min<std::int64_t>(items[0].as_count(), 1000));
    f.units_max = static_cast<int>(std::min<std::int64_t>(items[1].as_count(), 1000));
    if (f.units_min < 3 || f.units_max > kMaxUnits || f.units_min > f.units_max)
      count.fail("a climbing machine has 3 to " + std::to_string(kMaxUnits) +
                 " units: expected [fewest, most] within that, fewest first");
    if (auto v = u.optional("mount_step_m")) f.mount_step_m = v->as_number_in(kStep_m, "m");
    if (auto v = u.optional("mount_end_clearance_m"))
      f.mount_end_clearance_m = v->as_number_in(kShort_m, "m");
    if (auto v = u.optional("mount_spacing_m")) f.mount_spacing_m = v->as_number_in(kStep_m, "m");
    if (auto v = u.optional("swing_limit_deg"))
      f.swing_limit_rad = v->as_number_in(kSwing_deg, "deg") * M_PI / 180.0;
    if (auto v = u.optional("reach_m"))
      std::tie(f.reach_min_m, f.reach_max_m) = read_span(*v, kReach_m, "m");
    if (auto v = u.optional("stroke_m"))
      std::tie(f.stroke_min_m, f.stroke_max_m) = read_span(*v, kStroke_m, "m");
    if (f.stroke_max_m - f.stroke_min_m < 0.5)
      u.required("stroke_m").fail("a leg needs at least 0.5 m of stroke to climb");
  }
  if (auto v = family.optional("nozzle_m")) {
    std::tie(f.nozzle_low_m, f.nozzle_high_m) = read_span(*v, kNozzle_m, "m");
    if (f.nozzle_high_m - f.nozzle_low_m < 0.5)
      v->fail("the nozzle needs at least 0.5 m of vertical travel");
  }
  f.unit_mass_kg =
      kBaseMass_kg + kTurretMass_kg + kBoomMass_kg + kWristMass_kg + kFootMass_kg + kPinMass_kg;
  return f;
}

std::string climbing_family_urdf(const ClimbingFamily& f, const FittedPlatform& p,
                                 const std::string& header) {
  const double beam = f.beam_section_m;
  const double long_beam = p.length_m() + beam, cross_beam = p.width_m() + beam;
  const Eigen::Vector3d mid(0.5 * (p.x_min_m + p.x_max_m), 0.5 * (p.y_min_m + p.y_max_m), beam / 2);
  const Eigen::Vector3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), down(0, 0, -1);
  std::string out =
      "<?xml version=\"1.0\"?>\n<!-- " + header + " -->\n<robot name=\"cc_climber\">\n";
  const double beams_m = 2.0 * long_beam + 2.0 * cross_beam;
  out += link("platform", box({long_beam, beam, beam}, {mid.x(), p.y_min_m, beam / 2}) +
                              box({long_beam, beam, beam}, {mid.x(), p.y_max_m, beam / 2}) +
                              box({beam, cross_beam, beam}, {p.x_min_m, mid.y(), beam / 2}) +
                              box({beam, cross_beam, beam}, {p.x_max_m, mid.y(), beam / 2}) +
                              inertial(f.beam_mass_kg_per_m * beams_m, mid));
  // The gantry: the bridge rides on the beams along x, a carriage along the bridge, the
  // nozzle's column hanging below the platform.
  const Eigen::Vector3d bridge_centre(0, mid.y(), 0.25);
  out += link("bridge", box({0.8, cross_beam, 0.5}, bridge_centre) +
                            inertial(f.bridge_mass_kg_per_m * cross_beam, bridge_centre));
  const Limit rail{p.gantry_x_min_m, p.gantry_x_max_m, 0.5, 20000.0};
  out += joint("rail_x", "prismatic", "platform", "bridge", {0, 0, beam}, 0, &x, &rail);
  out +=
      link("carriage", box({0.8, 0.8, 0.4}, {0, 0, 0.7}) + inertial(kCarriageMass_kg, {0, 0, 0.7}));
  const Limit bridge_y{p.gantry_y_min_m, p.gantry_y_max_m, 0.5, 5000.0};
  out += joint("bridge_y", "prismatic", "bridge", "carriage", {0, 0, 0}, 0, &y, &bridge_y);
  // The column reaches from the carriage down past the lowest nozzle position.
  const double column_m = (f.nozzle_high_m - f.nozzle_low_m) + 1.2;
  out += link("slide", cylinder(0.12, column_m, {0, 0, column_m / 2 + 0.3}) +
                           inertial(kSlideMass_kg, {0, 0, column_m / 2 + 0.3}));
  const Limit lift{f.nozzle_low_m, f.nozzle_high_m, 0.05, 5000.0};
  out += joint("lift_z", "prismatic", "carriage", "slide", {0, 0, -beam}, 0, &z, &lift);
  out += link("nozzle", cylinder(0.1, 0.3, {0, 0, 0.15}) + inertial(kNozzleMass_kg, {0, 0, 0.15}));
  const Limit yaw{-2 * M_PI, 2 * M_PI, M_PI / 2, 200.0};
  out += joint("nozzle_yaw", "revolute", "slide", "nozzle", {0, 0, 0}, 0, &z, &yaw);
  // The units: swing, reach (the boom's frame at its tip), wrist (the leg's outer tube
  // hangs from it), stroke (the foot's frame at the pin's axis; the inner tube's top stays
  // 5 cm below the boom at the shortest stroke), pin (its frame at its tip).
  const double boom_m = f.reach_max_m - 0.2;
  const double inner_tube_m = f.stroke_min_m - 0.2;
  for (const UnitMount& u : p.units) {
    const std::string n = lower(u.name);
    out += link(n + "_base",
                box({0.5, 0.5, 0.3}, {0, 0, -0.15}) + inertial(kBaseMass_kg, {0, 0, -0.15}));
    out += joint(n + "_mount", "fixed", "platform", n + "_base",
                 {u.position_m.x(), u.position_m.y(), 0}, 0, nullptr, nullptr);
    out += link(n + "_turret",
                cylinder(0.25, 0.2, {0, 0, -0.1}) + inertial(kTurretMass_kg, {0, 0, -0.1}));
    const Limit swing{-f.swing_limit_rad, f.swing_limit_rad, 0.1, 50000.0};
    out += joint(n + "_swing", "revolute", n + "_base", n + "_turret", {0, 0, -0.3}, u.boom_yaw_rad,
                 &z, &swing);
    out += link(n + "_boom", box({boom_m, 0.25, 0.25}, {-boom_m / 2, 0, -0.325}) +
                                 inertial(kBoomMass_kg, {-boom_m / 2, 0, -0.325}));
    const Limit reach{f.reach_min_m, f.reach_max_m, 0.05, 50000.0};
    out += joint(n + "_reach", "prismatic", n + "_turret", n + "_boom", {0, 0, 0}, 0, &x, &reach);
    out += link(n + "_wrist",
                cylinder(0.16, 1.6, {0, 0, -1.25}) + inertial(kWristMass_kg, {0, 0, -1.25}));
    const Limit wrist{-2.0, 2.0, 0.1, 20000.0};
    out += joint(n + "_wrist_yaw", "revolute", n + "_boom", n + "_wrist", {0, 0, 0}, 0, &z, &wrist);
    out += link(n + "_foot", box({0.3, 0.3, 0.3}, {0, 0, 0}) +
                                 cylinder(0.11, inner_tube_m, {0, 0, 0.15 + inner_tube_m / 2}) +
                                 inertial(kFootMass_kg, {0, 0, 0.5}));
    const Limit stroke{f.stroke_min_m, f.stroke_max_m, 0.05, 200000.0};
    out += joint(n + "_stroke", "prismatic", n + "_wrist", n + "_foot", {0, 0, -0.45}, 0, &down,
                 &stroke);
    out += link(n + "_pin", cylinder(0.03, 0.35, {-0.175, 0, 0}, M_PI / 2) +
                                inertial(kPinMass_kg, {-0.175, 0, 0}));
    const Limit pin{0.0, 0.3, 0.02, 5000.0};
    out += joint(n + "_pin_slide", "prismatic", n + "_foot", n + "_pin", {0.15, 0, 0}, 0, &x, &pin);
  }
  return out + "</robot>\n";
}

Document fitted_profile_document(const ClimbingFamily& f, const FittedPlatform& p,
                                 const std::string& urdf_file, const std::string& description) {
  Document doc;
  doc.file = f.source_file;
  doc.root.kind = DocNode::Kind::kMap;
  for (const auto& [key, value] : f.document->root.entries) {
    if (key == "family" || key == "description") continue;
    if (key != "climbing") {
      doc.root.entries.emplace_back(key, value);
      if (key == "name") {
        doc.root.entries.emplace_back("urdf", scalar(urdf_file, true));
        doc.root.entries.emplace_back("joints", map_node({{"x", scalar("rail_x")},
                                                          {"y", scalar("bridge_y")},
                                                          {"z", scalar("lift_z")},
                                                          {"nozzle", scalar("nozzle_yaw")}}));
        doc.root.entries.emplace_back("description", scalar(description, true));
      }
      continue;
    }
    DocNode climbing = value;
    DocNode units;
    units.kind = DocNode::Kind::kSequence;
    for (const UnitMount& u : p.units) {
      const std::string n = lower(u.name);
      units.items.push_back(map_node({{"name", scalar(u.name)},
                                      {"swing", scalar(n + "_swing")},
                                      {"reach", scalar(n + "_reach")},
                                      {"wrist", scalar(n + "_wrist_yaw")},
                                      {"stroke", scalar(n + "_stroke")},
                                      {"pin", scalar(n + "_pin_slide")}}));
    }
    climbing.entries.insert(climbing.entries.begin(), {"units", units});
    climbing.entries.insert(climbing.entries.begin(), {"platform", scalar("platform")});
    doc.root.entries.emplace_back("climbing", std::move(climbing));
  }
  return doc;
}

}  // namespace ccbuild::machine
