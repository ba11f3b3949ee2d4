#include "ccbuild/schedule/schedule_json.hpp"

#include <cmath>

#include "ccbuild/common/sha256.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/schedule/json_blocks.hpp"

namespace ccbuild::schedule {
namespace {

using json = nlohmann::ordered_json;

json optional_number(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? json(rounded(*value)) : json(nullptr);
}

json piece_end_json(const PieceEnd& e) {
  return {{"wall", e.wall}, {"piece", e.piece}, {"x_m", rounded(e.x_m)}, {"y_m", rounded(e.y_m)}};
}

json reasons_json(const std::vector<WaitReason>& reasons) {
  json out = json::array();
  for (const auto& r : reasons)
    out.push_back({{"kind", to_string(r.kind)},
                   {"required_s", rounded(r.required_s)},
                   {"from_s", rounded(r.from_s)},
                   {"binding_s", rounded(r.binding_s)},
                   {"detail", r.detail}});
  return out;
}

json recorded_machine_json(const RecordedMachine& m) {
  json out = machine_limits_json(m);
  out["origin"] = m.origin;
  if (!m.profile.empty()) out["profile"] = m.profile;
  out["nozzles"] = m.nozzles;
  out["gantry_width_m"] = rounded(m.gantry_width_m);
  out["rail_axis"] = machine::to_string(m.rail_axis);
  out["purge_s"] = rounded(m.purge_s);
  if (m.pump_capacity_m3_s) out["pump_capacity_m3_h"] = rounded(*m.pump_capacity_m3_s * 3600.0);
  if (m.bead_width_range_m)
    out["bead_width_m"] = {rounded(m.bead_width_range_m->first),
                           rounded(m.bead_width_range_m->second)};
  out["kind"] = m.climbing ? "climbing" : "fixed gantry";
  if (m.climbing) {
    out["anchor_strength_mpa"] = rounded(m.anchor_strength_mpa);
    out["pipe_embed_s"] = rounded(m.pipe_embed_s);
  }
  return out;
}

json site_json(const site::SiteCalendar& calendar) {
  const site::SiteProgramme& p = calendar.programme();
  json week = json::object();
  for (int d = 0; d < 7; ++d) {
    json spans = json::array();
    for (const auto& h : p.week[d]) spans.push_back(to_string(h));
    week[site::weekday_keys()[d]] = spans;
  }
  json holidays = json::array();
  for (const auto day : p.holidays) holidays.push_back(site::local_date_text(day));
  return {{"start", calendar.timestamp(0.0)},
          {"start_local", site::local_start_text(p.start_local_s)},
          {"time_zone", p.time_zone},
          {"tzdb", calendar.tzdb_version()},
          {"working_hours", week},
          {"holidays", holidays},
          {"printing", p.printing_attended ? "attended" : "unattended"},
          {"pipes", p.pipes_need_crew ? "crew" : "unattended"}};
}

json material_json(const floors::MaterialProfile& m) {
  json curve = json::array();
  for (const auto& p : m.strength_curve)
    curve.push_back({{"age_s", rounded(p.age_s)}, {"strength_mpa", rounded(p.strength_mpa)}});
  json out = {{"name", m.name},
              {"density_kg_m3", rounded(m.density_kg_m3)},
              {"min_layer_interval_s", rounded(m.min_layer_interval_s)},
              {"max_layer_interval_s", rounded(m.max_layer_interval_s)},
              {"safety_factor", rounded(m.safety_factor)},
              {"delivery_batch_m3", rounded(m.delivery_batch_m3)},
              {"strength_curve", curve}};
  if (m.en1992)
    out["strength_en1992"] = {{"fcm_mpa", rounded(m.en1992->fcm_mpa)},
                              {"cement_class", m.en1992->cement_class},
                              {"s", rounded(m.en1992->s)},
                              {"from_s", rounded(m.en1992->from_s)}};
  return out;
}

json conditions_json(const site::SiteConditions& c) {
  json readings = json::array();
  for (const auto& r : c.readings)
    readings.push_back({rounded(r.t_s), rounded(r.temperature_c), rounded(r.wind_m_s)});
  return {{"source", c.source}, {"readings", readings}};
}

json maturity_json(const floors::MaterialProfile& m) {
  json out = {{"function", m.maturity.name()}};
  if (m.maturity.kind == floors::MaturityFunction::Kind::kArrhenius)
    out["activation_energy_j_mol"] = rounded(m.maturity.activation_energy_j_mol);
  else
    out["datum_temperature_c"] = rounded(m.maturity.datum_temperature_c);
  return out;
}

}  // namespace

RecordedInputs recorded_inputs(const Setup& project, const ScheduleOptions& options,
                               const Schedule* schedule) {
  RecordedInputs in;
  const floors::Building& b = project.building;
  in.building = project.file.string();
  in.name = b.name;
  in.units = floors::to_string(b.units);
  in.layer_height_m = b.layer_height_m;
  in.slab_stage_s = b.slab_stage_s;
  in.lintels = b.lintels;
  in.slabs = b.slabs;
  in.placement = project.placement;
  in.seed = options.seed;
  in.objective = options.objective;
  for (const auto& path : project.files_read())
    in.files.push_back({path.string(), sha256_file_hex(path)});
  const machine::MachineModel& m = *project.machine;
  RecordedMachine& r = in.machine;
  r = machine_limits(m);
  r.origin = project.machine_origin;
  // Which of the files read is the machine's profile (the dry-run loads it again).
  if (!m.source_file.empty()) {
    std::error_code ec;
    const auto source = std::filesystem::weakly_canonical(m.source_file, ec);
    for (const auto& f : in.files)
      if (!ec && std::filesystem::weakly_canonical(f.path, ec) == source && !ec) r.profile = f.path;
  }
  r.nozzles = m.nozzles;
  r.gantry_width_m = m.gantry_width_m;
  r.rail_axis = m.rail_axis;
  r.purge_s = m.purge_s;
  r.pump_capacity_m3_s = m.pump_capacity_m3_s;
  r.bead_width_range_m = m.bead_width_range_m;
  r.climbing = project.climber != nullptr;
  if (project.climber) {
    r.anchor_strength_mpa = project.climber->anchor_strength_mpa;
    r.pipe_embed_s = project.climber->pipe_embed_s;
    r.climb_wind_limit_m_s = project.climber->climb_wind_limit_m_s;
  }
  in.material = project.material;
  in.material_origin = project.material_origin;
  in.calendar = project.calendar;
  in.conditions = project.conditions;
  in.unit_names = project.unit_names();
  for (const auto& floor : b.floors) {
    FloorProvenance p;
    p.floor = floor.index;
    for (const auto& w : floor.plan.walls)
      if (!w.global_id.empty()) p.walls.emplace_back(w.id, w.global_id);
    for (const auto& o : floor.plan.openings)
      if (!o.global_id.empty() && !o.id.empty()) p.openings.emplace_back(o.id, o.global_id);
    const std::size_t at = &floor - b.floors.data();
    const floors::FloorQuantities q =
        schedule && at < schedule->quantities.size()
            ? schedule->quantities[at]
            : floors::floor_quantities(floor, b.layer_height_m, m.nozzle_width_m);
    if (q.model_m3)
      p.quantities = FloorProvenance::Quantities{*q.model_m3, q.printed_modelled_m3, q.printed_m3,
                                                 q.walls_modelled, q.walls_unmodelled};
    if (!p.walls.empty() || !p.openings.empty()) in.provenance.push_back(std::move(p));
  }
  in.left_out = b.left_out;
  if (b.print.stated) in.print = b.print;
  return in;
}

nlohmann::ordered_json schedule_json(const Setup& project, const ScheduleOptions& options,
                                     const Schedule& schedule) {
  return schedule_json(recorded_inputs(project, options, &schedule), schedule);
}

nlohmann::ordered_json schedule_json(const RecordedInputs& in, const Schedule& schedule,
                                     const ScheduleJsonOptions& options) {
  json out;
  out["format"] = "ccbuild-schedule";
  out["schema_version"] = kScheduleSchemaVersion;
  out["ccbuild_version"] = in.ccbuild_version;

  json files = json::array();
  for (const auto& f : in.files) files.push_back({{"path", f.path}, {"sha256", f.sha256}});
  json material = material_json(in.material);
  {
    // A stop for working hours, the cold or lintels may make a planned joint.
    const floors::PlannedJoint& j = in.material.planned_joint;
    material["planned_joint"] = {{"treatment_s", rounded(j.treatment_s)},
                                 {"min_age_s", rounded(j.min_age_s)},
                                 {"max_age_s", rounded(j.max_age_s)}};
  }
  if (in.conditions) {
    material["maturity"] = maturity_json(in.material);
    material["placing_temperature_c"] = {rounded(in.material.placing_min_c),
                                         rounded(in.material.placing_max_c)};
  }
  material["origin"] = in.material_origin;
  const site::SiteCalendar* calendar = in.calendar.get();
  // Seconds, with their local timestamp beside them when there is a calendar.
  const auto times = [calendar](json& j, const char* key, double t_s) {
    j[key] = calendar->timestamp(t_s);
  };
  out["inputs"] = {
      {"building", in.building},
      {"name", in.name},
      {"units", in.units},
      {"layer_height_m", rounded(in.layer_height_m)},
      {"slab_stage_s", rounded(in.slab_stage_s)},
      {"placement",
       {{"how", to_string(in.placement.how)},
        {"origin_m", {rounded(in.placement.origin_m.x()), rounded(in.placement.origin_m.y())}},
        {"rotation_deg", rounded(in.placement.rotation_rad * 180.0 / M_PI)}}},
      {"seed", in.seed},
      {"files", files},
      {"machine", recorded_machine_json(in.machine)},
      {"material", material}};
  // Only for buildings read from a BIM model: older schedules and YAML buildings keep
  // their bytes.
  if (!in.provenance.empty()) {
    json floors_json = json::array();
    for (const auto& p : in.provenance) {
      json walls = json::object(), openings = json::object();
      for (const auto& [id, guid] : p.walls) walls[std::to_string(id)] = guid;
      for (const auto& [id, guid] : p.openings) openings[id] = guid;
      floors_json.push_back({{"floor", p.floor}, {"walls", walls}, {"openings", openings}});
      if (p.quantities) {
        const auto& q = *p.quantities;
        floors_json.back()["quantities"] = {{"model_volume_m3", rounded(q.model_volume_m3)},
                                            {"printed_modelled_m3", rounded(q.printed_modelled_m3)},
                                            {"printed_m3", rounded(q.printed_m3)},
                                            {"walls_modelled", q.walls_modelled},
                                            {"walls_unmodelled", q.walls_unmodelled}};
      }
    }
    out["inputs"]["provenance"] = floors_json;
  }
  if (!in.left_out.empty()) {  // only where the print spec left walls out: others keep their bytes
    json left = json::array();
    for (const auto& w : in.left_out) {
      left.push_back({{"floor", w.floor},
                      {"wall", w.wall_id},
                      {"thickness_m", rounded(w.thickness_m)},
                      {"narrowest_bead_m", rounded(w.narrowest_m)}});
      if (!w.global_id.empty()) left.back()["guid"] = w.global_id;
    }
    out["inputs"]["left_out"] = left;
  }
  if (in.print) {  // only where the building states its print spec: others keep their bytes
    json print = {{"thin_walls", in.print->refuse_thin_walls ? "refuse" : "leave-out"}};
    if (!in.print->wall_types.empty()) {
      print["wall_types"] = in.print->wall_types;
      print["exclude_materials"] = in.print->excluded_materials;
    }
    out["inputs"]["print"] = print;
  }
  {
    const floors::LintelSpec& l = in.lintels;
    out["inputs"]["lintels"] = {{"type", floors::to_string(l.type)},
                                {"height_m", rounded(l.height_m)},
                                {"bearing_m", rounded(l.bearing_m)},
                                {"place_s", rounded(l.place_s)},
                                {"crew", l.crew},
                                {"by", l.by_arm ? "arm" : "crew"}};
  }
  if (in.slabs) {
    const floors::SlabSpec& sl = *in.slabs;
    out["inputs"]["slabs"] = {{"thickness_m", rounded(sl.thickness_m)},
                              {"setup_s", rounded(sl.setup_s)},
                              {"pour_m3_h", rounded(sl.pour_rate_m3_s * 3600.0)},
                              {"ready_mpa", rounded(sl.ready_mpa)},
                              {"concrete",
                               {{"fcm_mpa", rounded(sl.concrete.fcm_mpa)},
                                {"cement_class", sl.concrete.cement_class},
                                {"s", rounded(sl.concrete.s)}}},
                              {"crew", sl.crew},
                              {"roof", sl.roof}};
  }
  if (in.objective != Objective::kFewestNozzles)
    out["inputs"]["objective"] = to_string(in.objective);
  if (calendar) out["inputs"]["site"] = site_json(*calendar);
  if (calendar && in.conditions)
    out["inputs"]["site"]["conditions"] = conditions_json(*in.conditions);
  if (in.conditions && in.machine.climbing)
    out["inputs"]["machine"]["climb_wind_limit_m_s"] = rounded(in.machine.climb_wind_limit_m_s);

  out["feasible"] = schedule.feasible;
  if (schedule.infeasibility) {
    const Infeasibility& inf = *schedule.infeasibility;
    out["infeasibility"] = {
        {"kind", to_string(inf.kind)},
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
  out["totals"] = {{"makespan_s", rounded(t.makespan_s)},
                   {"layers", schedule.layers.size()},
                   {"deposition_s", rounded(t.deposition_s)},
                   {"airtime_s", rounded(t.airtime_s)},
                   {"moves_s", rounded(t.moves_s)},
                   {"waits_s", rounded(t.waits_s)},
                   {"pipes_s", rounded(t.pipes_s)},
                   {"purges_s", rounded(t.purges_s)},
                   {"climbs_s", rounded(t.climbs_s)},
                   {"slabs_s", rounded(t.slabs_s)},
                   {"machine_s", rounded(t.machine_s)},
                   {"concrete_m3", rounded(t.concrete_m3)},
                   {"joints_s", rounded(t.joints_s)},
                   {"lintels_s", rounded(t.lintels_s)},
                   {"crew_h", rounded(t.crew_h)}};
  if (calendar) {
    times(out["totals"], "start_time", 0.0);
    times(out["totals"], "finish_time", t.makespan_s);
    json days = json::array();
    for (const auto& d : schedule.days)
      days.push_back({{"date", d.date},
                      {"layers", d.layers},
                      {"first", {d.first_floor, d.first_layer}},
                      {"last", {d.last_floor, d.last_layer}},
                      {"printing_s", rounded(d.printing_s)},
                      {"concrete_m3", rounded(d.concrete_m3)},
                      {"deliveries", d.deliveries},
                      {"crew_h", rounded(d.crew_h)},
                      {"stop", to_string(d.stop)},
                      {"detail", d.detail}});
    out["days"] = days;
  }

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
    if (calendar) times(j, "start_time", l.start_s), times(j, "end_time", l.end_s);
    j["deposition_s"] = rounded(l.deposition_s);
    j["airtime_s"] = rounded(l.airtime_s);
    j["max_idle_s"] = rounded(l.max_idle_s);
    j["move_before_s"] = rounded(l.move_before_s);
    j["pipes_before_s"] = rounded(l.pipes_before_s);
    j["wait_before_s"] = rounded(l.wait_before_s);
    j["wait_reasons"] = reasons_json(l.wait_reasons);
    j["purge_before"] = l.purge_before;
    j["planned_joint"] = l.planned_joint;
    j["interval_s"] = optional_number(l.interval_s);
    j["local_interval_min_s"] = optional_number(l.local_interval_min_s);
    j["local_interval_max_s"] = optional_number(l.local_interval_max_s);
    j["local_interval_min_at"] =
        l.local_interval_min_s ? piece_end_json(l.local_min_at) : json(nullptr);
    j["local_interval_max_at"] =
        l.local_interval_max_s ? piece_end_json(l.local_max_at) : json(nullptr);
    j["piece_ends_checked"] = l.piece_ends_checked;
    j["concrete_m3"] = rounded(l.concrete_m3);
    j["peak_flow_m3_h"] = rounded(l.peak_flow_m3_s * 3600.0);
    j["below_strength_mpa"] = optional_number(l.below_strength_mpa);
    j["below_required_mpa"] = optional_number(l.below_required_mpa);
    if (in.conditions) {
      j["equivalent_interval_min_s"] = optional_number(l.equivalent_interval_min_s);
      j["equivalent_interval_max_s"] = optional_number(l.equivalent_interval_max_s);
    }
    layers.push_back(j);
  }
  out["layers"] = layers;

  json plans = json::object();
  for (const auto& [key, p] : schedule.plans) {
    json nozzles = json::array();
    const auto digest_json = [](const PathDigest& d) {
      return json{{"waypoints", d.waypoints}, {"sha256", d.sha256}};
    };
    for (std::size_t n = 0; n < p.digests.size(); ++n)
      nozzles.push_back({{"nozzle", n}, {"waypoints_digest", digest_json(p.digests[n])}});
    for (std::size_t n = 0; n < p.waypoints.size(); ++n) {
      json nozzle = {{"nozzle", n}};
      if (options.path_digests)
        nozzle["waypoints_digest"] = digest_json(path_digest(p.waypoints[n]));
      else
        nozzle["waypoints"] = waypoints_json(p.waypoints[n]);
      nozzles.push_back(nozzle);
    }
    plans[key] = {{"geometry", p.geometry},
                  {"nozzles_used", p.nozzles},
                  {"method", p.method},
                  {"z_top_m", rounded(p.z_top_m)},
                  {"layer_time_s", rounded(p.layer_time_s)},
                  {"min_gap_m", p.nozzles > 1 ? json(rounded(p.min_gap_m)) : json(nullptr)},
                  {"pieces", pieces_json(p.layer, in.machine.nozzle_width_m)},
                  {"nozzles", nozzles}};
  }
  out["plans"] = plans;

  json stages = json::array();
  for (const auto& s : schedule.stages) stages.push_back(stage_json(in.unit_names, s));
  out["stages"] = stages;

  json events = json::array();
  for (const auto& e : schedule.events) {
    json j = {{"kind", to_string(e.kind)}, {"start_s", rounded(e.start_s)},
              {"end_s", rounded(e.end_s)}, {"floor", e.floor},
              {"after_layer", e.layer},    {"crew", e.crew},
              {"detail", e.detail}};
    if (calendar) times(j, "start_time", e.start_s), times(j, "end_time", e.end_s);
    if (e.kind == Event::Kind::kPipe || e.kind == Event::Kind::kLintel ||
        e.kind == Event::Kind::kPour || (e.kind == Event::Kind::kSlab && in.slabs))
      j["wait_before_s"] = rounded(e.wait_before_s);
    if (e.kind == Event::Kind::kPour) j["concrete_m3"] = rounded(e.concrete_m3);
    if (e.kind == Event::Kind::kPour || (e.kind == Event::Kind::kSlab && in.slabs))
      j["roof"] = e.roof;
    if (e.lintel) {
      const LintelTask& l = *e.lintel;
      j["lintel"] = {{"opening", l.opening},
                     {"wall", l.wall},
                     {"offset_m", rounded(l.offset_m)},
                     {"width_m", rounded(l.width_m)},
                     {"from_m", rounded(l.from_m)},
                     {"to_m", rounded(l.to_m)},
                     {"start_m", {rounded(l.start_m.x()), rounded(l.start_m.y())}},
                     {"end_m", {rounded(l.end_m.x()), rounded(l.end_m.y())}},
                     {"sill_m", rounded(l.sill_m)},
                     {"head_m", rounded(l.head_m)},
                     {"head_z_m", rounded(l.head_z_m)},
                     {"type", floors::to_string(l.type)},
                     {"height_m", rounded(l.height_m)},
                     {"by", l.by_arm ? "arm" : "crew"}};
    }
    if (e.anchor) j["anchor"] = anchor_json(in.unit_names, *e.anchor);
    if (e.climb) {
      const ClimbEvent& c = *e.climb;
      json anchors = json::array();
      for (const auto& a : c.anchors)
        anchors.push_back({{"id", a.id},
                           {"unit", a.unit},
                           {"age_s", rounded(a.age_s)},
                           {"strength_mpa", rounded(a.strength_mpa)},
                           {"required_mpa", rounded(a.required_mpa)}});
      if (in.conditions)
        for (std::size_t k = 0; k < c.anchors.size(); ++k)
          anchors[k]["equivalent_age_s"] = rounded(c.anchors[k].equivalent_age_s);
      j["from_stage"] = c.from_stage;
      j["to_stage"] = c.to_stage;
      j["wait_before_s"] = rounded(c.wait_before_s);
      j["wait_reasons"] = reasons_json(c.wait_reasons);
      j["anchors"] = anchors;
      json strength = json::array();
      for (const auto& p : c.youngest_anchor_strength)
        strength.push_back({rounded(p.t_s), rounded(p.strength_mpa)});
      j["youngest_anchor_strength"] = strength;
      j["climb"] = climb_plan_json(in.unit_names, c.plan, false);
    }
    events.push_back(j);
  }
  out["events"] = events;
  json deliveries = json::array();
  for (const auto& d : schedule.deliveries) {
    json j = {{"due_s", rounded(d.due_s)}};
    if (calendar) times(j, "due_time", d.due_s);
    j["m3"] = rounded(d.m3);
    j["floor"] = d.floor;
    j["layer"] = d.layer;
    deliveries.push_back(j);
  }
  out["deliveries"] = deliveries;
  out["warnings"] = schedule.warnings;
  return out;
}

}  // namespace ccbuild::schedule
