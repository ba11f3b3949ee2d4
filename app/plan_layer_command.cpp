// ccbuild plan-layer PLAN: the tool path of one layer for one nozzle.

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/planner/search_reporter.hpp"
#include "ccbuild/report/layer_report.hpp"
#include "ccbuild/report/multi_report.hpp"
#include "ccbuild/report/plan_text.hpp"
#include "ccbuild/schedule/project.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct PlanLayerOptions {
  std::string file;
  InputOptions input;
  int floor = 0;
  std::optional<int> layer;
  std::string metric = "euclidean";
  std::string objective = "distance";
  std::string algorithm = "cc-tsp";
  std::string bound = "connected";
  std::optional<int> bound_rounds;
  std::string bound_certificate;
  std::optional<std::int64_t> start_vertex;
  std::optional<std::int64_t> first_wall;
  double time_limit_s = 30.0;
  std::uint64_t seed = 1;
  std::optional<long> max_kicks;
  std::optional<long> polish_kicks;
  bool anytime = false;  ///< --time-limit was given: search until it
  std::string neighbourhood = "lk";
  bool json = false;
  std::string svg;
  bool force = false;
  // Several nozzles.
  int nozzles = 1;
  std::string gantry_width;
  std::string rail_axis = "x";
  std::string method = "auto";
  std::string platform_width;
  bool quiet = false;
};

report::PlanTextOptions text_options(const PlanLayerOptions& o) {
  report::PlanTextOptions t;
  t.rail_axis = o.rail_axis;
  t.algorithm = o.algorithm;
  t.metric = o.metric;
  t.objective = o.objective;
  t.connected_asked = o.bound_rounds || !o.bound_certificate.empty();
  t.bound_certificate = o.bound_certificate;
  t.anytime = o.anytime;
  t.drawing = o.svg;
  return t;
}

// The layer step a --first-wall names: a wall cut by an opening starts with its first
// piece (its last when reversed).
planner::Step first_step(const floors::Layer& layer, std::int64_t signed_id,
                         const std::string& where) {
  const std::int64_t id = signed_id < 0 ? -signed_id : signed_id;
  const bool reversed = signed_id < 0;
  int chosen = -1;
  for (int s = 0; s < static_cast<int>(layer.segments.size()); ++s) {
    if (layer.segments[s].wall_id != id) continue;
    if (chosen < 0 || reversed) chosen = s;
    if (!reversed) break;
  }
  if (chosen < 0)
    throw InputError("", 0, "--first-wall",
                     printf_string("wall %lld is not in this layer (%s)",
                                   static_cast<long long>(id), where.c_str()));
  return planner::Step{chosen, reversed};
}

void run_plan_layer(const PlanLayerOptions& o, int& exit_code) {
  const schedule::Project project = open_input(o.file, o.input);
  // Refuse a drawing path that would replace any file this run reads, before planning.
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);
  if (!o.svg.empty()) outputs.claim_file("--svg", o.svg, o.force);
  if (!o.bound_certificate.empty())
    outputs.claim_file("--bound-certificate", o.bound_certificate, o.force);
  const floors::Building& b = project.building;
  const floors::Layer layer = schedule::layer_of(project, o.floor, o.layer);
  if (layer.segments.empty()) {
    const std::string where = printf_string("floor %d layer %d", o.floor, layer.index);
    if (o.layer)
      throw InputError("", 0, "layer",
                       where + " has no walls to plan (every wall is inside an opening there)");
    throw InputError(o.file, 0, "",
                     where +
                         " (the first layer; --layer names another) has no walls to plan "
                         "(every wall is inside an opening there)");
  }
  report::ReportContext context;
  context.file = o.file;
  context.floor = o.floor;
  context.layer = project.is_building || o.layer ? std::optional<int>(layer.index) : std::nullopt;
  context.seed = o.seed;
  context.unit = b.units;

  schedule::LayerPlanRequest request;
  request.nozzles = o.nozzles;
  planner::PlanOptions& options = request.planning;
  options.algorithm = *planner::parse_algorithm(o.algorithm);  // CLI11 checked the names
  options.metric = *planner::parse_metric(o.metric);
  options.objective = *planner::parse_objective(o.objective);
  options.time_limit_s = o.time_limit_s;
  options.seed = o.seed;
  options.max_kicks = o.max_kicks;
  options.anytime = o.anytime;
  if (o.polish_kicks) {
    if (o.objective != "time")
      throw InputError("", 0, "--polish-kicks",
                       "applies only with --objective time (the exact-time polish)");
    if (o.algorithm != "cc-tsp" || o.nozzles >= 2)
      throw InputError("", 0, "--polish-kicks",
                       "applies only to one nozzle's cc-tsp search (sections polish on their "
                       "own budgets)");
    // The polish of an anytime run, bounded by its kicks instead of the clock.
    options.polish_kicks = o.polish_kicks;
    options.anytime = true;
  }
  options.neighbourhood = *planner::parse_neighbourhood(o.neighbourhood);
  options.bound = *planner::parse_bound(o.bound);
  for (const auto& [given, flag] :
       {std::pair{o.bound_rounds.has_value(), "--bound-rounds"},
        std::pair{!o.bound_certificate.empty(), "--bound-certificate"}}) {
    if (!given) continue;
    if (options.bound != planner::BoundKind::kConnected)
      throw InputError("", 0, flag, "applies only to the connected bound (not --bound matching)");
    if (o.nozzles >= 2) throw InputError("", 0, flag, "applies only to one nozzle's plan");
  }
  if (o.bound_rounds) {
    // Run the cutting planes to the end, or to this many rounds: no stall rule.
    options.connected_bound.max_rounds = *o.bound_rounds;
    options.connected_bound.stall_fraction = 0.0;
  }
  options.connected_bound.keep_certificate = !o.bound_certificate.empty();
  if (o.first_wall && !o.start_vertex)
    throw InputError("", 0, "--first-wall", "needs --start-vertex");
  if (o.start_vertex) {
    if (o.nozzles >= 2)
      throw InputError("", 0, "--start-vertex", "multi-nozzle paths are closed tours");
    const floors::Vertex* v = b.floors[o.floor].plan.find_vertex(*o.start_vertex);
    if (v == nullptr)
      throw InputError("", 0, "--start-vertex",
                       printf_string("vertex %lld is not in the plan of floor %d",
                                     static_cast<long long>(*o.start_vertex), o.floor));
    options.path = planner::PathSpec::open_from(v->position_m);
    if (o.first_wall) options.path.first = first_step(layer, *o.first_wall, context.where());
  }
  if (o.nozzles >= 2) {
    if (options.algorithm != planner::Algorithm::kCcTsp)
      throw InputError("", 0, "--algorithm",
                       o.algorithm +
                           " plans one nozzle; with --nozzles every section is "
                           "planned by cc-tsp (leave --algorithm out)");
    if (o.gantry_width.empty())
      throw InputError("", 0, "--gantry-width", "is required with --nozzles 2 or more");
    planner::MultiNozzleOptions& multi = request.multi;
    multi.nozzles = o.nozzles;
    multi.message_unit = b.units;
    multi.gantry_width_m = length_flag(o.gantry_width, "--gantry-width", b.units);
    multi.rail_axis = *machine::rail_axis_named(o.rail_axis);  // CLI11 checked it
    multi.method = *planner::parse_multi_method(o.method);
    if (!o.platform_width.empty())
      multi.platform_width_m = length_flag(o.platform_width, "--platform-width", b.units);
    multi.planning = options;
  } else if (!o.gantry_width.empty() || !o.platform_width.empty()) {
    throw InputError("", 0, o.gantry_width.empty() ? "--platform-width" : "--gantry-width",
                     "applies only with --nozzles 2 or more");
  }

  std::optional<planner::SearchReporter> reporter;
  if (!o.quiet && o.nozzles == 1 && options.algorithm == planner::Algorithm::kCcTsp) {
    const bool distance = options.objective == planner::Objective::kDistance;
    reporter.emplace(
        [&project, distance](const planner::SearchProgress* best, double due_s) {
          if (best == nullptr)
            return printf_string("plan-layer: %.0f s, lower bound and first tour under way", due_s);
          if (best->polish)
            return printf_string(
                "plan-layer: %.0f s, best tour so far %.2f s of airtime (exact-time polish, found "
                "at %.1f s, after %ld of its kicks)",
                due_s, best->cost, best->elapsed_s, best->kicks);
          // The time objective's search cost is its estimate; the exact polish follows.
          const std::string cost =
              distance ? project.length(best->cost)
                       : printf_string("%.2f s by the search's estimate", best->cost);
          return printf_string(
              "plan-layer: %.0f s, best tour so far %s (found at %.1f s, after %ld "
              "kicks)",
              due_s, cost.c_str(), best->elapsed_s, best->kicks);
        },
        std::cerr);
    options.on_progress = [&reporter](const planner::SearchProgress& p) { reporter->record(p); };
  }
  const schedule::LayerPlanResult result = schedule::plan_layer(project, layer, request);
  reporter.reset();
  if (result.multi) {
    const auto& plan = *result.multi;
    if (!o.svg.empty())
      outputs.write(o.svg, report::multi_plan_svg(context, layer, plan, request.multi));
    outputs.commit();
    if (o.json)
      std::cout << report::multi_plan_json(context, layer, project.machine_model(), plan,
                                           request.multi)
                       .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                << "\n";
    else
      report::write_multi_plan_text(std::cout, project, context, layer, plan, request.multi,
                                    text_options(o));
    exit_code = plan.status ? kExitOk : kExitNo;
  } else {
    const auto& plan = *result.single;
    const bool certificate_kept = plan.connected_bound && plan.connected_bound->certificate;
    if (!o.bound_certificate.empty() && !certificate_kept)
      throw InputError("", 0, "--bound-certificate",
                       "no certificate: the connected bound did not run (it gets a third of "
                       "--time-limit; give more time)");
    if (!o.svg.empty()) outputs.write(o.svg, report::layer_plan_svg(context, layer, plan));
    if (!o.bound_certificate.empty())
      outputs.write(o.bound_certificate,
                    report::bound_certificate_json(context, layer, plan)
                            .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                        "\n");
    outputs.commit();
    if (o.json)
      std::cout << report::layer_plan_json(context, layer, project.machine_model(), plan)
                       .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                << "\n";
    else
      report::write_layer_plan_text(std::cout, project, context, layer, plan, text_options(o));
    exit_code = kExitOk;
  }
  if (result.idle_limit_violations() > 0)
    std::cerr << printf_string(
        "ccbuild: warning: %d air move(s) exceed the nozzle idle limit of %.0f s (longest "
        "%.1f s): the concrete may set in the nozzle\n",
        result.idle_limit_violations(), project.machine_model().nozzle_idle_limit_s,
        result.max_idle_s());
}

}  // namespace

void add_plan_layer_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<PlanLayerOptions>();
  CLI::App* command = app.add_subcommand(
      "plan-layer",
      "Plan the tool path of one layer: for one nozzle (CC-TSP: each wall is two nodes joined by a "
      "fixed edge, solved by a chained local search seeded with an Euler walk), or with --nozzles "
      "for several gantries on common rails (sections, collision-free paths, exact x/t checks).\n"
      "Prints airtime (distance and time), deposition and layer time, a lower bound on airtime "
      "distance with the gap to it, and the sequence as signed wall ids (-5: wall 5 from its end "
      "vertex to its start vertex; 5:2: the second piece of a wall cut by an opening).\n"
      "Examples:\n"
      "  ccbuild plan-layer tests/data/plans/paper_example1.txt --units ft --start-vertex 1 "
      "--first-wall 1\n"
      "  ccbuild plan-layer config/buildings/house.yaml --floor 1 --layer 12 --objective time "
      "--svg l12.svg\n"
      "  ccbuild plan-layer plan.yaml --algorithm nearest --metric rectilinear --json\n"
      "  ccbuild plan-layer config/buildings/apartment.yaml --layer 10 --nozzles 2 --gantry-width "
      "5ft --svg two.svg\n"
      "The JSON (docs/json.md) holds every nozzle's timed path as waypoints, complete enough "
      "to re-check coverage, speeds and gantry gaps without ccbuild.\n"
      "Exit code 1 when no collision-free multi-nozzle plan was found (the reasons are printed).");
  command->add_option("PLAN", o->file, "Floor plan (YAML, JSON, table text) or building file")
      ->required();
  command->add_option("--floor", o->floor, "Floor of a building (0 = ground)")
      ->check(integer_in(0, 100000))
      ->capture_default_str();
  command
      ->add_option(
          "--layer", o->layer,
          "Layer within the floor (default 0); for a plan file, slices it with --floor-height "
          "and --layer-height instead of planning whole walls")
      ->check(integer_in(0, 10000000));
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
      ->add_option("--algorithm", o->algorithm,
                   "cc-tsp; nearest (greedy nearest wall end); original (file order); exact (small "
                   "layers). With --nozzles, cc-tsp only")
      ->check(CLI::IsMember({"cc-tsp", "nearest", "original", "exact"}))
      ->capture_default_str();
  command
      ->add_option("--bound", o->bound,
                   "Lower bound: connected (an LP with connectivity cuts, certified on every "
                   "pair of points) or matching (the odd points' matching alone: faster, "
                   "weaker)")
      ->check(CLI::IsMember({"connected", "matching"}))
      ->capture_default_str();
  command
      ->add_option("--start-vertex", o->start_vertex,
                   "Plan an open path starting at this plan vertex (default: a closed tour)")
      ->check(integer_in(1, 999999999));
  command
      ->add_option("--first-wall", o->first_wall,
                   "With --start-vertex: deposit this wall first (negative: from its end vertex)")
      ->check(integer_in(-999999999, 999999999));
  CLI::Option* time_limit =
      command
          ->add_option(
              "--time-limit", o->time_limit_s,
              "Search until this many seconds have passed, set-up included (anytime: "
              "the answer is the best found, and depends on the machine's speed; "
              "--max-kicks with the kicks printed reproduces it; a search that stalls "
              "restarts from another first tour and merges in what is better there). "
              "Not given: the search stops on its own budget (deterministic), within "
              "30 s at most. "
              "With --objective time the extra time goes to the exact-time "
              "polish (--max-kicks and --polish-kicks with the numbers printed "
              "reproduce it). With --nozzles or --algorithm exact: a cap on the whole run, "
              "the heuristic searches on their own budgets")
          ->check(number_in(Range::above(0.0, 86400.0), "s"));
  command->add_option("--seed", o->seed, "Random seed: the same seed and inputs give the same plan")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--max-kicks", o->max_kicks,
                   "Kicks of the chained search, exactly, unless the time limit or a proof of "
                   "optimality comes first, restarts as with --time-limit (default: a budget "
                   "from the layer's size that ends early when kicks stop finding better "
                   "tours; docs/planning.md)")
      ->check(integer_in(0, 1000000000));
  command
      ->add_option("--polish-kicks", o->polish_kicks,
                   "With --objective time: kicks of the exact-time polish after its descent, "
                   "exactly, as a --time-limit run makes them (no step budget), unless the "
                   "time limit comes first; 0: the descent alone. With --max-kicks, the two "
                   "numbers a --time-limit run prints replay it (default: 500 kicks on layers "
                   "of up to 16 walls, 20 up to 200, the descent alone above)")
      ->check(integer_in(0, 1000000000));
  command
      ->add_option("--neighbourhood", o->neighbourhood,
                   "Local search of cc-tsp: lk (Lin-Kernighan chains of 3-opt moves; with "
                   "--objective time after 2-opt and Or-opt) or 2opt-oropt (the earlier "
                   "search, for comparison)")
      ->check(CLI::IsMember({"lk", "2opt-oropt"}))
      ->capture_default_str();
  command->add_flag("--json", o->json, "Print one JSON object instead of text (errors too)");
  command
      ->add_option("--bound-rounds", o->bound_rounds,
                   "Cutting-plane rounds of the connected bound, without its stall rule: a "
                   "stronger bound, slower (default: up to 50 rounds, ending when they stop "
                   "raising it). The bound gets a third of --time-limit (10 s by default)")
      ->check(integer_in(1, 100000));
  command
      ->add_option(
          "--bound-certificate", o->bound_certificate,
          "Also write the connected bound's dual solution into this new JSON file (docs/json.md): "
          "the proof of the lower bound, which tests/tools/check_bound.py re-checks without "
          "ccbuild")
      ->check(output_path());
  command->add_option("--svg", o->svg, "Also draw the plan into this SVG file")
      ->check(output_path());
  command->add_flag("--force", o->force,
                    "Overwrite an existing --svg or --bound-certificate file (never one this "
                    "run reads)");
  command
      ->add_option(
          "--nozzles", o->nozzles,
          "Nozzles on common rails (2 or more: sections, collision-free paths, x/t checks)")
      ->check(integer_in(1, planner::kMaxNozzles))
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
  command->add_flag("--quiet", o->quiet,
                    "No progress lines on stderr (one-nozzle searches past 1 s print the "
                    "best tour so far at 1, 2, 4, 8, 16 and 32 s, then every minute)");
  add_input_options(*command, o->input);
  command->callback([o, time_limit, &exit_code] {
    o->anytime = time_limit->count() > 0;
    run_plan_layer(*o, exit_code);
  });
}

}  // namespace ccbuild::cli
