#include "ccbuild/schedule/project.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/plane.hpp"
#include "ccbuild/import/dxf.hpp"
#include "ccbuild/import/ifc.hpp"

namespace ccbuild::schedule {
namespace fs = std::filesystem;

namespace {

// The bundled profiles, for a lone plan that names none.
fs::path bundled(const char* relative) {
  return fs::path(CCBUILD_CONFIG_DIR) / relative;
}

// The material used when neither the user nor a building names one and the bundled
// profile is missing (an installed binary without its config folder).
floors::MaterialProfile default_material() {
  floors::MaterialProfile m;
  m.name = "built-in default mix";
  m.density_kg_m3 = 2200.0;
  m.min_layer_interval_s = 180.0;
  m.max_layer_interval_s = 2400.0;
  m.strength_curve = {{0.0, 0.005}, {3600.0, 0.08}, {86'400.0, 6.0}, {604'800.0, 20.0}};
  return m;
}

// Places the building in the machine's frame: its site's rotation, then its site's origin
// or (asked for either way) the middle of the machine's x and y travel.
void place(Project& project, bool centre, std::optional<double> rotation_deg) {
  floors::Building& b = project.building;
  const floors::Site site = b.site.value_or(floors::Site{});
  schedule::Placement& placed = project.placement;
  placed.rotation_rad = rotation_deg ? *rotation_deg * M_PI / 180.0 : site.rotation_rad;
  floors::place_building(b, placed.rotation_rad, Eigen::Vector2d::Zero());
  if (centre || site.centre) {
    const machine::MachineModel& m = *project.machine;
    const floors::Envelope space = floors::envelope(b);
    const Eigen::Vector2d middle_m(0.5 * (m.x.min_m + m.x.max_m), 0.5 * (m.y.min_m + m.y.max_m));
    placed.origin_m = middle_m - 0.5 * (space.min_m + space.max_m);
    placed.how = PlacedBy::kCentred;
  } else if (b.site && b.site->places) {
    placed.origin_m = site.origin_m.value_or(Eigen::Vector2d::Zero());
    placed.how = PlacedBy::kSite;
  }
  floors::place_building(b, 0.0, placed.origin_m);
}

}  // namespace

std::optional<FittingTurn> turn_that_fits(const floors::Building& building, double now_deg,
                                          double reach_x_m, double reach_y_m) {
  // A footprint's narrowest boxes lie along its outline's convex hull's edges.
  std::vector<Eigen::Vector2d> points;
  for (const auto& floor : building.floors)
    for (const auto& v : floor.plan.vertices) points.push_back(v.position_m);
  if (points.size() < 2) return std::nullopt;
  const std::vector<Eigen::Vector2d> hull = floors::convex_hull(std::move(points));
  // Each edge along x or along y; the turn as `site: rotation_deg` says it (from the
  // building's own axes), rounded to 0.01 degree. The hull's corners rank the turns by the
  // room they leave; the best few are checked at their rounded value, walls included. The
  // most room to spare wins, the smaller turn on a tie.
  constexpr std::size_t kMostHullCorners = 1000, kTurnsChecked = 8;
  constexpr double kLeastRoom_m = 1e-6;
  if (hull.size() > kMostHullCorners) return std::nullopt;
  std::vector<std::pair<double, double>> ranked;  // (room by the corners, m; turn, deg)
  for (std::size_t e = 0; e < hull.size(); ++e) {
    const Eigen::Vector2d d = hull[(e + 1) % hull.size()] - hull[e];
    if (d.norm() < 1e-9) continue;
    const double edge_deg = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
    for (const double along : {0.0, 90.0}) {
      // A half turn leaves the footprint's size as it is: the turn within (-90, 90].
      double deg = std::round(std::remainder(now_deg - edge_deg + along, 180.0) * 100.0) / 100.0;
      if (deg <= -90.0) deg += 180.0;
      deg += 0.0;  // -0 is said as 0
      const Eigen::Rotation2Dd by((deg - now_deg) * M_PI / 180.0);
      Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
      Eigen::Vector2d hi = -lo;
      for (const auto& p : hull) {
        lo = lo.cwiseMin(by * p);
        hi = hi.cwiseMax(by * p);
      }
      ranked.emplace_back(std::min(reach_x_m - (hi - lo).x(), reach_y_m - (hi - lo).y()), deg);
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::optional<FittingTurn> best;
  double best_room_m = -1.0;
  for (std::size_t i = 0; i < ranked.size() && i < kTurnsChecked; ++i) {
    const double deg = ranked[i].second;
    if (ranked[i].first < 0.0) break;
    floors::Building turned = building;
    floors::place_building(turned, (deg - now_deg) * M_PI / 180.0, Eigen::Vector2d::Zero());
    const Eigen::Vector2d size = floors::envelope(turned).size_m();
    const double room_m = std::min(reach_x_m - size.x(), reach_y_m - size.y());
    // Within 1 µm of the travel is not proposed: a turn applied anew rounds otherwise.
    if (room_m < kLeastRoom_m) continue;
    if (!best || room_m > best_room_m + 1e-9 ||
        (room_m > best_room_m - 1e-9 && std::abs(deg) < std::abs(best->deg))) {
      best = FittingTurn{deg, size};
      best_room_m = room_m;
    }
  }
  return best;
}

Project open_project(const fs::path& file, const ProjectOptions& options) {
  Project project;
  project.file = file;
  if (import::is_ifc_path(file)) {
    // An IFC model is a building; its profiles are the flags' or the bundled ones.
    import::IfcOptions ifc;
    ifc.layer_height_m = options.plan_layer_height_m;
    project.is_building = true;
    project.building = import::read_ifc_building(file, ifc).building;
  } else {
    floors::BuildingOrPlan input =
        floors::load_building_or_plan(file, options.plan_unit, import::read_drawing);
    project.is_building = input.is_building;
    if (input.is_building) {
      project.building = std::move(input.building);
    } else {
      project.building =
          floors::building_from_plan(std::move(input.plan), file.stem().string(),
                                     options.plan_floor_height_m, options.plan_layer_height_m);
    }
  }
  project.file_unit = project.building.units;
  if (options.shown_unit) {
    project.building.units = *options.shown_unit;
    for (floors::Floor& floor : project.building.floors) floor.plan.units = *options.shown_unit;
  }
  const floors::Building& b = project.building;

  // --machine, else the building's, else the bundled profile (else built-in defaults
  // when an installed binary has no config folder).
  const auto pick = [&](const fs::path& given, const fs::path& buildings, const char* bundled_file,
                        const char* flag) {
    if (!given.empty())
      return std::pair<fs::path, std::string>(given, std::string("(") + flag + ")");
    if (project.is_building && !buildings.empty())
      return std::pair<fs::path, std::string>(buildings, "(the building's)");
    return std::pair<fs::path, std::string>(bundled(bundled_file), "(bundled default)");
  };
  std::error_code ec;
  const auto [machine_path, machine_why] =
      pick(options.machine_profile, b.machine_profile, "machines/cc-gantry.yaml", "--machine");
  if (machine_why == "(bundled default)" && !fs::exists(machine_path, ec)) {
    project.machine =
        std::make_shared<const machine::MachineModel>(machine::MachineModel::defaults());
    project.machine_origin = "built-in defaults";
  } else {
    machine::MachineProfile profile = machine::load_machine_profile(machine_path);
    std::string fitted;
    if (profile.family) {
      // A family: its member is built around the building where it stands, as printed:
      // the walls thinner than its beads are the crew's, not the platform's to span or its
      // units' to pin into.
      place(project, false, options.rotation_deg);
      floors::leave_out_thin_walls(project.building, bead_spec(profile.gantry, project.building));
      climb::FitOptions fit;
      fs::path out = options.fitted_profile;
      if (out.empty())
        out = machine_path.parent_path() / (machine_path.stem().string() + "-fitted.yaml");
      fit.profile_path = out.string();
      fit.urdf_file = out.stem().string() + ".urdf";
      fit.progress = options.progress;
      auto result = std::make_shared<climb::FitResult>(
          climb::fit_climbing_machine(project.building, *profile.family, fit));
      if (!result->status) throw NoFit(std::move(*result));
      const std::vector<fs::path> family_files = profile.gantry.files_read;
      profile = result->profile;
      profile.gantry.files_read = family_files;
      if (profile.climbing) {
        auto climber = std::make_shared<machine::ClimbingMachine>(*profile.climbing);
        climber->files_read = family_files;
        climber->gantry.files_read = family_files;
        profile.climbing = climber;
      }
      fitted = ", fitted to this building (" + result->summary + ")";
      project.fit = std::move(result);
    }
    project.machine = std::make_shared<const machine::MachineModel>(std::move(profile.gantry));
    project.climber = std::move(profile.climbing);
    project.machine_origin =
        project.machine->name + ", " + machine_path.string() + " " + machine_why + fitted;
  }
  const auto [material_path, material_why] = pick(options.material_profile, b.material_profile,
                                                  "materials/standard-mix.yaml", "--material");
  if (material_why == "(bundled default)" && !fs::exists(material_path, ec)) {
    project.material = default_material();
    project.material_origin = "built-in defaults";
  } else {
    project.material = floors::load_material_profile(material_path);
    project.material_origin =
        project.material.name + ", " + material_path.string() + " " + material_why;
  }
  // What the machine prints: walls thinner than its beads are left to the crew before the
  // building is placed on it (a family's fit left them out already, with the same beads).
  const floors::BeadSpec beads = bead_spec(*project.machine, project.building);
  for (auto& floor : project.building.floors) floor.plan.beads = beads;
  floors::leave_out_thin_walls(project.building, beads);
  if (!project.fit) place(project, options.place_centre, options.rotation_deg);
  // The site's programme: --site FILE, else the building's `site:`.
  std::optional<site::SiteProgramme> programme;
  if (!options.site_file.empty()) {
    programme = site::load_site_programme(options.site_file.string());
    project.site_file = options.site_file;
  } else if (b.site && b.site->programme) {
    const Document& doc = *b.site->programme;
    programme = site::read_site_programme(Field(doc, doc.root, "site"), floors::kSitePlacementKeys);
  }
  if (programme) {
    project.calendar = std::make_shared<const site::SiteCalendar>(std::move(*programme));
    const site::SiteProgramme& p = project.calendar->programme();
    if (!p.weather_file.empty())
      project.conditions = std::make_shared<const site::SiteConditions>(
          site::read_weather_csv(p.weather_file, *project.calendar));
    else if (p.temperature_c || p.wind_m_s)
      project.conditions = std::make_shared<const site::SiteConditions>(
          site::constant_conditions(p.temperature_c.value_or(20.0), p.wind_m_s.value_or(0.0)));
  }
  check_fit(project);
  return project;
}

floors::BeadSpec bead_spec(const machine::MachineModel& machine, const floors::Building& building) {
  auto [narrowest_m, widest_m] = machine.bead_widths();
  // A bead W wide draws W x layer height x deposition speed: the pump bounds the widest
  // (never under the nozzle's own width; a pump that cannot feed that refuses the plans).
  if (machine.pump_capacity_m3_s && building.layer_height_m > 0.0 &&
      machine.deposition_speed_m_s > 0.0)
    widest_m =
        std::max(machine.nozzle_width_m,
                 std::min(widest_m, *machine.pump_capacity_m3_s /
                                        (building.layer_height_m * machine.deposition_speed_m_s)));
  return {machine.nozzle_width_m, building.wall_pattern, narrowest_m, widest_m};
}

NoFit::NoFit(climb::FitResult result)
    : std::runtime_error("no member of the machine family climbs the building: " +
                         result.status.to_string()),
      fit(std::move(result)) {}

void check_fit(const Project& project) {
  const floors::Building& b = project.building;
  const machine::MachineModel& m = *project.machine;
  const std::string where = m.source_file.empty() ? std::string("built-in machine") : m.source_file;
  auto L = [&](double value_m) { return project.length(value_m, 2); };
  // Footprint against the x and y travel: too large to fit wherever it is placed.
  const floors::Envelope space = floors::envelope(b);
  const Eigen::Vector2d extent = space.size_m();
  const double reach_x = m.x.max_m - m.x.min_m, reach_y = m.y.max_m - m.y.min_m;
  if (extent.x() > reach_x || extent.y() > reach_y) {
    std::string turn;
    const double now_deg = project.placement.rotation_rad * 180.0 / M_PI;
    if (const auto fits = turn_that_fits(b, now_deg, reach_x, reach_y)) {
      const std::string d = printf_string("%.2f", fits->deg);
      turn = "; turned by " + d + " degrees it is " + L(fits->size_m.x()) + " x " +
             L(fits->size_m.y()) + " and fits: `--rotate " + d +
             " --place centre`, or `site: {rotation_deg: " + d +
             ", place: centre}` in the building file";
    }
    throw InputError(where, 0, "",
                     "the building is " + L(extent.x()) + " x " + L(extent.y()) +
                         " but the machine reaches " + L(reach_x) + " x " + L(reach_y) +
                         " (its x and y joints' ranges)" + turn);
  }
  // Where it stands: every vertex within each axis's travel.
  DiagnosticSink outside;
  const char* hint = b.site && b.site->places && !b.site->centre
                         ? "`site: {origin: [x, y]}` in the building file"
                         : "with `site: {origin: [x, y]}` in a building file";
  for (int axis = 0; axis < 2; ++axis) {
    const machine::AxisLimits& travel = axis == 0 ? m.x : m.y;
    const char* name = axis == 0 ? "x" : "y";
    const floors::Vertex* low = nullptr;
    const floors::Vertex* high = nullptr;
    std::string low_floor, high_floor;
    for (const auto& floor : b.floors)
      for (const auto& v : floor.plan.vertices) {
        if (!low || v.position_m[axis] < low->position_m[axis]) {
          low = &v;
          low_floor = floor.name;
        }
        if (!high || v.position_m[axis] > high->position_m[axis]) {
          high = &v;
          high_floor = floor.name;
        }
      }
    if (!low) continue;
    const double span_low_m = low->position_m[axis], span_high_m = high->position_m[axis];
    const auto report = [&](const floors::Vertex& v, const std::string& floor, double beyond_m,
                            bool below) {
      outside.add({v.source.file, v.source.line, v.source.path.empty() ? "vertices" : v.source.path,
                   "floor '" + floor + "' vertex " + std::to_string(v.id) + " stands at " + name +
                       " = " + L(v.position_m[axis]) + " on the machine, " +
                       project.length(beyond_m) + (below ? " before the start" : " past the end") +
                       " of its " + name + " travel (" + L(below ? travel.min_m : travel.max_m) +
                       "): the building spans " + name + " " + L(span_low_m) + " to " +
                       L(span_high_m) + ", the machine's " + name + " travel " + L(travel.min_m) +
                       " to " + L(travel.max_m) + "; move the building by " + (below ? "+" : "-") +
                       project.length(beyond_m) + " or more along " + name + " (" + hint +
                       "), or centre it with --place centre"});
    };
    if (span_low_m < travel.min_m - 1e-9) report(*low, low_floor, travel.min_m - span_low_m, true);
    if (span_high_m > travel.max_m + 1e-9)
      report(*high, high_floor, span_high_m - travel.max_m, false);
  }
  outside.throw_if_any();
  // Height: the top layer is printed at the top of the building, and the nozzle must
  // still lift over the walls there.
  const double top_m = space.top_m;
  const double reach_z = m.z.max_m - m.z.min_m;
  if (!project.climber && top_m + m.lift_height_m > reach_z + 1e-9)
    throw InputError(where, 0, "",
                     "the building is " + L(top_m) + " tall, and the nozzle lifts " +
                         L(m.lift_height_m) +
                         " over its walls, but the machine's z joint reaches " + L(reach_z) +
                         "; this machine cannot build it");
  // Beads (floors::wall_beads): one pass up to the widest bead, two skins, or skins and the
  // pattern's fill; a wall no bead or two skins make up cannot be printed by this machine.
  DiagnosticSink sink;
  const floors::BeadSpec spec = bead_spec(m, b);
  const double narrowest_m = spec.narrowest_m, widest_m = spec.widest_m;
  const bool pumped = widest_m < m.bead_widths().second;
  const auto up = [&](double v) {
    return floors::length_text(v, b.units, 3, floors::Towards::kUp);
  };
  const auto down = [&](double v) {
    return floors::length_text(v, b.units, 3, floors::Towards::kDown);
  };
  for (const auto& floor : b.floors)
    for (const auto& wall : floor.plan.walls) {
      if (!wall.thickness_m) continue;
      const double t = *wall.thickness_m;
      const floors::WallPrint how = floors::wall_beads(t, spec).how;
      if (how != floors::WallPrint::kTooThin && how != floors::WallPrint::kBetween) continue;
      const bool thin = how == floors::WallPrint::kTooThin;
      const std::string range =
          narrowest_m == widest_m ? project.length(narrowest_m)
                                  : project.length(narrowest_m) + " to " + project.length(widest_m);
      sink.add({wall.source.file, wall.source.line,
                wall.source.path.empty() ? "thickness" : wall.source.path + ".thickness",
                "wall " + std::to_string(wall.id) + " is " + project.length(t) + " thick, but " +
                    m.name + " lays beads " + range + " wide (bead_width_m, else nozzle_width_m" +
                    (pumped ? std::string("; the widest its pump feeds at this layer height and "
                                          "speed, pump_capacity_m3_h")
                            : std::string()) +
                    "), and a wall is printed " +
                    (thin ? "at least one bead wide"
                          : "as one bead, as two skins of half the wall each, or as two skins of "
                            "the nozzle's width and what lies between them (wall_pattern)") +
                    ": make it " +
                    (thin ? up(narrowest_m) + " or more"
                          : down(widest_m) + " or less (one bead) or " + up(2.0 * narrowest_m) +
                                " or more (two skins)") +
                    ", or use a machine whose beads reach " +
                    (thin ? down(t) + " (the narrowest of bead_width_m), or leave it to the crew "
                                      "(print: {thin_walls: leave-out})"
                          : up(t) + " (the widest of bead_width_m) or down to " + down(0.5 * t) +
                                " (the narrowest)")});
    }
  sink.throw_if_any();
}

floors::Layer layer_of(const Project& project, int floor, std::optional<int> layer) {
  const floors::Building& b = project.building;
  check_floor(project, floor);
  const floors::Floor& f = b.floors[floor];
  if (!project.is_building && !layer) return floors::plan_as_layer(f.plan);
  const int count = floors::layer_count(f.height_m, b.layer_height_m);
  const int k = layer.value_or(0);
  if (k < 0 || k >= count)
    throw InputError("", 0, "layer",
                     "no layer " + std::to_string(k) + "; floor " + std::to_string(floor) +
                         " has layers 0 to " + std::to_string(count - 1));
  return floors::slice_floor_layer(f, b.layer_height_m, k);
}

std::vector<DistinctLayer> distinct_layers(const Project& project, std::optional<int> floor,
                                           std::optional<int> layer) {
  const floors::Building& b = project.building;
  if (floor) check_floor(project, *floor);
  std::vector<DistinctLayer> out;
  floors::GeometryNumbering numbering;
  for (const auto& f : b.floors) {
    if (floor && f.index != *floor) continue;
    std::vector<floors::Layer> layers;
    if (!project.is_building && !layer)
      layers.push_back(floors::plan_as_layer(f.plan));
    else if (!layer)
      layers = floors::slice_floor(f, b.layer_height_m);
    else if (*layer >= 0 && *layer < floors::layer_count(f.height_m, b.layer_height_m))
      layers.push_back(floors::slice_floor_layer(f, b.layer_height_m, *layer));  // that one only
    for (auto& l : layers) {
      bool fresh = false;
      const int label = numbering.number(l, &fresh);
      if (label == 0) continue;
      const LayerRef ref{f.index, l.index};
      if (fresh) {
        DistinctLayer d;
        d.key = floors::GeometryKey(l);
        d.label = label;
        d.layer = std::move(l);
        out.push_back(std::move(d));
      }
      out[label - 1].where.push_back(ref);
    }
  }
  if (layer && out.empty())
    throw InputError("", 0, "layer",
                     "no layer " + std::to_string(*layer) + " with walls on the floors selected");
  return out;
}

LayerPlanResult plan_layer(const Project& project, const floors::Layer& layer,
                           const LayerPlanRequest& request) {
  return planner::plan_layer_nozzles(layer, *project.machine, request);
}

}  // namespace ccbuild::schedule
