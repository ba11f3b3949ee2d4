// ccbuild climb BUILDING: where a climbing machine stands, stage after stage, and every
// climb between stages planned with OMPL against the walls built so far.

#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/report/climb_report.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ClimbOptions {
  std::string file;
  InputOptions input;
  std::optional<int> floor;
  std::uint64_t seed = 1;
  double time_limit_s = 10.0;
  bool json = false;
  std::string svg;
  bool force = false;
};

std::string minutes(double s) {
  return s >= 120.0 ? printf_string("%.1f min", s / 60.0) : printf_string("%.1f s", s);
}

void run_climb(const ClimbOptions& o, int& exit_code) {
  const orchestrator::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);
  if (!o.svg.empty()) outputs.claim_file("--svg", o.svg, o.force);
  climb::ClimbOptions options;
  options.seed = o.seed;
  options.time_limit_s = o.time_limit_s;
  const schedule::ClimbReport report = schedule::plan_climbs(project, o.floor, options);
  const climb::ClimbStatus status = report.status();
  if (!o.svg.empty()) outputs.write(o.svg, report::climb_report_svg(project, report));
  outputs.commit();
  exit_code = status ? kExitOk : kExitNo;
  if (o.json) {
    std::cout << report::climb_report_json(project, report)
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    return;
  }
  auto L = [&](double value_m) { return project.length(value_m, 2); };
  // Clearances are what a reader checks to the millimetre (or the inch's hundredth).
  auto clearance = [&](double value_m) {
    return floors::fine_length_text(value_m, project.building.units);
  };
  if (report.fixed_gantry) {
    const double top_m = floors::envelope(project.building).top_m;
    std::cout << o.file << " on " << project.machine_origin << ": a fixed gantry; the building ("
              << L(top_m) << " tall) is within its reach, so no climbs are needed\n";
    return;
  }
  const machine::ClimbingMachine& m = *project.climber;
  std::cout << printf_string(
      "%s on %s: %zu stages, %zu climbs planned%s\n", o.file.c_str(),
      project.machine_origin.c_str(), report.stages.stages.size(), report.climbs.size(),
      o.floor ? printf_string(" (those made while floor %d is printed)", *o.floor).c_str() : "");
  for (const auto& s : report.stages.stages) {
    std::cout << printf_string(
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
    std::cout << "       " << pins << "\n";
  }
  if (!report.stages.stages.empty())
    std::cout << "  (U1->A1: unit U1 pins into the pipe of anchor A1 while the stage prints; "
                 "foundation: into the ground slab; cast after: the layer the pipe is set on; "
                 "at: the pipe's height)\n";
  for (const auto& c : report.climbs) {
    std::cout << printf_string(
        "climb %d -> %d: %s, %s of motion, planned in %.3f s, nearest wall "
        "%s\n",
        c.from_stage, c.to_stage,
        c.status ? "feasible" : ("NOT feasible: " + c.status.to_string()).c_str(),
        minutes(c.duration_s).c_str(), c.planning_s,
        std::isfinite(c.min_clearance_m) ? clearance(c.min_clearance_m).c_str() : "-");
    for (const auto& p : c.phases) {
      const std::string who = p.unit >= 0 ? " " + m.units[p.unit].name : "";
      std::cout << printf_string(
          "  %-8s%-4s %10s  %zu waypoints, nearest wall %s%s\n", climb::to_string(p.kind).c_str(),
          who.c_str(), minutes(p.duration_s).c_str(), p.path.size(),
          std::isfinite(p.min_clearance_m) ? clearance(p.min_clearance_m).c_str() : "-",
          p.strokes ? printf_string(", %d strokes", p.strokes).c_str() : "");
    }
  }
  if (o.floor && report.climbs.empty())
    std::cout << printf_string(
        "no climb is made while floor %d is printed: the platform stays "
        "where it is from its first layer to its last\n",
        *o.floor);
  if (!status) std::cout << "not feasible: " << status.to_string() << "\n";
  std::cout << printf_string("total: %s of climbing, %.2f s of planning\n",
                             minutes(report.climb_time_s()).c_str(), report.planning_s());
}

}  // namespace

void add_climb_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ClimbOptions>();
  CLI::App* command = app.add_subcommand(
      "climb",
      "Plan how a climbing machine climbs the building it prints (paper 000 section 7): the "
      "stages the platform stands at (as high as its legs allow, the next layer still in the "
      "nozzle's reach), the pipes each stage's pins go into (as low as the legs allow, so they "
      "cure while printing goes on), and every climb: park the gantry, then unit by unit "
      "balance (the gantry as counterweight), release, transit and insert the pin, then lift. "
      "Each motion is planned by OMPL against the walls built so far (FCL), within the URDF's "
      "limits and statically stable, and re-checked at a finer resolution.\n"
      "On a fixed gantry (a profile without `climbing:`) it says whether the building is within "
      "its reach: then no climbs are needed; otherwise exit code 2 says what is out of reach.\n"
      "Exit code 1 when a stage or a climb is not feasible (the reason is printed).\n"
      "Examples:\n"
      "  ccbuild climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml\n"
      "  ccbuild climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml "
      "--floor 3 --json\n"
      "  ccbuild climb building.yaml --svg climbs.svg");
  command->add_option("BUILDING", o->file, "Building file")->required();
  command
      ->add_option("--floor", o->floor,
                   "Only the climbs made while this floor is printed (those after a stage whose "
                   "last layer is on it); every stage is still listed")
      ->check(integer_in(0, 100000));
  command->add_option("--seed", o->seed, "Random seed: the same seed gives the same motions")
      ->check(unsigned_integer())
      ->capture_default_str();
  command->add_option("--time-limit", o->time_limit_s, "Planning time for each climb, s")
      ->check(number_in(Range::above(0.0, 3600.0), "s"))
      ->capture_default_str();
  command->add_flag("--json", o->json, "Print one JSON object (errors too)");
  command->add_option("--svg", o->svg, "Also draw the platform and pipes in plan and elevation")
      ->check(output_path());
  command->add_flag("--force", o->force,
                    "Overwrite an existing --svg file (never one this run reads)");
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_climb(*o, exit_code); });
}

}  // namespace ccbuild::cli
