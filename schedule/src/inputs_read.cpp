#include "inputs_read.hpp"

#include <algorithm>
#include <cmath>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/print_names.hpp"
#include "read_limits.hpp"

namespace ccbuild::schedule::detail {
namespace {
using namespace read_limits;
using json = nlohmann::json;

RecordedMachine read_machine(const JsonAt& m) {
  m.only_keys({"name",
               "deposition_speed_m_s",
               "travel_speed_m_s",
               "x_speed_m_s",
               "y_speed_m_s",
               "z_speed_m_s",
               "rotation_speed_rad_s",
               "rotate_while_moving",
               "accel_delay_s",
               "lift_height_m",
               "lift_time_s",
               "lower_time_s",
               "stopper_min_rad",
               "stopper_max_rad",
               "nozzle_idle_limit_s",
               "nozzle_width_m",
               "x_range_m",
               "y_range_m",
               "z_range_m",
               "origin",
               "profile",
               "nozzles",
               "gantry_width_m",
               "rail_axis",
               "purge_s",
               "pump_capacity_m3_h",
               "bead_width_m",
               "kind",
               "anchor_strength_mpa",
               "pipe_embed_s",
               "climb_wind_limit_m_s"});
  RecordedMachine r;
  r.name = m.at("name").string(1000);
  r.deposition_speed_m_s = m.at("deposition_speed_m_s").number(kSpeed, "m/s");
  r.travel_speed_m_s = m.at("travel_speed_m_s").number(kSpeed, "m/s");
  r.x_speed_m_s = m.at("x_speed_m_s").number(kSpeed, "m/s");
  r.y_speed_m_s = m.at("y_speed_m_s").number(kSpeed, "m/s");
  r.z_speed_m_s = m.at("z_speed_m_s").number(kSpeed, "m/s");
  r.rotation_speed_rad_s = m.at("rotation_speed_rad_s").number(kSpeed, "rad/s");
  r.rotate_while_moving = m.at("rotate_while_moving").boolean();
  r.accel_delay_s = m.at("accel_delay_s").number(Range::closed(0, 1e4), "s");
  r.lift_height_m = m.at("lift_height_m").number(Range::closed(0, 100), "m");
  r.lift_time_s = m.at("lift_time_s").number(Range::closed(0, 1e4), "s");
  r.lower_time_s = m.at("lower_time_s").number(Range::closed(0, 1e4), "s");
  r.stopper_min_rad = m.at("stopper_min_rad").number_or_null(kHeading_rad, "rad");
  r.stopper_max_rad = m.at("stopper_max_rad").number_or_null(kHeading_rad, "rad");
  if (r.stopper_min_rad.has_value() != r.stopper_max_rad.has_value() ||
      (r.stopper_min_rad && *r.stopper_min_rad > *r.stopper_max_rad))
    m.at("stopper_max_rad").refuse("expected both stopper ends or neither, min at most max");
  r.nozzle_idle_limit_s = m.at("nozzle_idle_limit_s").number(kPositive, "s");
  r.nozzle_width_m = m.at("nozzle_width_m").number(Range::above(0, 100), "m");
  auto range = [&](const char* key, double& lo, double& hi) {
    const auto ends = m.at(key).elements(2);
    if (ends.size() != 2) m.at(key).refuse("expected [min, max]");
    lo = ends[0].number(kCoordinate_m, "m");
    hi = ends[1].number(kCoordinate_m, "m");
    if (lo > hi) m.at(key).refuse("expected [min, max] with min at most max");
  };
  range("x_range_m", r.x_min_m, r.x_max_m);
  range("y_range_m", r.y_min_m, r.y_max_m);
  range("z_range_m", r.z_min_m, r.z_max_m);
  r.origin = m.at("origin").string(10'000);
  if (const auto profile = m.maybe("profile")) r.profile = profile->string(4096);
  r.nozzles = static_cast<int>(m.at("nozzles").integer(1, kMaxNozzles));
  r.gantry_width_m = m.at("gantry_width_m").number(Range::closed(0, 1000), "m");
  const std::string axis = m.at("rail_axis").string(10);
  const auto named = machine::rail_axis_named(axis);
  if (!named) m.at("rail_axis").refuse("expected \"x\" or \"y\", got \"" + axis + "\"");
  r.rail_axis = *named;
  r.purge_s = m.at("purge_s").number(Range::closed(0, 1e6), "s");
  if (const auto pump = m.maybe("pump_capacity_m3_h"))
    r.pump_capacity_m3_s = pump->number(Range::above(0.0, 1e4), "m3/h") / 3600.0;
  if (const auto beads = m.maybe("bead_width_m")) {
    const auto ends = beads->elements(2);
    if (ends.size() != 2) beads->refuse("expected [narrowest, widest]");
    const double lo = ends[0].number(Range::above(0, 100), "m");
    const double hi = ends[1].number(Range::above(0, 100), "m");
    if (lo > hi || r.nozzle_width_m < lo || r.nozzle_width_m > hi)
      beads->refuse("expected [narrowest, widest] around nozzle_width_m");
    r.bead_width_range_m = std::make_pair(lo, hi);
  }
  const std::string kind = m.at("kind").string(100);
  if (kind != "climbing" && kind != "fixed gantry")
    m.at("kind").refuse("expected \"climbing\" or \"fixed gantry\", got \"" + kind + "\"");
  r.climbing = kind == "climbing";
  if (r.climbing) {
    r.anchor_strength_mpa = m.at("anchor_strength_mpa").number(kStrength_mpa, "MPa");
    r.pipe_embed_s = m.at("pipe_embed_s").number(kDuration_s, "s");
    if (const auto wind = m.maybe("climb_wind_limit_m_s"))
      r.climb_wind_limit_m_s = wind->number(Range::above(0.0, 100.0), "m/s");
  } else if (m.maybe("anchor_strength_mpa") || m.maybe("pipe_embed_s")) {
    m.refuse("a fixed gantry has no anchor_strength_mpa or pipe_embed_s");
  }
  return r;
}

std::shared_ptr<const site::SiteCalendar> read_site(const JsonAt& j) {
  j.only_keys({"start", "start_local", "time_zone", "tzdb", "working_hours", "holidays", "printing",
               "pipes", "conditions"});
  site::SiteProgramme p;
  p.source = "the schedule's /inputs/site";
  const auto start = site::parse_local_start(j.at("start_local").string(40));
  if (!start) j.at("start_local").refuse("expected a local date and time as YYYY-MM-DD HH:MM[:SS]");
  p.start_local_s = *start;
  p.time_zone = j.at("time_zone").string(100);
  const JsonAt week = j.at("working_hours");
  week.only_keys({"mon", "tue", "wed", "thu", "fri", "sat", "sun"});
  for (int d = 0; d < 7; ++d)
    for (const auto& span : week.at(site::weekday_keys()[d]).elements(8)) {
      const auto hours = site::parse_working_hours(span.string(20));
      if (!hours) span.refuse("expected working hours as HH:MM-HH:MM");
      if (!p.week[d].empty() && hours->from_min < p.week[d].back().to_min)
        span.refuse("spans must follow each other without overlapping");
      p.week[d].push_back(*hours);
    }
  for (const auto& h : j.at("holidays").elements(2000)) {
    const auto day = site::parse_local_date(h.string(20));
    if (!day) h.refuse("expected a date as YYYY-MM-DD");
    if (!p.holidays.empty() && *day <= p.holidays.back()) h.refuse("holidays are listed in order");
    p.holidays.push_back(*day);
  }
  const std::string printing = j.at("printing").string(20), pipes = j.at("pipes").string(20);
  if (printing != "attended" && printing != "unattended")
    j.at("printing").refuse("expected \"attended\" or \"unattended\"");
  if (pipes != "crew" && pipes != "unattended")
    j.at("pipes").refuse("expected \"crew\" or \"unattended\"");
  p.printing_attended = printing == "attended";
  p.pipes_need_crew = pipes == "crew";
  std::shared_ptr<const site::SiteCalendar> calendar;
  try {
    calendar = std::make_shared<const site::SiteCalendar>(std::move(p));
  } catch (const InputError&) {
    j.at("time_zone").refuse("not a time zone of this system's tzdata");
  }
  if (calendar->timestamp(0.0) != j.at("start").string(40))
    j.at("start").refuse("expected " + calendar->timestamp(0.0) + ", start_local in " +
                         calendar->programme().time_zone + " (tzdata " + calendar->tzdb_version() +
                         "; the schedule's was " + j.at("tzdb").string(40) + ")");
  return calendar;
}

void read_material(const JsonAt& m, RecordedInputs& in) {
  m.only_keys({"name", "density_kg_m3", "min_layer_interval_s", "max_layer_interval_s",
               "safety_factor", "strength_curve", "planned_joint", "strength_en1992", "maturity",
               "delivery_batch_m3", "placing_temperature_c", "origin"});
  if (const auto batch = m.maybe("delivery_batch_m3"))
    in.material.delivery_batch_m3 = batch->number(Range::above(0.0, 1e4), "m3");
  if (const auto en = m.maybe("strength_en1992")) {
    en->only_keys({"fcm_mpa", "cement_class", "s", "from_s"});
    floors::En1992Strength e;
    e.fcm_mpa = en->at("fcm_mpa").number(Range::above(0.0, 500.0), "MPa");
    e.cement_class = en->at("cement_class").string(2);
    e.s = en->at("s").number(Range::above(0.0, 1.0), "");
    e.from_s = en->at("from_s").number(kDuration_s, "s");
    in.material.en1992 = e;
  }
  if (const auto maturity = m.maybe("maturity")) {
    maturity->only_keys({"function", "activation_energy_j_mol", "datum_temperature_c"});
    floors::MaturityFunction& f = in.material.maturity;
    const std::string name = maturity->at("function").string(20);
    if (name == "arrhenius") {
      f.kind = floors::MaturityFunction::Kind::kArrhenius;
      f.activation_energy_j_mol =
          maturity->at("activation_energy_j_mol").number(Range::above(0.0, 1e6), "J/mol");
    } else if (name == "nurse-saul") {
      f.kind = floors::MaturityFunction::Kind::kNurseSaul;
      f.datum_temperature_c =
          maturity->at("datum_temperature_c").number(Range::closed(-60, 19), "°C");
    } else {
      maturity->at("function").refuse("expected \"arrhenius\" or \"nurse-saul\"");
    }
  }
  if (const auto placing = m.maybe("placing_temperature_c")) {
    const auto range = placing->elements(2);
    if (range.size() != 2) placing->refuse("expected [min, max]");
    in.material.placing_min_c = range[0].number(Range::closed(-60.0, 60.0), "°C");
    in.material.placing_max_c = range[1].number(Range::closed(-60.0, 60.0), "°C");
  }
  if (const auto joint = m.maybe("planned_joint")) {
    joint->only_keys({"treatment_s", "min_age_s", "max_age_s"});
    floors::PlannedJoint& pj = in.material.planned_joint;
    pj.treatment_s = joint->at("treatment_s").number(kDuration_s, "s");
    pj.min_age_s = joint->at("min_age_s").number(kDuration_s, "s");
    pj.max_age_s = joint->at("max_age_s").number(kDuration_s, "s");
  }
  floors::MaterialProfile& p = in.material;
  p.name = m.at("name").string(1000);
  p.density_kg_m3 = m.at("density_kg_m3").number(Range::above(0, 1e5), "kg/m3");
  p.min_layer_interval_s = m.at("min_layer_interval_s").number(kDuration_s, "s");
  p.max_layer_interval_s = m.at("max_layer_interval_s").number(kDuration_s, "s");
  if (p.min_layer_interval_s > p.max_layer_interval_s)
    m.at("max_layer_interval_s").refuse("must be at least min_layer_interval_s");
  p.safety_factor = m.at("safety_factor").number(Range::above(0, 1e3), "");
  const auto curve = m.at("strength_curve").elements(kMaxSmall);
  if (curve.empty()) m.at("strength_curve").refuse("expected at least one point");
  for (const auto& point : curve) {
    point.only_keys({"age_s", "strength_mpa"});
    const double age_s = point.at("age_s").number(kDuration_s, "s");
    const double mpa = point.at("strength_mpa").number(kStrength_mpa, "MPa");
    if (!p.strength_curve.empty() &&
        (age_s <= p.strength_curve.back().age_s || mpa < p.strength_curve.back().strength_mpa))
      point.refuse("ages must increase and strengths not decrease along the curve");
    p.strength_curve.push_back({age_s, mpa});
  }
  in.material_origin = m.at("origin").string(10'000);
}

}  // namespace

void read_lintel_kind(const JsonAt& j, floors::LintelSpec::Type& type, bool& by_arm) {
  const std::string name = j.at("type").string(20);
  if (name != "precast" && name != "formwork")
    j.at("type").refuse("expected \"precast\" or \"formwork\", got \"" + name + "\"");
  type =
      name == "precast" ? floors::LintelSpec::Type::kPrecast : floors::LintelSpec::Type::kFormwork;
  const std::string by = j.at("by").string(10);
  if (by != "crew" && by != "arm")
    j.at("by").refuse("expected \"crew\" or \"arm\", got \"" + by + "\"");
  by_arm = by == "arm";
}

RecordedInputs read_inputs(const JsonAt& root) {
  RecordedInputs in;
  in.ccbuild_version = root.at("ccbuild_version").string(100);
  const JsonAt i = root.at("inputs");
  i.only_keys({"building", "name", "units", "layer_height_m", "slab_stage_s", "placement", "seed",
               "files", "machine", "material", "provenance", "site", "objective", "lintels",
               "slabs", "left_out", "print"});
  in.building = i.at("building").string(4096);
  in.name = i.at("name").string(1000);
  in.units = i.at("units").string(10);
  if (in.units != "m" && in.units != "ft")
    i.at("units").refuse("expected \"m\" or \"ft\", got \"" + in.units + "\"");
  in.layer_height_m = i.at("layer_height_m").number(Range::above(0, 100), "m");
  in.slab_stage_s = i.at("slab_stage_s").number(kDuration_s, "s");
  if (const auto placed = i.maybe("placement")) {
    placed->only_keys({"how", "origin_m", "rotation_deg"});
    const std::string how = placed->at("how").string(20);
    const auto named = placed_by_named(how);
    if (!named)
      placed->at("how").refuse("expected \"as drawn\", \"site\" or \"centred\", got \"" + how +
                               "\"");
    in.placement.how = *named;
    const auto origin = placed->at("origin_m").elements(3);
    if (origin.size() != 2) placed->at("origin_m").refuse("expected [x, y]");
    in.placement.origin_m = {origin[0].number(floors::limits::kCoordinate_m, "m"),
                             origin[1].number(floors::limits::kCoordinate_m, "m")};
    in.placement.rotation_rad =
        placed->at("rotation_deg").number(Range::closed(-360.0, 360.0), "deg") * M_PI / 180.0;
  }
  in.seed = i.at("seed").unsigned_integer();
  if (const auto objective = i.maybe("objective")) {
    const std::string name = objective->string(20);
    if (name == "shortest")
      in.objective = Objective::kShortest;
    else if (name != "fewest-nozzles")
      objective->refuse("expected \"fewest-nozzles\" or \"shortest\", got \"" + name + "\"");
  }
  for (const auto& f : i.at("files").elements(kMaxSmall)) {
    f.only_keys({"path", "sha256"});
    RecordedFile file{f.at("path").string(4096), f.at("sha256").string(64)};
    const bool hex =
        file.sha256.size() == 64 && std::all_of(file.sha256.begin(), file.sha256.end(), [](char c) {
          return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
        });
    if (!hex) f.at("sha256").refuse("expected 64 lowercase hex digits (a SHA-256)");
    in.files.push_back(std::move(file));
  }
  if (const auto provenance = i.maybe("provenance")) {
    for (const auto& f : provenance->elements(kMaxSmall)) {
      f.only_keys({"floor", "walls", "openings", "quantities"});
      FloorProvenance p;
      p.floor = static_cast<int>(f.at("floor").integer(0, floors::limits::kMaxFloors));
      for (const auto& [id, guid] : f.at("walls").members(kMaxItems)) {
        std::size_t used = 0;
        long long wall = 0;
        try {
          wall = std::stoll(id, &used);
        } catch (const std::exception&) {
        }
        if (used != id.size() || wall < 1)
          guid.refuse("expected a wall id as the key, got \"" + id + "\"");
        p.walls.emplace_back(wall, guid.string(64));
      }
      for (const auto& [id, guid] : f.at("openings").members(kMaxItems))
        p.openings.emplace_back(id, guid.string(64));
      if (const auto q = f.maybe("quantities")) {
        q->only_keys({"model_volume_m3", "printed_modelled_m3", "printed_m3", "walls_modelled",
                      "walls_unmodelled"});
        FloorProvenance::Quantities read;
        const Range volume_m3 = Range::closed(0.0, 1e9);
        const auto walls = static_cast<std::int64_t>(floors::limits::kMaxWalls);
        read.model_volume_m3 = q->at("model_volume_m3").number(volume_m3, "m3");
        read.printed_modelled_m3 = q->at("printed_modelled_m3").number(volume_m3, "m3");
        read.printed_m3 = q->at("printed_m3").number(volume_m3, "m3");
        read.walls_modelled = static_cast<int>(q->at("walls_modelled").integer(0, walls));
        read.walls_unmodelled = static_cast<int>(q->at("walls_unmodelled").integer(0, walls));
        p.quantities = read;
      }
      in.provenance.push_back(std::move(p));
    }
  }
  if (const auto left = i.maybe("left_out")) {
    for (const auto& w : left->elements(kMaxItems)) {
      w.only_keys({"floor", "wall", "thickness_m", "narrowest_bead_m", "guid"});
      floors::LeftOutWall out;
      out.floor = static_cast<int>(w.at("floor").integer(0, floors::limits::kMaxFloors));
      out.wall_id = w.at("wall").integer(1, kMaxWallId);
      out.thickness_m = w.at("thickness_m").number(Range::above(0, 100), "m");
      out.narrowest_m = w.at("narrowest_bead_m").number(Range::above(0, 100), "m");
      if (out.thickness_m >= out.narrowest_m)
        w.at("thickness_m").refuse("expected a wall thinner than narrowest_bead_m");
      if (const auto guid = w.maybe("guid")) out.global_id = guid->string(64);
      in.left_out.push_back(std::move(out));
    }
  }
  if (const auto p = i.maybe("print")) {
    p->only_keys({"thin_walls", "wall_types", "exclude_materials"});
    floors::PrintSpec spec;
    spec.stated = true;
    const std::string thin = p->at("thin_walls").string(16);
    if (thin != "leave-out" && thin != "refuse")
      p->at("thin_walls").refuse("expected leave-out or refuse");
    spec.refuse_thin_walls = thin == "refuse";
    if (const auto types = p->maybe("wall_types")) {
      for (const auto& t : types->elements(floors::limits::kMaxPrintNames)) {
        spec.wall_types.push_back(t.string(64));
        if (const auto fault = floors::wall_type_name_fault(spec.wall_types.back()); !fault.empty())
          t.refuse(fault);
      }
      if (spec.wall_types.empty()) types->refuse("expected at least one wall type");
      for (const auto& m : p->at("exclude_materials").elements(floors::limits::kMaxPrintNames)) {
        spec.excluded_materials.push_back(m.string(100));
        if (const auto fault = floors::excluded_material_name_fault(spec.excluded_materials.back());
            !fault.empty())
          m.refuse(fault);
      }
    } else if (p->maybe("exclude_materials")) {
      p->at("exclude_materials").refuse("expected beside wall_types only");
    }
    in.print = std::move(spec);
  }
  if (const auto l = i.maybe("lintels")) {
    l->only_keys({"type", "height_m", "bearing_m", "place_s", "crew", "by"});
    read_lintel_kind(*l, in.lintels.type, in.lintels.by_arm);
    in.lintels.height_m = l->at("height_m").number(floors::limits::kLintelHeight_m, "m");
    in.lintels.bearing_m = l->at("bearing_m").number(floors::limits::kLintelBearing_m, "m");
    in.lintels.place_s = l->at("place_s").number(floors::limits::kLintelPlace_s, "s");
    in.lintels.crew = static_cast<int>(l->at("crew").integer(0, 100));
  }
  if (const auto sl = i.maybe("slabs")) {
    sl->only_keys({"thickness_m", "setup_s", "pour_m3_h", "ready_mpa", "concrete", "crew", "roof"});
    floors::SlabSpec spec;
    spec.thickness_m = sl->at("thickness_m").number(floors::limits::kSlabThickness_m, "m");
    spec.setup_s = sl->at("setup_s").number(floors::limits::kSlabSetup_s, "s");
    spec.pour_rate_m3_s = sl->at("pour_m3_h").number(Range::above(0.1, 500.0), "m3/h") / 3600.0;
    spec.ready_mpa = sl->at("ready_mpa").number(floors::limits::kSlabReady_mpa, "MPa");
    const JsonAt c = sl->at("concrete");
    c.only_keys({"fcm_mpa", "cement_class", "s"});
    spec.concrete.fcm_mpa = c.at("fcm_mpa").number(Range::above(0, 200), "MPa");
    spec.concrete.cement_class = c.at("cement_class").string(2);
    spec.concrete.s = c.at("s").number(Range::closed(0.0, 1.0), "");
    spec.crew = static_cast<int>(sl->at("crew").integer(0, 100));
    spec.roof = sl->at("roof").boolean();
    in.slabs = spec;
  }
  in.machine = read_machine(i.at("machine"));
  if (!in.machine.profile.empty() &&
      std::none_of(in.files.begin(), in.files.end(),
                   [&](const RecordedFile& f) { return f.path == in.machine.profile; }))
    i.at("machine").at("profile").refuse("expected one of the paths of /inputs/files, got \"" +
                                         in.machine.profile + "\"");
  read_material(i.at("material"), in);
  if (const auto site = i.maybe("site")) {
    in.calendar = read_site(*site);
    if (const auto c = site->maybe("conditions")) {
      c->only_keys({"source", "readings"});
      auto conditions = std::make_shared<site::SiteConditions>();
      conditions->source = c->at("source").string(10'000);
      for (const auto& r : c->at("readings").elements(site::kMaxWeatherReadings)) {
        const auto v = r.elements(3);
        if (v.size() != 3) r.refuse("expected [t_s, temperature_c, wind_m_s]");
        const site::WeatherReading w{v[0].number(Range::closed(-1e10, 1e10), "s"),
                                     v[1].number(Range::closed(-60.0, 60.0), "°C"),
                                     v[2].number(Range::closed(0.0, 80.0), "m/s")};
        if (!conditions->readings.empty() && w.t_s <= conditions->readings.back().t_s)
          r.refuse("readings are listed in time order");
        conditions->readings.push_back(w);
      }
      if (conditions->readings.empty()) c->at("readings").refuse("expected at least one reading");
      in.conditions = std::move(conditions);
    }
  }
  return in;
}

}  // namespace ccbuild::schedule::detail
