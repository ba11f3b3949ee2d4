#include "ccbuild/orchestrator/schedule_json.hpp"

#include <cmath>

#include "ccbuild/common/sha256.hpp"
#include "ccbuild/orchestrator/climb_report.hpp"
#include "report_common.hpp"

namespace ccbuild::orchestrator {
namespace {

using detail::json;
using detail::rounded;

json optional_number(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? json(rounded(*value)) : json(nullptr);
}

json piece_end_json(const PieceEnd& e) {
  return {{"wall", e.wall}, {"piece", e.piece}, {"x_m", rounded(e.x_m)}, {"y_m", rounded(e.y_m)}};
}

json reasons_json(const std::vector<WaitReason>& reasons) {
  json out = json::array();
  for (const auto& r : reasons)
    out.push_back({{"kind", r.kind}, {"required_s", rounded(r.required_s)}, {"detail", r.detail}});
  return out;
}

json material_json(const floors::MaterialProfile& m) {
  json curve = json::array();
  for (const auto& p : m.strength_curve)
    curve.push_back({{"age_s", rounded(p.age_s)}, {"strength_mpa", rounded(p.strength_mpa)}});
  return {{"name", m.name},
          {"density_kg_m3", rounded(m.density_kg_m3)},
          {"min_layer_interval_s", rounded(m.min_layer_interval_s)},
          {"max_layer_interval_s", rounded(m.max_layer_interval_s)},
          {"safety_factor", rounded(m.safety_factor)},
          {"strength_curve", curve}};
}

}  // namespace

nlohmann::ordered_json schedule_json(const Project& project, const ScheduleOptions& options,
                                     const Schedule& schedule) {
  const floors::Building& b = project.building;
  json out;
  out["format"] = "ccbuild-schedule";
  out["schema_version"] = kScheduleSchemaVersion;
  out["ccbuild_version"] = kCcbuildVersion;

  json files = json::array();
  for (const auto& path : project.files_read())
    files.push_back({{"path", path.string()}, {"sha256", sha256_file_hex(path)}});
  json machine = detail::machine_json(*project.machine);
  machine["origin"] = project.machine_origin;
  machine["nozzles"] = project.machine->nozzles;
  machine["gantry_width_m"] = rounded(project.machine->gantry_width_m);
  machine["rail_axis"] = std::string(1, project.machine->rail_axis);
  machine["purge_s"] = rounded(project.machine->purge_s);
  machine["kind"] = project.climber ? "climbing" : "fixed gantry";
  if (project.climber) {
    machine["anchor_strength_mpa"] = rounded(project.climber->anchor_strength_mpa);
    machine["pipe_embed_s"] = rounded(project.climber->pipe_embed_s);
  }
  json material = material_json(project.material);
  material["origin"] = project.material_origin;
  out["inputs"] = {{"building", project.file.string()},
                   {"name", b.name},
                   {"units", floors::to_string(b.units)},
                   {"layer_height_m", rounded(b.layer_height_m)},
                   {"slab_stage_s", rounded(b.slab_stage_s)},
                   {"seed", options.seed},
                   {"files", files},
                   {"machine", machine},
                   {"material", material}};

  out["feasible"] = schedule.feasible;
  if (schedule.infeasibility) {
    const Infeasibility& inf = *schedule.infeasibility;
    out["infeasibility"] = {
        {"kind", inf.kind},
        {"floor", inf.floor},
        {"layer", inf.layer},
        {"message", inf.message},
        {"required_s", rounded(inf.required_s)},
        {"achieved_s", rounded(inf.achieved_s)},
        {"fix",
         {{"text", inf.fix},
          {"nozzles_needed", inf.nozzles_needed ? json(*inf.nozzles_needed) : json(nullptr)},
          {"deposition_speed_needed_m_s", optional_number(inf.deposition_speed_needed_m_s)},
          {"max_interval_needed_s", optional_number(inf.max_interval_needed_s)}}}};
  } else {
    out["infeasibility"] = nullptr;
  }

  const ScheduleTotals& t = schedule.totals;
  out["totals"] = {{"makespan_s", rounded(t.makespan_s)},     {"layers", schedule.layers.size()},
                   {"deposition_s", rounded(t.deposition_s)}, {"airtime_s", rounded(t.airtime_s)},
                   {"moves_s", rounded(t.moves_s)},           {"waits_s", rounded(t.waits_s)},
                   {"pipes_s", rounded(t.pipes_s)},           {"purges_s", rounded(t.purges_s)},
                   {"climbs_s", rounded(t.climbs_s)},         {"slabs_s", rounded(t.slabs_s)},
                   {"machine_s", rounded(t.machine_s)}};

  json layers = json::array();
  for (const auto& l : schedule.layers) {
    json j;
    j["floor"] = l.floor;
    j["layer"] = l.layer;
    j["z_m"] = rounded(l.z_top_m);
    j["z_bottom_m"] = rounded(l.z_bottom_m);
    j["geometry"] = l.geometry;
    j["plan"] = l.plan;
    j["nozzles"] = l.nozzles;
    j["method"] = l.method;
    j["start_s"] = rounded(l.start_s);
    j["end_s"] = rounded(l.end_s);
    j["deposition_s"] = rounded(l.deposition_s);
    j["airtime_s"] = rounded(l.airtime_s);
    j["max_idle_s"] = rounded(l.max_idle_s);
    j["move_before_s"] = rounded(l.move_before_s);
    j["pipes_before_s"] = rounded(l.pipes_before_s);
    j["wait_before_s"] = rounded(l.wait_before_s);
    j["wait_reasons"] = reasons_json(l.wait_reasons);
    j["purge_before"] = l.purge_before;
    j["interval_s"] = optional_number(l.interval_s);
    j["local_interval_min_s"] = optional_number(l.local_interval_min_s);
    j["local_interval_max_s"] = optional_number(l.local_interval_max_s);
    j["local_interval_min_at"] =
        l.local_interval_min_s ? piece_end_json(l.local_min_at) : json(nullptr);
    j["local_interval_max_at"] =
        l.local_interval_max_s ? piece_end_json(l.local_max_at) : json(nullptr);
    j["piece_ends_checked"] = l.piece_ends_checked;
    layers.push_back(j);
  }
  out["layers"] = layers;

  json plans = json::object();
  for (const auto& [key, p] : schedule.plans) {
    json nozzles = json::array();
    for (std::size_t n = 0; n < p.waypoints.size(); ++n)
      nozzles.push_back({{"nozzle", n}, {"waypoints", detail::waypoints_json(p.waypoints[n])}});
    plans[key] = {{"geometry", p.geometry},
                  {"nozzles_used", p.nozzles},
                  {"method", p.method},
                  {"z_top_m", rounded(p.z_top_m)},
                  {"layer_time_s", rounded(p.layer_time_s)},
                  {"min_gap_m", p.nozzles > 1 ? json(rounded(p.min_gap_m)) : json(nullptr)},
                  {"pieces", detail::pieces_json(p.layer)},
                  {"nozzles", nozzles}};
  }
  out["plans"] = plans;

  json stages = json::array();
  for (const auto& s : schedule.stages) stages.push_back(stage_json(project, s));
  out["stages"] = stages;

  json events = json::array();
  for (const auto& e : schedule.events) {
    json j = {{"kind", to_string(e.kind)}, {"start_s", rounded(e.start_s)},
              {"end_s", rounded(e.end_s)}, {"floor", e.floor},
              {"after_layer", e.layer},    {"detail", e.detail}};
    if (e.anchor) j["anchor"] = anchor_json(project, *e.anchor);
    if (e.climb) {
      const ClimbEvent& c = *e.climb;
      json anchors = json::array();
      for (const auto& a : c.anchors)
        anchors.push_back({{"id", a.id},
                           {"unit", a.unit},
                           {"age_s", rounded(a.age_s)},
                           {"strength_mpa", rounded(a.strength_mpa)},
                           {"required_mpa", rounded(a.required_mpa)}});
      j["from_stage"] = c.from_stage;
      j["to_stage"] = c.to_stage;
      j["wait_before_s"] = rounded(c.wait_before_s);
      j["wait_reasons"] = reasons_json(c.wait_reasons);
      j["anchors"] = anchors;
      j["climb"] = climb_plan_json(project, c.plan, false);
    }
    events.push_back(j);
  }
  out["events"] = events;
  out["warnings"] = schedule.warnings;
  return out;
}

}  // namespace ccbuild::orchestrator
