// ccbuild sweep FILE: the overhead-platform design study of paper 002 §5 (Tables 1 and
// 2): over numbers of nozzles, platform widths, gantry widths and rail orientations, which
// method found a collision-free plan, total construction and machine time, vertices.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/orchestrator/project.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct SweepOptions {
  std::string file;
  InputOptions input;
  std::vector<int> nozzles{2, 3};
  std::vector<std::string> platform_widths{"40ft", "60ft"};
  std::vector<std::string> gantry_widths{"2.5ft", "5ft", "7.5ft", "10ft"};
  std::vector<std::string> rail_axes{"x", "y"};
  std::optional<int> floor;
  std::optional<int> layer;
  std::string objective = "time";
  std::uint64_t seed = 1;
  double time_limit_s = 30.0;
  std::string csv;
  bool json = false;
  bool force = false;
};

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

struct Row {
  int nozzles = 1;
  std::string rail_axis;                       // empty for the one-nozzle baseline
  std::optional<double> platform_m, gantry_m;  // unset for the baseline
  std::string methods;  // one letter per platform stage of the largest layer, '-' for none
  planner::PlanStatus status;
  double construction_s = 0.0, machine_s = 0.0;
  int vertices = 0;
};

void run_sweep(const SweepOptions& o, int& exit_code) {
  const orchestrator::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);
  if (!o.csv.empty()) outputs.claim_file("--csv", o.csv, o.force);
  const floors::Building& b = project.building;
  const floors::LengthUnit unit = b.units;
  std::vector<double> platforms, gantries;
  for (const auto& t : o.platform_widths)
    platforms.push_back(length_flag(t, "--platform-width", unit));
  for (const auto& t : o.gantry_widths) gantries.push_back(length_flag(t, "--gantry-width", unit));

  // The layers to plan: each distinct geometry once, weighted by how many layers share it.
  const auto distinct = orchestrator::distinct_layers(project, o.floor, o.layer);
  if (distinct.empty()) throw InputError("", 0, "--floor", "selects no layer with walls");
  const orchestrator::DistinctLayer* largest = &distinct.front();
  for (const auto& d : distinct)
    if (d.layer.segments.size() > largest->layer.segments.size()) largest = &d;
  int total_layers = 0;
  for (const auto& d : distinct) total_layers += static_cast<int>(d.where.size());

  planner::PlanOptions planning;
  planning.objective = *planner::parse_objective(o.objective);
  planning.seed = o.seed;
  planning.time_limit_s = o.time_limit_s;
  planning.waypoints = false;  // a sweep reports times, never paths
  // Each layer's single-nozzle time, once: the baseline row and the comparison inside
  // every plan, with the same machine and options as plan-layer would use.
  std::vector<double> single_time;
  double single_total_s = 0.0;
  for (const auto& d : distinct) {
    const auto result = orchestrator::plan_layer(project, d.layer, {1, planning, {}});
    single_time.push_back(result.layer_time_s());
    single_total_s += result.layer_time_s() * static_cast<double>(d.where.size());
  }
  std::vector<Row> rows;
  std::size_t total = 0;
  for (int n : o.nozzles)
    total += n == 1 ? 1 : o.rail_axes.size() * platforms.size() * gantries.size();
  std::size_t done = 0;
  for (int n : o.nozzles) {
    if (n == 1) {
      Row row;
      row.methods = "-";
      row.construction_s = row.machine_s = single_total_s;
      row.vertices = static_cast<int>(largest->layer.points.size());
      std::cerr << printf_string("sweep: %zu/%zu  1 nozzle (the baseline)\n", ++done, total);
      rows.push_back(row);
      continue;
    }
    for (const auto& axis : o.rail_axes) {
      for (double platform : platforms) {
        for (double gantry : gantries) {
          Row row;
          row.nozzles = n;
          row.rail_axis = axis;
          row.platform_m = platform;
          row.gantry_m = gantry;
          ++done;
          std::cerr << printf_string(
              "sweep: %zu/%zu  %d nozzles, %s rails, platform %s, gantry %s, %zu layer "
              "geometr%s\n",
              done, total, n, axis.c_str(), project.length(platform, 2).c_str(),
              project.length(gantry, 2).c_str(), distinct.size(),
              distinct.size() == 1 ? "y" : "ies");
          orchestrator::LayerPlanRequest request;
          request.nozzles = n;
          planner::MultiNozzleOptions& m = request.multi;
          m.gantry_width_m = gantry;
          m.rail_axis = *machine::rail_axis_named(axis);  // checked when parsed
          m.message_unit = unit;
          m.platform_width_m = platform;
          m.planning = planning;
          m.planning.max_kicks = 300;
          std::pair<int, int> failed_at{0, 0};
          try {
            for (std::size_t k = 0; k < distinct.size(); ++k) {
              const auto& d = distinct[k];
              m.single_nozzle_time_s = single_time[k];
              const auto result = orchestrator::plan_layer(project, d.layer, request);
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

  const double per_unit = floors::meters_per(unit);
  const std::string u = floors::to_string(unit);
  auto opt = [](const std::optional<double>& v) {
    return v ? printf_string("%.6g", *v) : std::string();
  };
  std::ostringstream csv;
  csv << "nozzles,rail_axis,platform_width_m,gantry_width_m,methods,status,construction_time_s,"
         "machine_time_s,vertex_count,status_reason\n";
  for (const auto& r : rows)
    csv << r.nozzles << "," << r.rail_axis << "," << opt(r.platform_m) << "," << opt(r.gantry_m)
        << "," << r.methods << "," << planner::to_string(r.status.code()) << ","
        << (r.status ? printf_string("%.6g", r.construction_s) : "") << ","
        << (r.status ? printf_string("%.6g", r.machine_s) : "") << "," << r.vertices << ","
        << csv_field(r.status.reason()) << "\n";
  if (!o.csv.empty()) outputs.write(o.csv, csv.str());
  outputs.commit();

  const bool any =
      std::any_of(rows.begin(), rows.end(), [](const Row& r) { return bool(r.status); });
  if (o.json) {
    nlohmann::ordered_json out;
    out["file"] = o.file;
    out["layer_count"] = total_layers;
    out["distinct_layer_count"] = distinct.size();
    out["rows"] = nlohmann::ordered_json::array();
    for (const auto& r : rows) {
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
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::cout << printf_string(
        "%s: %d layer(s), %zu distinct; times summed over all of them; methods per platform stage "
        "of the largest layer (A path cycling, B buffer zone path cycling, C auxiliary buffer "
        "zone, D delay, - none)\n",
        o.file.c_str(), total_layers, distinct.size());
    std::cout << printf_string("  %-13s %s\n", "machine", project.machine_origin.c_str());
    std::cout << printf_string("%-7s  %-5s  %10s  %10s  %-8s  %16s  %11s  %8s\n", "nozzles",
                               "rails", ("platform " + u).c_str(), ("gantry " + u).c_str(),
                               "methods", "construction min", "machine min", "vertices");
    auto width = [&](const std::optional<double>& v) {
      return v ? printf_string("%.1f", *v / per_unit) : std::string("-");
    };
    for (const auto& r : rows) {
      std::cout << printf_string(
          "%-7d  %-5s  %10s  %10s  %-8s  %16s  %11s  %8d\n", r.nozzles,
          r.rail_axis.empty() ? "-" : r.rail_axis.c_str(), width(r.platform_m).c_str(),
          width(r.gantry_m).c_str(), r.methods.c_str(),
          r.status ? printf_string("%.1f", r.construction_s / 60).c_str() : "none",
          r.status ? printf_string("%.1f", r.machine_s / 60).c_str() : "none", r.vertices);
    }
    std::cout << "  (rails: the axis the gantries run along; platform, gantry: their widths across "
                 "the rails; methods: the letters above, one per platform stage; construction: the "
                 "layers' times summed, the nozzles working together; machine: the nozzles' busy "
                 "times summed; vertices: "
                 "the largest layer's, after splitting walls at the platform's sections)\n";
    for (const auto& r : rows)
      if (!r.status)
        std::cout << printf_string("  %d nozzles, %s, platform %s, gantry %s: %s\n", r.nozzles,
                                   r.rail_axis.c_str(), width(r.platform_m).c_str(),
                                   width(r.gantry_m).c_str(), r.status.to_string().c_str());
  }
  if (!any) std::cerr << "ccbuild: no configuration has a collision-free plan\n";
  exit_code = any ? kExitOk : kExitNo;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Design study of an overhead platform carrying several nozzles (as in paper 002, Tables 1 "
      "and 2): for "
      "every combination of nozzle count, rail orientation, platform width and gantry width, plan "
      "the layers "
      "with the automatic method and report which method succeeded in each platform stage, the "
      "total "
      "construction time (all layers), the total machine time (busy time of all nozzles) and the "
      "vertices "
      "after splitting. Progress goes to stderr. --nozzles 1 adds the one-nozzle baseline.\n"
      "Exit code 1 when no configuration has a collision-free plan.\n"
      "Lengths take a unit (40ft, 12m); bare numbers are in the file's unit.\n"
      "Examples:\n"
      "  ccbuild sweep config/buildings/apartment.yaml --floor 4 --csv study.csv\n"
      "  ccbuild sweep plan.txt --units ft --nozzles 2,3 --platform-width 40,60 --gantry-width "
      "2.5,5,7.5,10");
  command->add_option("FILE", o->file, "Building file or floor plan")->required();
  command->add_option("--nozzles", o->nozzles, "Nozzle counts; 1 adds the one-nozzle baseline row")
      ->delimiter(',')
      ->check(integer_in(1, planner::kMaxNozzles))
      ->capture_default_str();
  command->add_option("--platform-width", o->platform_widths, "Platform widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--gantry-width", o->gantry_widths, "Gantry widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--rail-axis", o->rail_axes, "Rail orientations: x, y")
      ->delimiter(',')
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  command->add_option("--floor", o->floor, "Only this floor of a building")
      ->check(integer_in(0, 100000));
  command->add_option("--layer", o->layer, "Only this layer (of each floor selected)")
      ->check(integer_in(0, 10000000));
  command
      ->add_option("--objective", o->objective,
                   "What each section's tour minimises: time or distance")
      ->check(CLI::IsMember({"time", "distance"}))
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Random seed")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--time-limit", o->time_limit_s,
                   "Bound on each layer's planning in each configuration, s")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  command->add_option("--csv", o->csv, "Also write the table as CSV (SI units)")
      ->check(output_path());
  command->add_flag("--json", o->json, "Print the table as JSON");
  command->add_flag("--force", o->force, "Overwrite an existing --csv file");
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_sweep(*o, exit_code); });
}

}  // namespace ccbuild::cli
