// ccbuild plan-layer PLAN: the tool path of one layer for one nozzle.

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/orchestrator/layer_report.hpp"
#include "ccbuild/orchestrator/multi_report.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct PlanLayerOptions {
  std::string file;
  PlanInputOptions plan;
  int floor = 0;
  std::optional<int> layer;
  std::string metric = "euclidean";
  std::string objective = "distance";
  std::string algorithm = "cc-tsp";
  std::string bound = "connected";
  std::optional<std::int64_t> start_vertex;
  std::optional<std::int64_t> first_wall;
  double time_limit_s = 30.0;
  std::uint64_t seed = 1;
  std::optional<long> max_kicks;
  std::string machine;
  bool json = false;
  std::string svg;
  bool force = false;
  // Several nozzles.
  int nozzles = 1;
  std::string gantry_width;
  std::string rail_axis = "x";
  std::string method = "auto";
  std::string platform_width;
};

// What the JSON answer was computed from.
nlohmann::ordered_json annotated(nlohmann::ordered_json out, const PlanLayerOptions& o,
                                 const std::string& where) {
  out["file"] = o.file;
  out["layer"] = where;
  out["seed"] = o.seed;
  return out;
}

// A length flag: "5ft", "1.5m", or a bare number in the input's own unit.
double length_option(const std::string& text, const char* flag, floors::LengthUnit unit) {
  const auto value = floors::parse_length_m(text, unit);
  if (!value)
    throw InputError("", 0, flag, "expected a length such as 1.5, 1.5m or 5ft, got '" + text + "'");
  return *value;
}

void print_multi(const PlanLayerOptions& o, const std::string& where, const floors::Layer& layer,
                 const planner::MultiNozzlePlan& plan, const planner::MultiNozzleOptions& options) {
  std::cout << printf_string(
      "%s, %s: %zu walls, %d nozzles on %s rails, gantries %.3f m wide%s\n", o.file.c_str(),
      where.c_str(), layer.segments.size(), options.nozzles, o.rail_axis.c_str(),
      options.gantry_width_m,
      options.platform_width_m
          ? printf_string(", platform %.3f m", *options.platform_width_m).c_str()
          : "");
  if (plan.collision_free) {
    std::cout << printf_string("  %-13s %.2f s; one nozzle %.2f s: %.1f%% saved\n", "layer time",
                               plan.layer_time_s, plan.single_nozzle_time_s,
                               100.0 * (1.0 - plan.layer_time_s / plan.single_nozzle_time_s));
    std::cout << printf_string("  %-13s %.2f s (busy time summed over nozzles)\n", "machine time",
                               plan.machine_time_s);
    std::cout << printf_string("  %-13s %.3f m (gantry width %.3f m): collision-free\n", "min gap",
                               plan.min_gap_m, options.gantry_width_m);
    if (plan.platform_travel_s > 0)
      std::cout << printf_string("  %-13s %.2f s\n", "platform", plan.platform_travel_s);
  } else {
    std::cout << printf_string("  %-13s none found: %s\n", "plan", plan.failure.c_str());
  }
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const auto& stage = plan.stages[k];
    if (plan.stages.size() > 1)
      std::cout << printf_string("  stage %zu       %s %.3f-%.3f m, %.2f s\n", k + 1,
                                 o.rail_axis.c_str(), stage.from_m, stage.to_m, stage.time_s);
    std::cout << printf_string("  %-13s %s\n", "method",
                               stage.nozzles.empty() ? "none" : stage.method_detail.c_str());
    for (const auto& attempt : stage.attempts)
      std::cout << printf_string("  %-13s %s\n", "", attempt.c_str());
    for (const auto& n : stage.nozzles) {
      std::cout << printf_string(
          "  nozzle %-6d section %s %.3f-%.3f m, %zu walls, start offset %d, busy %.2f s, waits "
          "%.2f s\n",
          n.nozzle + 1, o.rail_axis.c_str(), n.section_from_m, n.section_to_m, n.sequence.size(),
          n.start_offset, n.busy_s, n.wait_s);
      if (!n.sequence.empty())
        std::cout << printf_string("  %-13s %s\n", "",
                                   orchestrator::signed_sequence(n.layer, n.sequence).c_str());
    }
  }
}

machine::MachineModel load_machine_for(const PlanLayerOptions& options, const LoadedInput& input,
                                       std::string& description) {
  fs::path profile;
  if (!options.machine.empty()) {
    profile = options.machine;
  } else if (input.is_building) {
    profile = input.building.machine_profile;
  } else {
    profile = fs::path(CCBUILD_CONFIG_DIR) / "machines" / "cc-gantry.yaml";
    std::error_code ec;
    if (!fs::exists(profile, ec)) {
      description = "built-in defaults (no --machine given)";
      return machine::MachineModel::defaults();
    }
  }
  machine::MachineModel m = machine::load_machine(profile);
  description = m.name + " (" + profile.string() + ")";
  return m;
}

void run_plan_layer(const PlanLayerOptions& o, int& exit_code) {
  const auto algorithm = planner::parse_algorithm(o.algorithm);
  const auto metric = planner::parse_metric(o.metric);
  const auto objective = planner::parse_objective(o.objective);
  if (!o.svg.empty()) check_output_path(o.svg, o.force, {o.file});
  const LoadedInput input = load_input(o.file, o.plan);
  const floors::Building& b = input.building;
  if (o.floor < 0 || o.floor >= static_cast<int>(b.floors.size()))
    throw InputError("", 0, "--floor",
                     printf_string("no floor %d; %s has floors 0 to %zu", o.floor, o.file.c_str(),
                                   b.floors.size() - 1));
  const floors::Floor& floor = b.floors[o.floor];
  floors::Layer layer;
  std::string where;
  if (input.is_building || o.layer) {
    const auto layers = floors::slice_floor(floor, b.layer_height_m);
    const int k = o.layer.value_or(0);
    if (k < 0 || k >= static_cast<int>(layers.size()))
      throw InputError("", 0, "--layer",
                       printf_string("no layer %d; floor %d has layers 0 to %zu", k, o.floor,
                                     layers.size() - 1));
    layer = layers[k];
    where = printf_string("floor %d layer %d", o.floor, k);
  } else {
    layer = floors::plan_as_layer(floor.plan);
    where = "all walls whole";
  }

  std::string machine_description;
  const machine::MachineModel machine = load_machine_for(o, input, machine_description);

  planner::PlanOptions options;
  options.algorithm = *algorithm;
  options.metric = *metric;
  options.objective = *objective;
  options.time_limit_s = o.time_limit_s;
  options.seed = o.seed;
  options.max_kicks = o.max_kicks;
  options.bound = *planner::parse_bound(o.bound);  // CLI11 checked the name
  if (o.first_wall && !o.start_vertex)
    throw InputError("", 0, "--first-wall", "needs --start-vertex");
  if (o.start_vertex) {
    const floors::Vertex* v = floor.plan.find_vertex(*o.start_vertex);
    if (v == nullptr)
      throw InputError("", 0, "--start-vertex",
                       printf_string("vertex %lld is not in the plan", (long long)*o.start_vertex));
    options.path = planner::PathSpec::open_from(v->position_m);
    if (o.first_wall) {
      const std::int64_t id = std::llabs(*o.first_wall);
      const bool reversed = *o.first_wall < 0;
      // A wall cut by an opening starts with its first piece (its last when reversed).
      int chosen = -1;
      for (int s = 0; s < static_cast<int>(layer.segments.size()); ++s) {
        const auto& seg = layer.segments[s];
        if (seg.wall_id != id) continue;
        if (chosen < 0 || reversed) chosen = s;
        if (!reversed) break;
      }
      if (chosen < 0)
        throw InputError(
            "", 0, "--first-wall",
            printf_string("wall %lld is not in this layer (%s)", (long long)id, where.c_str()));
      options.path.first = planner::Step{chosen, reversed};
    }
  }

  if (o.nozzles >= 2) {
    if (o.start_vertex)
      throw InputError("", 0, "--start-vertex", "multi-nozzle paths are closed tours");
    if (o.gantry_width.empty())
      throw InputError("", 0, "--gantry-width", "is required with --nozzles");
    planner::MultiNozzleOptions multi;
    multi.nozzles = o.nozzles;
    multi.gantry_width_m = length_option(o.gantry_width, "--gantry-width", b.units);
    multi.rail_axis = o.rail_axis == "y" ? planner::RailAxis::kY : planner::RailAxis::kX;
    multi.method = *planner::parse_multi_method(o.method);
    if (!o.platform_width.empty())
      multi.platform_width_m = length_option(o.platform_width, "--platform-width", b.units);
    multi.planning = options;
    const planner::MultiNozzlePlan plan = planner::plan_layer_multi(layer, machine, multi);
    if (!o.svg.empty())
      write_file_atomically(o.svg, orchestrator::multi_plan_svg(plan, multi, o.file + ", " + where),
                            o.force, {o.file});
    if (o.json) {
      std::cout << annotated(orchestrator::multi_plan_json(plan, multi), o, where).dump(2) << "\n";
    } else {
      print_multi(o, where, layer, plan, multi);
    }
    exit_code = plan.collision_free ? kExitOk : kExitNo;
    return;
  }
  if (o.nozzles < 1) throw InputError("", 0, "--nozzles", "must be at least 1");

  const planner::LayerPlan plan = planner::plan_layer(layer, machine, options);
  const auto& e = plan.evaluation;
  if (!o.svg.empty())
    write_file_atomically(o.svg, orchestrator::layer_plan_svg(layer, plan, o.file + ", " + where),
                          o.force, {o.file});

  if (o.json) {
    auto out = annotated(orchestrator::layer_plan_json(layer, plan), o, where);
    out["idle_limit_s"] = machine.nozzle_idle_limit_s;
    std::cout << out.dump(2) << "\n";
  } else {
    const double unit = floors::meters_per(b.units);
    auto length = [&](double m) {
      std::string text = printf_string("%.3f m", m);
      if (b.units == floors::LengthUnit::kFoot) text += printf_string(" (%.3f ft)", m / unit);
      return text;
    };
    std::cout << printf_string("%s, %s: %zu walls\n", o.file.c_str(), where.c_str(),
                               layer.segments.size());
    std::cout << printf_string(
        "  %-13s %s, %s metric, %s objective, %s\n", "algorithm", o.algorithm.c_str(),
        o.metric.c_str(), o.objective.c_str(),
        plan.path.closed ? "closed tour" : "open path from the start vertex");
    std::cout << printf_string("  %-13s %s\n", "machine", machine_description.c_str());
    std::cout << printf_string("  %-13s %s, %.2f s (%d lifts, %.1f turns of the nozzle)\n",
                               "airtime", length(e.airtime_distance_m).c_str(), e.airtime_s,
                               e.lift_count, e.total_rotation_rad / (2 * M_PI));
    std::cout << printf_string("  %-13s %.2f s\n", "deposition", e.deposition_s);
    std::cout << printf_string("  %-13s %.2f s\n", "layer time", e.layer_time_s);
    const double gap = plan.gap();
    std::cout << printf_string(
        "  %-13s %s (%s), gap %s\n", "lower bound", length(plan.lower_bound_m).c_str(),
        plan.lower_bound_source.c_str(),
        std::isnan(gap) ? "n/a (bound is 0)"
        : plan.objective == planner::Objective::kTime
            // The bound is on distance; the fastest tour may travel further to avoid lifts.
            ? printf_string("%.2f%% in distance (time objective)", 100.0 * gap).c_str()
            : printf_string("%.2f%%", 100.0 * gap).c_str());
    std::cout << printf_string(
        "  %-13s %.2f s (limit %.0f s)%s\n", "longest idle", e.max_idle_s,
        machine.nozzle_idle_limit_s,
        e.idle_limit_violations
            ? printf_string(": %d move(s) over the limit", e.idle_limit_violations).c_str()
            : "");
    std::cout << printf_string(
        "  %-13s %.3f s, %s%s\n", "solve", plan.solve_s, planner::to_string(plan.stop).c_str(),
        plan.kicks ? printf_string(" after %ld kicks", plan.kicks).c_str() : "");
    std::cout << printf_string("  %-13s %s\n", "sequence",
                               orchestrator::signed_sequence(layer, plan.sequence).c_str());
    if (!o.svg.empty()) std::cout << printf_string("  %-13s %s\n", "drawing", o.svg.c_str());
  }
  if (e.idle_limit_violations > 0)
    std::cerr << printf_string(
        "ccbuild: warning: %d air move(s) exceed the nozzle idle limit of %.0f s\n",
        e.idle_limit_violations, machine.nozzle_idle_limit_s);
  exit_code = kExitOk;
}

}  // namespace

void add_plan_layer_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<PlanLayerOptions>();
  CLI::App* command = app.add_subcommand(
      "plan-layer",
      "Plan the tool path of one layer for one nozzle (CC-TSP: each wall is two nodes joined by a "
      "fixed edge, solved by a chained local search seeded with an Euler walk).\n"
      "Prints airtime (distance and time), deposition and layer time, a lower bound on airtime "
      "distance with the gap to it, and the sequence as signed wall ids (-5: wall 5 from its end "
      "vertex to its start vertex; 5:2: the second piece of a wall cut by an opening).\n"
      "Examples:\n"
      "  ccbuild plan-layer tests/data/plans/paper_example1.txt --start-vertex 1 --first-wall 1\n"
      "  ccbuild plan-layer config/buildings/house.yaml --floor 1 --layer 12 --objective time "
      "--svg l12.svg\n"
      "  ccbuild plan-layer plan.yaml --algorithm nearest --metric rectilinear --json\n"
      "  ccbuild plan-layer config/buildings/apartment.yaml --layer 10 --nozzles 2 --gantry-width "
      "5ft --svg two.svg\n"
      "Exit code 1 when no collision-free multi-nozzle plan was found (the reasons are printed).");
  command->add_option("PLAN", o->file, "Floor plan (YAML, JSON, table text) or building file")
      ->required();
  command->add_option("--floor", o->floor, "Floor of a building (0 = ground)")
      ->capture_default_str();
  command->add_option(
      "--layer", o->layer,
      "Layer within the floor (default 0); for a plan file, slices it with --floor-height and "
      "--layer-height instead of planning whole walls");
  command
      ->add_option("--metric", o->metric,
                   "Air moves: euclidean (straight) or rectilinear (x, then y)")
      ->check(CLI::IsMember({"euclidean", "rectilinear"}))
      ->capture_default_str();
  command
      ->add_option("--objective", o->objective,
                   "distance: airtime distance only; time: travel, rotation with the stopper, "
                   "delays and lifts")
      ->check(CLI::IsMember({"distance", "time"}))
      ->capture_default_str();
  command
      ->add_option(
          "--algorithm", o->algorithm,
          "cc-tsp; nearest (greedy nearest wall end); original (file order); exact (small layers)")
      ->check(CLI::IsMember({"cc-tsp", "nearest", "original", "exact"}))
      ->capture_default_str();
  command
      ->add_option("--bound", o->bound,
                   "Lower bound: connected (an LP with connectivity cuts, certified on every "
                   "pair of points) or matching (the odd points' matching alone: faster, "
                   "weaker)")
      ->check(CLI::IsMember({"connected", "matching"}))
      ->capture_default_str();
  command->add_option("--start-vertex", o->start_vertex,
                      "Plan an open path starting at this plan vertex (default: a closed tour)");
  command->add_option(
      "--first-wall", o->first_wall,
      "With --start-vertex: deposit this wall first (negative: from its end vertex)");
  command->add_option("--time-limit", o->time_limit_s, "Bound on the whole run, set-up included, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Random seed: the same seed and inputs give the same plan")
      ->capture_default_str();
  command
      ->add_option("--max-kicks", o->max_kicks,
                   "Kicks of the chained search (default: from the layer size)")
      ->check(CLI::NonNegativeNumber);
  command->add_option(
      "--machine", o->machine,
      "Machine profile (default: the building's, or config/machines/cc-gantry.yaml)");
  command->add_flag("--json", o->json, "Print one JSON object instead of text");
  command->add_option("--svg", o->svg, "Also draw the plan into this SVG file");
  command->add_flag("--force", o->force, "Overwrite an existing --svg file");
  command
      ->add_option(
          "--nozzles", o->nozzles,
          "Nozzles on common rails (2 or more: sections, collision-free paths, x/t checks)")
      ->capture_default_str();
  command->add_option("--gantry-width", o->gantry_width,
                      "With --nozzles: closest two gantry centres may come, e.g. 1.5m or 5ft "
                      "(bare: the file's unit)");
  command
      ->add_option("--rail-axis", o->rail_axis, "With --nozzles: the axis the gantries ride along")
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  command
      ->add_option(
          "--method", o->method,
          "With --nozzles: auto (path cycling, buffer zone path cycling, auxiliary buffer zone, "
          "then "
          "waits), path-cycling, global-path-cycling, bz-path-cycling, aux-buffer-zone, delay")
      ->check(CLI::IsMember({"auto", "path-cycling", "global-path-cycling", "bz-path-cycling",
                             "aux-buffer-zone", "delay"}))
      ->capture_default_str();
  command->add_option(
      "--platform-width", o->platform_width,
      "With --nozzles: an overhead platform this long along the rails; longer layouts are built in "
      "platform-wide stages");
  add_plan_input_options(*command, o->plan);
  command->callback([o, &exit_code] { run_plan_layer(*o, exit_code); });
}

}  // namespace ccbuild::cli
