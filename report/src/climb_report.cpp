#include "ccbuild/report/climb_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/machine/climbing_family.hpp"
#include "ccbuild/schedule/json_blocks.hpp"
#include "report_common.hpp"
#include "svg.hpp"

namespace ccbuild::report {

using detail::json;
using detail::rounded;

nlohmann::ordered_json climb_report_json(const schedule::Setup& project,
                                         const schedule::ClimbReport& report) {
  json out;
  out["format"] = "ccbuild-climbs-1";
  out["file"] = project.file.string();
  if (report.fixed_gantry) {
    out["machine"] = {{"name", project.machine->name},
                      {"origin", project.machine_origin},
                      {"kind", "fixed gantry"}};
  } else {
    const machine::ClimbingMachine& m = *project.climber;
    json units = json::array();
    static const char* roles[] = {"swing", "reach", "wrist", "stroke", "pin"};
    for (const auto& u : m.units) {
      json unit = {{"name", u.name}};
      for (int k = 0; k < 5; ++k) unit[roles[k]] = m.robot->joint_info(u.joints[k]).name;
      units.push_back(unit);
    }
    out["machine"] = {{"name", m.name},
                      {"origin", project.machine_origin},
                      {"kind", "climbing"},
                      {"units", units},
                      // A family fitted on the fly has no URDF file: `ccbuild fit` writes one.
                      {"urdf", project.fit ? json(nullptr) : json(m.robot->urdf().source_file)},
                      {"mass_kg", rounded(m.robot->total_mass_kg())},
                      {"stability_margin_m", rounded(m.stability_margin_m)},
                      {"stroke_end_margin_m", rounded(m.stroke_end_margin_m)},
                      {"stroke_speed_loaded_m_s", rounded(m.stroke_speed_loaded_m_s)},
                      {"lift_per_stroke_m", rounded(m.lift_per_stroke_m)},
                      {"stroke_reset_s", rounded(m.stroke_reset_s)},
                      {"pin_insert_s", rounded(m.pin_insert_s)},
                      {"pin_release_s", rounded(m.pin_release_s)},
                      {"anchor_strength_mpa", rounded(m.anchor_strength_mpa)},
                      {"pipe_embed_s", rounded(m.pipe_embed_s)}};
  }
  const climb::ClimbStatus status = report.status();
  out["status"] = climb::to_string(status.code());
  out["status_reason"] = status.reason();
  json stages = json::array();
  const auto units = project.unit_names();
  for (const auto& s : report.stages.stages) stages.push_back(schedule::stage_json(units, s));
  out["stages"] = stages;
  json climbs = json::array();
  for (const auto& c : report.climbs) climbs.push_back(schedule::climb_plan_json(units, c, true));
  out["climbs"] = climbs;
  out["totals"] = {{"stage_count", report.stages.stages.size()},
                   {"climb_count", report.climbs.size()},
                   {"climb_time_s", rounded(report.climb_time_s())},
                   {"planning_s", rounded(report.planning_s())}};
  return out;
}

std::string climb_report_svg(const schedule::Setup& project, const schedule::ClimbReport& report) {
  // A fixed gantry: the building alone, titled so.
  const machine::ClimbingMachine* m = project.climber.get();
  const floors::Building& b = project.building;
  const floors::LengthUnit unit = b.units;
  const double per = floors::meters_per(unit);
  const std::string u = floors::to_string(unit);
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#8c564b", "#e377c2"};
  // The plan: the platform's outline (its root link's boxes) and every floor's walls.
  const auto zero_poses = m ? m->robot->link_poses(Eigen::Isometry3d::Identity(), m->robot->zero())
                            : std::vector<Eigen::Isometry3d>{};
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> beams;  // corners in plan
  const std::vector<machine::CollisionShape> no_shapes;
  for (const auto& shape : m ? m->robot->link_info(m->robot->root()).collisions : no_shapes) {
    if (shape.kind != machine::CollisionShape::Kind::kBox) continue;
    const Eigen::Vector3d c = (zero_poses[m->robot->root()] * shape.origin).translation();
    const Eigen::Vector2d half = 0.5 * shape.size.head<2>();
    beams.push_back({c.head<2>() - half, c.head<2>() + half});
    lo = lo.cwiseMin(beams.back().first);
    hi = hi.cwiseMax(beams.back().second);
  }
  for (const auto& f : b.floors)
    for (const auto& v : f.plan.vertices) {
      lo = lo.cwiseMin(v.position_m);
      hi = hi.cwiseMax(v.position_m);
    }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  const double left = 70.0, top = 70.0;
  const detail::PlanView view = detail::plan_view(lo, hi, left, top, 860.0);
  const double width = std::max(760.0, left + view.width_px() + 60.0);
  svg::Document doc(width, 2000.0);
  const climb::ClimbStatus status = report.status();
  doc.text(10, 22,
           svg::fit(project.file.string() + ": climbs on " + project.machine->name, width - 20, 15,
                    true),
           15, "id=\"title\" font-weight=\"bold\"");
  doc.text(10, 42,
           svg::fit(report.fixed_gantry
                        ? std::string("a fixed gantry: the building is within its reach, no climbs")
                    : status ? printf_string("%zu stages, %zu climbs, %.1f min of climbing in all",
                                             report.stages.stages.size(), report.climbs.size(),
                                             report.climb_time_s() / 60.0)
                             : "NOT feasible: " + status.to_string(),
                    width - 20, 12),
           12, std::string("id=\"subtitle\"") + (status ? "" : " fill=\"#d62728\""));
  detail::draw_axes(doc, view, unit);
  std::string g = "<g id=\"platform\" fill=\"#eee\" stroke=\"#999\">\n";
  for (const auto& [a, c] : beams)
    g += "<rect x=\"" + svg::px(view.X(a.x())) + "\" y=\"" + svg::px(view.Y(c.y())) +
         "\" width=\"" + svg::px((c.x() - a.x()) * view.scale_px_per_m) + "\" height=\"" +
         svg::px((c.y() - a.y()) * view.scale_px_per_m) + "\"/>\n";
  doc.raw(g + "</g>\n<g id=\"walls\" stroke-linecap=\"round\">\n");
  for (const auto& f : b.floors) {
    const floors::Layer layer = floors::plan_as_layer(f.plan);
    const bool top_floor = f.index + 1 == static_cast<int>(b.floors.size());
    for (const auto& s : layer.segments)
      doc.raw("<line x1=\"" + svg::px(view.X(layer.start_m(s).x())) + "\" y1=\"" +
              svg::px(view.Y(layer.start_m(s).y())) + "\" x2=\"" +
              svg::px(view.X(layer.end_m(s).x())) + "\" y2=\"" +
              svg::px(view.Y(layer.end_m(s).y())) + "\" stroke=\"" + (top_floor ? "#888" : "#ddd") +
              "\" stroke-width=\"" + (top_floor ? "2.5" : "4") + "\"/>\n");
  }
  doc.raw("</g>\n<g id=\"units\">\n");
  for (std::size_t k = 0; m && k < m->units.size(); ++k) {
    const int turret = m->robot->link(m->robot->joint_info(m->units[k].joints[0]).child_link);
    const Eigen::Vector3d mount = zero_poses[turret].translation();
    doc.raw("<circle cx=\"" + svg::px(view.X(mount.x())) + "\" cy=\"" + svg::px(view.Y(mount.y())) +
            "\" r=\"7\" fill=\"#333\"/>\n");
    doc.text(view.X(mount.x()) + 9, view.Y(mount.y()) + 4, m->units[k].name, 12);
  }
  // Each unit's mount (the swing's axis) in plan, at the platform's frame height.
  auto mount_of = [&](int u) {
    const int turret = m->robot->link(m->robot->joint_info(m->units[u].joints[0]).child_link);
    return Eigen::Vector3d(zero_poses[turret].translation());
  };
  doc.raw("</g>\n<g id=\"anchors\">\n");
  for (const auto& s : report.stages.stages)
    for (const auto& a : s.anchors) {
      // The leg's reach in plan: from its mount to the pipe.
      const Eigen::Vector3d mount = mount_of(a.unit);
      doc.raw("<line class=\"leg\" x1=\"" + svg::px(view.X(mount.x())) + "\" y1=\"" +
              svg::px(view.Y(mount.y())) + "\" x2=\"" + svg::px(view.X(a.centre_m.x())) +
              "\" y2=\"" + svg::px(view.Y(a.centre_m.y())) + "\" stroke=\"" + palette[s.index % 7] +
              "\" stroke-width=\"1.5\"/>\n");
      doc.raw("<circle cx=\"" + svg::px(view.X(a.centre_m.x())) + "\" cy=\"" +
              svg::px(view.Y(a.centre_m.y())) + "\" r=\"4\" fill=\"" + palette[s.index % 7] +
              "\"/>\n");
    }
  doc.raw("</g>\n");
  const double plan_bottom = top + view.height_px();
  detail::draw_scale_bar(doc, view, left, plan_bottom + 46.0, unit);

  // The elevation: x against height.
  double z_top = 0.0;
  for (const auto& f : b.floors) z_top = std::max(z_top, f.base_elevation_m + f.height_m);
  for (const auto& s : report.stages.stages) z_top = std::max(z_top, s.platform_z_m + 1.0);
  const double e_top = plan_bottom + 90.0, e_height = 420.0;
  const double z_lo = -1.0;
  auto EX = [&](double x) { return view.X(x); };
  auto EZ = [&](double z) { return e_top + e_height - (z - z_lo) / (z_top - z_lo) * e_height; };
  doc.text(left, e_top - 10,
           "elevation: x (" + u + ") against height (" + u +
               "); floors grey, the platform at each stage, its legs and pipes",
           12, "id=\"elevation-title\"");
  std::string e = "<g id=\"elevation\">\n<rect x=\"" + svg::px(left) + "\" y=\"" + svg::px(e_top) +
                  "\" width=\"" + svg::px(view.width_px()) + "\" height=\"" + svg::px(e_height) +
                  "\" fill=\"none\" stroke=\"#999\"/>\n";
  for (const auto& f : b.floors) {
    double x0 = 1e300, x1 = -1e300;
    for (const auto& v : f.plan.vertices) {
      x0 = std::min(x0, v.position_m.x());
      x1 = std::max(x1, v.position_m.x());
    }
    e += "<rect x=\"" + svg::px(EX(x0)) + "\" y=\"" + svg::px(EZ(f.base_elevation_m + f.height_m)) +
         "\" width=\"" + svg::px(EX(x1) - EX(x0)) + "\" height=\"" +
         svg::px(EZ(f.base_elevation_m) - EZ(f.base_elevation_m + f.height_m)) +
         "\" fill=\"#e6e6e6\" stroke=\"#bbb\"/>\n";
  }
  for (const auto& s : report.stages.stages) {
    const char* c = palette[s.index % 7];
    e += "<line class=\"stage\" x1=\"" + svg::px(EX(lo.x())) + "\" y1=\"" +
         svg::px(EZ(s.platform_z_m)) + "\" x2=\"" + svg::px(EX(hi.x())) + "\" y2=\"" +
         svg::px(EZ(s.platform_z_m)) + "\" stroke=\"" + c + "\" stroke-width=\"3\"/>\n";
    e += "<text x=\"" + svg::px(EX(hi.x()) + 4) + "\" y=\"" + svg::px(EZ(s.platform_z_m) + 4) +
         "\" font-family=\"sans-serif\" font-size=\"11\" fill=\"" + c + "\">" +
         svg::escape("stage " + std::to_string(s.index)) + "</text>\n";
    for (const auto& a : s.anchors) {
      // The leg hanging from the platform to its pin.
      const Eigen::Vector3d mount = mount_of(a.unit);
      e += "<line class=\"leg\" x1=\"" + svg::px(EX(mount.x())) + "\" y1=\"" +
           svg::px(EZ(s.platform_z_m + mount.z())) + "\" x2=\"" + svg::px(EX(a.centre_m.x())) +
           "\" y2=\"" + svg::px(EZ(a.centre_m.z())) + "\" stroke=\"" + c +
           "\" stroke-width=\"1.5\"/>\n";
      e += "<circle cx=\"" + svg::px(EX(a.centre_m.x())) + "\" cy=\"" +
           svg::px(EZ(a.centre_m.z())) + "\" r=\"4\" fill=\"" + c + "\"/>\n";
    }
  }
  const auto z_ticks = svg::ticks(z_lo / per, z_top / per, 6);
  const double z_step = z_ticks.size() > 1 ? z_ticks[1] - z_ticks[0] : 1.0;
  for (double z : z_ticks)
    e += "<text class=\"tick-label\" x=\"" + svg::px(left - 8) + "\" y=\"" +
         svg::px(EZ(z * per) + 4) +
         "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#555\">" +
         svg::tick_label(z, z_step) + "</text>\n";
  doc.raw(e + "</g>\n");
  std::vector<svg::Document::LegendItem> legend{{"band", "#999", "platform"},
                                                {"dot", "#333", "climbing unit"},
                                                {"line", "#888", "walls (top floor dark)"}};
  for (const auto& s : report.stages.stages)
    legend.push_back({"dot", palette[s.index % 7],
                      "stage " + std::to_string(s.index) + ": its pipes and the legs to them"});
  const double legend_top = e_top + e_height + 30.0;
  const double legend_height = doc.legend(10, legend_top, width - 20, legend);
  doc.set_height(legend_top + legend_height + 10.0);
  return doc.str();
}

namespace {
std::string minutes(double s) {
  return s >= 120.0 ? printf_string("%.1f min", s / 60.0) : printf_string("%.1f s", s);
}
}  // namespace

void write_climb_text(std::ostream& out, const schedule::Project& project,
                      const schedule::ClimbReport& report, const std::string& file,
                      const std::optional<int>& floor) {
  const climb::ClimbStatus status = report.status();
  auto L = [&](double value_m) { return project.length(value_m, 2); };
  // Clearances are what a reader checks to the millimetre (or the inch's hundredth).
  auto clearance = [&](double value_m) {
    return floors::fine_length_text(value_m, project.building.units);
  };
  if (report.fixed_gantry) {
    const double top_m = floors::envelope(project.building).top_m;
    out << file << " on " << project.machine_origin << ": a fixed gantry; the building ("
        << L(top_m) << " tall) is within its reach, so no climbs are needed\n";
    return;
  }
  const machine::ClimbingMachine& m = *project.climber;
  out << printf_string(
      "%s on %s: %zu stages, %zu climbs planned%s\n", file.c_str(), project.machine_origin.c_str(),
      report.stages.stages.size(), report.climbs.size(),
      floor ? printf_string(" (those made while floor %d is printed)", *floor).c_str() : "");
  for (const auto& s : report.stages.stages) {
    out << printf_string(
        "stage %d  platform at %s, prints floor %d layer %d to floor %d "
        "layer %d (top %s)\n",
        s.index, L(s.platform_z_m).c_str(), s.first.floor, s.first.layer, s.last.floor,
        s.last.layer, L(s.top_m).c_str());
    std::string pins;
    for (const auto& a : s.anchors)
      pins += printf_string("  %s->%s", m.units[a.unit].name.c_str(), a.id.c_str()) +
              (a.floor < 0 ? std::string(" (foundation)")
                           : printf_string(" (wall %lld, cast after floor %d layer %d, at %s)",
                                           static_cast<long long>(a.wall_id), a.floor, a.layer,
                                           L(a.centre_m.z()).c_str()));
    out << "       " << pins << "\n";
  }
  if (!report.stages.stages.empty())
    out << "  (U1->A1: unit U1 pins into the pipe of anchor A1 while the stage prints; "
           "foundation: into the ground slab; cast after: the layer the pipe is set on; "
           "at: the pipe's height)\n";
  for (const auto& c : report.climbs) {
    out << printf_string(
        "climb %d -> %d: %s, %s of motion, planned in %.3f s, nearest wall "
        "%s\n",
        c.from_stage, c.to_stage,
        c.status ? "feasible" : ("NOT feasible: " + c.status.to_string()).c_str(),
        minutes(c.duration_s).c_str(), c.planning_s,
        std::isfinite(c.min_clearance_m) ? clearance(c.min_clearance_m).c_str() : "-");
    for (const auto& p : c.phases) {
      const std::string who = p.unit >= 0 ? " " + m.units[p.unit].name : "";
      out << printf_string(
          "  %-8s%-4s %10s  %zu waypoints, nearest wall %s%s\n", climb::to_string(p.kind).c_str(),
          who.c_str(), minutes(p.duration_s).c_str(), p.path.size(),
          std::isfinite(p.min_clearance_m) ? clearance(p.min_clearance_m).c_str() : "-",
          p.strokes ? printf_string(", %d strokes", p.strokes).c_str() : "");
    }
  }
  if (floor && report.climbs.empty())
    out << printf_string(
        "no climb is made while floor %d is printed: the platform stays "
        "where it is from its first layer to its last\n",
        *floor);
  if (!status) out << "not feasible: " << status.to_string() << "\n";
  out << printf_string("total: %s of climbing, %.2f s of planning\n",
                       minutes(report.climb_time_s()).c_str(), report.planning_s());
}

nlohmann::ordered_json fit_json(const schedule::Project& project, const climb::FitResult& fit,
                                const std::string& profile, const std::string& urdf) {
  nlohmann::ordered_json out;
  out["building"] = project.file.string();
  out["family"] = fit.profile.gantry.source_file;
  out["profile"] = profile;
  out["urdf"] = urdf;
  const auto& p = fit.platform;
  out["platform"] = {
      {"length_m", p.length_m()},
      {"width_m", p.width_m()},
      {"beams_m",
       {{"x_min", p.x_min_m}, {"x_max", p.x_max_m}, {"y_min", p.y_min_m}, {"y_max", p.y_max_m}}},
      {"gantry_m",
       {{"x_min", p.gantry_x_min_m},
        {"x_max", p.gantry_x_max_m},
        {"y_min", p.gantry_y_min_m},
        {"y_max", p.gantry_y_max_m}}}};
  out["units"] = nlohmann::ordered_json::array();
  for (const auto& u : p.units)
    out["units"].push_back({{"name", u.name},
                            {"beam", machine::to_string(u.beam)},
                            {"x_m", u.position_m.x()},
                            {"y_m", u.position_m.y()}});
  out["mass_kg"] = fit.mass_kg;
  out["least_margin_m"] = fit.least_margin_m;
  out["stages"] = fit.stages;
  out["mounts_considered"] = fit.mounts_considered;
  out["mounts_reaching"] = fit.mounts_reaching;
  out["members_tried"] = fit.members_tried;
  out["optimised"] = fit.optimised;
  return out;
}

void write_fit_text(std::ostream& out, const schedule::Project& project,
                    const climb::FitResult& fit, const std::string& family) {
  const auto& p = fit.platform;
  out << printf_string("%s fitted to %s: %s\n", family.c_str(), project.file.string().c_str(),
                       fit.summary.c_str());
  const floors::LengthUnit unit = project.building.units;
  auto L = [unit](double m) { return floors::length_text(m, unit, 2); };
  auto in = [unit](double m) { return floors::length_in(m, unit); };
  out << printf_string(
      "  platform  beams at x %.2f to %s, y %.2f to %s; the gantry reaches x %.2f to %s, y %.2f "
      "to %s\n",
      in(p.x_min_m), L(p.x_max_m).c_str(), in(p.y_min_m), L(p.y_max_m).c_str(),
      in(p.gantry_x_min_m), L(p.gantry_x_max_m).c_str(), in(p.gantry_y_min_m),
      L(p.gantry_y_max_m).c_str());
  for (const auto& u : p.units)
    out << printf_string("  %-4s      under the %s beam at (%.2f, %.2f) %s\n", u.name.c_str(),
                         machine::to_string(u.beam).c_str(), in(u.position_m.x()),
                         in(u.position_m.y()), floors::to_string(unit).c_str());
  out << printf_string(
      "  checked   %d stages; %d mount positions on the beams, %d reaching solid wall at every "
      "stage; %d unit sets tried\n",
      fit.stages, fit.mounts_considered, fit.mounts_reaching, fit.members_tried);
  out << "  optimised " << fit.optimised << "\n";
}

}  // namespace ccbuild::report
