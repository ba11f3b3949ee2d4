#include "ccbuild/schedule/json_blocks.hpp"

#include <cmath>

#include "ccbuild/common/sha256.hpp"

namespace ccbuild::schedule {
namespace {
using json = nlohmann::ordered_json;

json optional_number(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? json(rounded(*value)) : json(nullptr);
}
}  // namespace

double rounded(double value) {
  const double r = std::round(value * 1e6) / 1e6;
  return r == 0.0 ? 0.0 : r;  // no "-0.0"
}

json point_json(const Eigen::Vector2d& p) {
  return json::array({rounded(p.x()), rounded(p.y())});
}

json pieces_json(const floors::Layer& layer, double nozzle_width_m) {
  json out = json::array();
  for (const auto& s : layer.segments) {
    out.push_back({{"wall", s.wall_id},
                   {"piece", s.piece + 1},
                   {"piece_count", s.piece_count},
                   {"start_m", point_json(layer.start_m(s))},
                   {"end_m", point_json(layer.end_m(s))},
                   {"length_m", rounded(s.length_m)}});
    // A bead of a wall thicker than one bead says what it is and how wide, and so does a
    // pass of another width than the machine's nozzle (inputs.machine.nozzle_width_m).
    if (s.role != floors::BeadRole::kPass ||
        (nozzle_width_m > 0.0 && s.width_m > 0.0 && std::abs(s.width_m - nozzle_width_m) > 1e-9)) {
      out.back()["bead"] = floors::bead_role_name(s.role);
      out.back()["width_m"] = rounded(s.width_m);
    }
  }
  return out;
}

json waypoints_json(const std::vector<planner::Waypoint>& waypoints) {
  json out = json::array();
  for (const auto& w : waypoints) {
    out.push_back({{"t_s", rounded(w.t_s)},
                   {"x_m", rounded(w.position_m.x())},
                   {"y_m", rounded(w.position_m.y())},
                   {"z_m", rounded(w.z_m)},
                   {"heading_rad", rounded(w.heading_rad)},
                   {"extruding", w.extruding},
                   {"wall", w.wall},
                   {"piece", w.piece}});
  }
  return out;
}

PathDigest path_digest(const std::vector<planner::Waypoint>& waypoints) {
  return {waypoints.size(), sha256_hex(waypoints_json(waypoints).dump())};
}

RecordedMachine machine_limits(const machine::MachineModel& m) {
  RecordedMachine r;
  r.name = m.name;
  r.deposition_speed_m_s = m.deposition_speed_m_s;
  r.travel_speed_m_s = m.travel_speed_m_s;
  r.x_speed_m_s = m.x.speed_m_s;
  r.y_speed_m_s = m.y.speed_m_s;
  r.z_speed_m_s = m.z.speed_m_s;
  r.rotation_speed_rad_s = m.rotation_speed_rad_s;
  r.rotate_while_moving = m.rotate_while_moving;
  r.accel_delay_s = m.accel_delay_s;
  r.lift_height_m = m.lift_height_m;
  r.lift_time_s = m.lift_time_s;
  r.lower_time_s = m.lower_time_s;
  if (std::isfinite(m.stopper_min_rad) && std::isfinite(m.stopper_max_rad)) {
    r.stopper_min_rad = m.stopper_min_rad;
    r.stopper_max_rad = m.stopper_max_rad;
  }
  r.nozzle_idle_limit_s = m.nozzle_idle_limit_s;
  r.nozzle_width_m = m.nozzle_width_m;
  r.x_min_m = m.x.min_m;
  r.x_max_m = m.x.max_m;
  r.y_min_m = m.y.min_m;
  r.y_max_m = m.y.max_m;
  r.z_min_m = m.z.min_m;
  r.z_max_m = m.z.max_m;
  return r;
}

json machine_limits_json(const RecordedMachine& m) {
  json out;
  out["name"] = m.name;
  out["deposition_speed_m_s"] = rounded(m.deposition_speed_m_s);
  out["travel_speed_m_s"] = rounded(m.travel_speed_m_s);
  out["x_speed_m_s"] = rounded(m.x_speed_m_s);
  out["y_speed_m_s"] = rounded(m.y_speed_m_s);
  out["z_speed_m_s"] = rounded(m.z_speed_m_s);
  out["rotation_speed_rad_s"] = rounded(m.rotation_speed_rad_s);
  out["rotate_while_moving"] = m.rotate_while_moving;
  out["accel_delay_s"] = rounded(m.accel_delay_s);
  out["lift_height_m"] = rounded(m.lift_height_m);
  out["lift_time_s"] = rounded(m.lift_time_s);
  out["lower_time_s"] = rounded(m.lower_time_s);
  out["stopper_min_rad"] = optional_number(m.stopper_min_rad);
  out["stopper_max_rad"] = optional_number(m.stopper_max_rad);
  out["nozzle_idle_limit_s"] = rounded(m.nozzle_idle_limit_s);
  out["nozzle_width_m"] = rounded(m.nozzle_width_m);
  out["x_range_m"] = {rounded(m.x_min_m), rounded(m.x_max_m)};
  out["y_range_m"] = {rounded(m.y_min_m), rounded(m.y_max_m)};
  out["z_range_m"] = {rounded(m.z_min_m), rounded(m.z_max_m)};
  return out;
}

nlohmann::ordered_json anchor_json(const std::vector<std::string>& units, const climb::Anchor& a) {
  return {{"id", a.id},
          {"unit", units.at(a.unit)},
          {"floor", a.floor < 0 ? json(nullptr) : json(a.floor)},
          {"wall", a.floor < 0 ? json(nullptr) : json(a.wall_id)},
          {"after_layer", a.floor < 0 ? json(nullptr) : json(a.layer)},
          {"x_m", rounded(a.centre_m.x())},
          {"y_m", rounded(a.centre_m.y())},
          {"z_m", rounded(a.centre_m.z())},
          {"outward", {rounded(a.outward.x()), rounded(a.outward.y())}},
          {"by_default_rule", a.by_default_rule}};
}

nlohmann::ordered_json stage_json(const std::vector<std::string>& units,
                                  const climb::ClimbStage& s) {
  json anchors = json::array();
  for (const auto& a : s.anchors) anchors.push_back(anchor_json(units, a));
  return {{"stage", s.index},
          {"platform_z_m", rounded(s.platform_z_m)},
          {"first", {{"floor", s.first.floor}, {"layer", s.first.layer}}},
          {"last", {{"floor", s.last.floor}, {"layer", s.last.layer}}},
          {"top_m", rounded(s.top_m)},
          {"anchors", anchors}};
}

nlohmann::ordered_json climb_plan_json(const std::vector<std::string>& units,
                                       const climb::ClimbPlan& c, bool with_planning_time) {
  json phases = json::array();
  for (const auto& p : c.phases) {
    json waypoints = json::array();
    for (std::size_t k = 0; k < p.path.size(); ++k) {
      json values = json::array();
      for (double v : p.path[k]) values.push_back(rounded(v));
      json point = {{"t_s", rounded(k < p.t_s.size() ? p.t_s[k] : 0.0)}, {"values", values}};
      if (k < p.following.size()) {
        json legs = json::array();
        for (double v : p.following[k]) legs.push_back(rounded(v));
        point["following"] = legs;
      }
      waypoints.push_back(point);
    }
    json phase = {{"kind", climb::to_string(p.kind)},
                  {"unit", p.unit >= 0 ? json(units.at(p.unit)) : json(nullptr)},
                  {"joints", p.joints},
                  {"following_joints", p.following_joints},
                  {"duration_s", rounded(p.duration_s)}};
    if (with_planning_time) phase["planning_s"] = rounded(p.planning_s);
    phase["min_clearance_m"] =
        std::isfinite(p.min_clearance_m) ? json(rounded(p.min_clearance_m)) : json(nullptr);
    phase["strokes"] = p.strokes;
    phase["waypoints"] = waypoints;
    phases.push_back(phase);
  }
  json out = {{"from_stage", c.from_stage},
              {"to_stage", c.to_stage},
              {"status", climb::to_string(c.status.code())},
              {"status_reason", c.status.reason()},
              {"duration_s", rounded(c.duration_s)}};
  if (with_planning_time) out["planning_s"] = rounded(c.planning_s);
  out["min_clearance_m"] =
      std::isfinite(c.min_clearance_m) ? json(rounded(c.min_clearance_m)) : json(nullptr);
  out["phases"] = phases;
  return out;
}

}  // namespace ccbuild::schedule
