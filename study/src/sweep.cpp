// The overhead-platform design study (sweep.hpp).

#include "ccbuild/study/sweep.hpp"

#include <sstream>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"

namespace ccbuild::study {
namespace {

char letter(planner::MultiMethod m) {
  switch (m) {
    case planner::MultiMethod::kPathCycling:
      return 'A';
    case planner::MultiMethod::kBufferZonePathCycling:
      return 'B';
    case planner::MultiMethod::kAuxBufferZone:
      return 'C';
    case planner::MultiMethod::kDelay:
      return 'D';
    case planner::MultiMethod::kGlobalPathCycling:
      return 'G';
    case planner::MultiMethod::kAuto:
      return '?';
  }
  return '?';
}

}  // namespace

SweepResult run_sweep(const schedule::Project& project, const SweepGrid& grid,
                      std::ostream& progress) {
  SweepResult result;
  // The layers to plan: each distinct geometry once, weighted by how many layers share it.
  const auto distinct = schedule::distinct_layers(project, grid.floor, grid.layer);
  if (distinct.empty()) throw InputError("", 0, "--floor", "selects no layer with walls");
  const schedule::DistinctLayer* largest = &distinct.front();
  for (const auto& d : distinct)
    if (d.layer.segments.size() > largest->layer.segments.size()) largest = &d;
  int total_layers = 0;
  for (const auto& d : distinct) total_layers += static_cast<int>(d.where.size());

  planner::PlanOptions planning = grid.planning;
  planning.waypoints = false;  // a sweep reports times, never paths
  // Each layer's single-nozzle time, once: the baseline row and the comparison inside
  // every plan, with the same machine and options as plan-layer would use.
  std::vector<double> single_time;
  double single_total_s = 0.0;
  for (const auto& d : distinct) {
    const auto result = schedule::plan_layer(project, d.layer, {1, planning, {}});
    single_time.push_back(result.layer_time_s());
    single_total_s += result.layer_time_s() * static_cast<double>(d.where.size());
  }
  std::vector<SweepRow>& rows = result.rows;
  std::size_t total = 0;
  for (int n : grid.nozzles)
    total += n == 1 ? 1
                    : grid.rail_axes.size() * grid.platform_widths_m.size() *
                          grid.gantry_widths_m.size();
  std::size_t done = 0;
  for (int n : grid.nozzles) {
    if (n == 1) {
      SweepRow row;
      row.methods = "-";
      row.construction_s = row.machine_s = single_total_s;
      row.vertices = static_cast<int>(largest->layer.points.size());
      progress << printf_string("sweep: %zu/%zu  1 nozzle (the baseline)\n", ++done, total);
      rows.push_back(row);
      continue;
    }
    for (const auto& axis : grid.rail_axes) {
      for (double platform : grid.platform_widths_m) {
        for (double gantry : grid.gantry_widths_m) {
          SweepRow row;
          row.nozzles = n;
          row.rail_axis = axis;
          row.platform_m = platform;
          row.gantry_m = gantry;
          ++done;
          progress << printf_string(
              "sweep: %zu/%zu  %d nozzles, %s rails, platform %s, gantry %s, %zu layer "
              "geometr%s\n",
              done, total, n, axis.c_str(), project.length(platform, 2).c_str(),
              project.length(gantry, 2).c_str(), distinct.size(),
              distinct.size() == 1 ? "y" : "ies");
          schedule::LayerPlanRequest request;
          request.nozzles = n;
          planner::MultiNozzleOptions& m = request.multi;
          m.gantry_width_m = gantry;
          m.rail_axis = *machine::rail_axis_named(axis);  // checked when parsed
          m.message_unit = project.building.units;
          m.platform_width_m = platform;
          m.planning = planning;
          m.planning.max_kicks = 300;
          std::pair<int, int> failed_at{0, 0};
          try {
            for (std::size_t k = 0; k < distinct.size(); ++k) {
              const auto& d = distinct[k];
              m.single_nozzle_time_s = single_time[k];
              const auto result = schedule::plan_layer(project, d.layer, request);
              const auto& plan = *result.multi;
              if (&d == largest) {
                for (const auto& stage : plan.stages)
                  row.methods += stage.status ? letter(stage.method) : '-';
                row.vertices = plan.vertex_count;
              }
              if (!plan.status) {
                // Name the lowest failing layer, whatever the order of the geometries.
                const std::pair<int, int> at{d.where.front().floor, d.where.front().layer};
                if (row.status || at < failed_at) {
                  const std::string where =
                      project.is_building
                          ? printf_string(
                                "floor %d layer %d%s: ", at.first, at.second,
                                d.where.size() > 1
                                    ? printf_string(" (and %zu more like it)", d.where.size() - 1)
                                          .c_str()
                                    : "")
                          : std::string();
                  row.status = {plan.status.code(), where + plan.status.reason()};
                  failed_at = at;
                }
                continue;
              }
              row.construction_s += plan.layer_time_s * static_cast<double>(d.where.size());
              row.machine_s += plan.machine_time_s * static_cast<double>(d.where.size());
            }
          } catch (const InputError& e) {
            // This configuration cannot work at all (e.g. the gantries do not fit).
            row.status = {planner::PlanStatus::Code::kNotApplicable, e.first().message};
            row.methods = "-";
          }
          rows.push_back(row);
        }
      }
    }
  }

  result.layer_count = total_layers;
  result.distinct_count = distinct.size();
  return result;
}

std::string sweep_csv(const SweepResult& result) {
  auto opt = [](const std::optional<double>& v) {
    return v ? printf_string("%.6g", *v) : std::string();
  };
  std::ostringstream csv;
  csv << "nozzles,rail_axis,platform_width_m,gantry_width_m,methods,status,construction_time_s,"
         "machine_time_s,vertex_count,status_reason\n";
  for (const auto& r : result.rows)
    csv << r.nozzles << "," << r.rail_axis << "," << opt(r.platform_m) << "," << opt(r.gantry_m)
        << "," << r.methods << "," << planner::to_string(r.status.code()) << ","
        << (r.status ? printf_string("%.6g", r.construction_s) : "") << ","
        << (r.status ? printf_string("%.6g", r.machine_s) : "") << "," << r.vertices << ","
        << csv_field(r.status.reason()) << "\n";
  return csv.str();
}

nlohmann::ordered_json sweep_json(const SweepResult& result, const std::string& file) {
  nlohmann::ordered_json out;
  out["file"] = file;
  out["layer_count"] = result.layer_count;
  out["distinct_layer_count"] = result.distinct_count;
  out["rows"] = nlohmann::ordered_json::array();
  for (const auto& r : result.rows) {
    auto num = [](const std::optional<double>& v) {
      return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
    };
    out["rows"].push_back(
        {{"nozzles", r.nozzles},
         {"rail_axis", r.rail_axis.empty() ? nlohmann::ordered_json(nullptr)
                                           : nlohmann::ordered_json(r.rail_axis)},
         {"platform_width_m", num(r.platform_m)},
         {"gantry_width_m", num(r.gantry_m)},
         {"methods", r.methods},
         {"status", planner::to_string(r.status.code())},
         {"status_reason", r.status.reason()},
         {"construction_time_s", r.status ? num(r.construction_s) : num(std::nullopt)},
         {"machine_time_s", r.status ? num(r.machine_s) : num(std::nullopt)},
         {"vertex_count", r.vertices}});
  }
  return out;
}

}  // namespace ccbuild::study
