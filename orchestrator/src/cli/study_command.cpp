// ccbuild study STUDY.yaml -o results/: a design study of whole buildings, run here
// (--jobs) or as a Slurm job array (--slurm); `study run` is what an array task runs,
// `study collect` gathers what finished (docs/studies.md).

#include <unistd.h>

#include <chrono>
#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/runner.hpp"
#include "ccbuild/study/slurm.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct StudyOptions {
  std::string study, output;
  int jobs = 2;
  bool force = false;
  bool slurm = false, submit = false, wait = false;
  study::SlurmOptions slurm_options;
  int chunk = 1;
  // study run
  std::string folder;
  std::optional<int> task, variant;
  // study collect
  bool resubmit = false;
};

/// This binary, for the variants' processes and the array tasks' scripts.
fs::path self() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path("ccbuild") : exe;
}

std::string minutes(double s) {
  return duration_text(s);
}

/// Writes results.csv, results.json and results.html, after a report for each variant on a
/// Pareto front (the page links to it); prints the counts and each variant without a
/// result with its log. Returns those variants (failed or missing), by index.
std::vector<int> write_results(const study::Plan& plan, bool slurm) {
  study::Collected c = study::collect(plan);
  std::vector<int> fronts;
  for (const auto& [cost, label] : study::front_costs())
    for (int i : study::pareto_front(c, cost)) fronts.push_back(i);
  std::sort(fronts.begin(), fronts.end());
  fronts.erase(std::unique(fronts.begin(), fronts.end()), fronts.end());
  study::RunOptions run;
  run.ccbuild = self();
  for (int i : fronts) {
    std::error_code ec;
    if (fs::is_regular_file(plan.folder / "variants" / plan.study.variants[i].id / "report.html",
                            ec))
      continue;
    if (!study::write_report(plan, i, run))
      std::cerr << "study: no report for " << plan.study.variants[i].id
                << " (ccbuild report failed; its log says why)\n";
  }
  write_file_atomically(plan.folder / "results.csv", study::results_csv(plan, c), true);
  write_file_atomically(plan.folder / "results.json", study::results_json(plan, c), true);
  write_file_atomically(plan.folder / "results.html", study::results_html(plan, c), true);
  std::cout << printf_string(
      "%s: %zu variants: %zu feasible, %zu infeasible, %zu failed, %zu not run\n",
      plan.study.name.c_str(), c.rows.size(), c.feasible.size(), c.infeasible.size(),
      c.failed.size(), c.missing.size());
  for (const auto& [cost, label] : study::front_costs()) {
    const auto front = study::pareto_front(c, cost);
    if (front.empty()) continue;
    std::string ids;
    for (int i : front) ids += (ids.empty() ? "" : " ") + plan.study.variants[i].id;
    std::cout << "  front of makespan against " << label << ": " << ids << "\n";
  }
  std::vector<int> lacking = c.failed;
  lacking.insert(lacking.end(), c.missing.begin(), c.missing.end());
  std::sort(lacking.begin(), lacking.end());
  for (int i : lacking) {
    const auto& row = c.rows[i];
    const fs::path dir = plan.folder / "variants" / plan.study.variants[i].id;
    std::string line = "  " + row["id"].get<std::string>() + " " + row["status"].get<std::string>();
    if (row.contains("reason")) line += ": " + row["reason"].get<std::string>();
    std::error_code ec;
    if (fs::exists(dir / "log.txt", ec)) line += "; log " + (dir / "log.txt").string();
    if (slurm)
      if (const auto state = study::task_state(plan, i))
        line += "; Slurm task " + state->job + " " + state->state + ", log " + state->log.string();
    std::cout << line << "\n";
  }
  std::cout << "results: " << (plan.folder / "results.csv").string()
            << ", results.json, results.html\n";
  return lacking;
}

int exit_code_of(const std::vector<int>& lacking) {
  return lacking.empty() ? kExitOk : kExitNo;
}

void run_locally(const study::Plan& plan, const std::vector<int>& indices, int jobs, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  std::size_t done = 0, run = 0, failed = 0, skipped = 0;
  study::RunOptions options;
  options.ccbuild = self();
  study::run_variants(plan, indices, jobs, options, [&](int index, const study::Outcome& o) {
    ++done;
    o.skipped ? ++skipped : ++run;
    if (o.status == "failed") ++failed;
    if (quiet || o.skipped) return;  // the skipped are counted once, below
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t left = indices.size() - done;
    std::string eta =
        run > 0 && left > 0 ? ", about " + minutes(elapsed_s / run * left) + " left" : "";
    std::cerr << printf_string(
        "study: %zu of %zu variants (%s %s%s%s), %s%s\n", done, indices.size(),
        plan.study.variants[index].id.c_str(), o.skipped ? "finished before" : o.status.c_str(),
        o.reason.empty() ? "" : ": ", o.reason.c_str(), minutes(elapsed_s).c_str(), eta.c_str());
  });
  if (!quiet && skipped > 0)
    std::cerr << printf_string(
        "study: %zu variant(s) finished before with the same inputs were not run again\n", skipped);
  (void)failed;
}

void run_study(const StudyOptions& o, int& exit_code) {
  const study::Study s = study::read_study(o.study);
  std::error_code ec;
  if (fs::exists(o.output, ec) && !fs::is_directory(o.output, ec))
    throw InputError(o.output, 0, "-o", "expected a folder for the results, got a file");
  const study::Plan plan = study::prepare(s, o.output, o.slurm ? o.chunk : 1, o.force);
  std::cerr << printf_string("study '%s': %zu variants of %lld combinations, results in %s\n",
                             s.name.c_str(), s.variants.size(), s.grid_size, plan.folder.c_str());
  if (!o.slurm) {
    std::vector<int> all(s.variants.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
    run_locally(plan, all, o.jobs, false);
    exit_code = exit_code_of(write_results(plan, false));
    return;
  }
  fs::create_directories(plan.folder / "slurm");
  const fs::path script = plan.folder / "slurm" / "study.sbatch";
  write_file_atomically(script, study::sbatch_script(plan, o.slurm_options, self()), true);
  fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add, ec);
  if (!o.submit) {
    std::cout << "wrote " << script.string() << "; submit it with `sbatch " << script.string()
              << "` (or pass --submit), then `ccbuild study collect " << plan.folder.string()
              << "`\n";
    exit_code = kExitOk;
    return;
  }
  if (!study::slurm_available())
    throw InputError(
        "", 0, "--submit",
        "sbatch and squeue are not on the PATH (install slurm-client, or run without --slurm)");
  const std::string job = study::submit(plan, script);
  std::cout << "submitted job " << job << " (" << script.string() << ")\n";
  if (!o.wait) {
    std::cout << "collect with `ccbuild study collect " << plan.folder.string()
              << "` once it is done\n";
    exit_code = kExitOk;
    return;
  }
  study::wait_for_jobs(plan, [](const std::string& line) { std::cerr << line << "\n"; });
  exit_code = exit_code_of(write_results(plan, true));
}

void run_task(const StudyOptions& o, int& exit_code) {
  const study::Plan plan = study::open_plan(o.folder);
  const int n = static_cast<int>(plan.study.variants.size());
  std::vector<int> indices;
  if (o.variant) {
    if (*o.variant < 0 || *o.variant >= n)
      throw InputError("", 0, "--variant",
                       printf_string("expected 0 to %d, got %d", n - 1, *o.variant));
    indices.push_back(*o.variant);
  } else {
    const int first = *o.task * plan.chunk;
    if (*o.task < 0 || first >= n)
      throw InputError("", 0, "--task",
                       printf_string("expected 0 to %d, got %d", (n - 1) / plan.chunk, *o.task));
    for (int k = first; k < std::min(n, first + plan.chunk); ++k) indices.push_back(k);
  }
  run_locally(plan, indices, o.jobs, false);
  exit_code = kExitOk;  // each variant's fate is in its result.json
}

void run_collect(const StudyOptions& o, int& exit_code) {
  const study::Plan plan = study::open_plan(o.folder);
  std::error_code ec;
  const bool slurm = fs::exists(plan.folder / "slurm" / "jobs.tsv", ec);
  if (slurm && o.wait)
    study::wait_for_jobs(plan, [](const std::string& line) { std::cerr << line << "\n"; });
  const std::vector<int> again = write_results(plan, slurm);
  exit_code = exit_code_of(again);
  if (!o.resubmit || again.empty()) return;
  fs::create_directories(plan.folder / "slurm");
  int earlier = 0;  // resubmit-1.sbatch, resubmit-2.sbatch, ...
  for (const auto& entry : fs::directory_iterator(plan.folder / "slurm"))
    if (entry.path().filename().string().rfind("resubmit-", 0) == 0) ++earlier;
  const fs::path script = plan.folder / "slurm" / printf_string("resubmit-%d.sbatch", earlier + 1);
  write_file_atomically(script, study::sbatch_script(plan, o.slurm_options, self(), again), true);
  if (!study::slurm_available())
    throw InputError("", 0, "--resubmit",
                     "sbatch and squeue are not on the PATH (install slurm-client)");
  const std::string job = study::submit(plan, script, again);
  std::cout << printf_string("resubmitted %zu variant(s) as job %s (%s)\n", again.size(),
                             job.c_str(), script.c_str());
  if (!o.wait) return;
  study::wait_for_jobs(plan, [](const std::string& line) { std::cerr << line << "\n"; });
  exit_code = exit_code_of(write_results(plan, true));
}

void add_slurm_options(CLI::App& command, StudyOptions& o) {
  command.add_option("--partition", o.slurm_options.partition,
                     "Slurm partition (default: the cluster's)");
  command.add_option("--time", o.slurm_options.time,
                     "Time limit of each array task, in Slurm's syntax (30, 2:00:00)");
  command
      .add_option("--array-max", o.slurm_options.array_max,
                  "At most this many array tasks at once (the array's %K)")
      ->check(CLI::Range(0, 100000));
  command.add_flag(
      "--wait", o.wait,
      "Wait until the study's jobs have left the queue (squeue), then collect the results");
}

}  // namespace

void add_study_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<StudyOptions>();
  CLI::App* command = app.add_subcommand(
      "study",
      "A design study of whole buildings: a study file (docs/studies.md) names the building(s) and "
      "the axes to vary (machine and material profiles, any number in a profile by its path, "
      "sites, "
      "objectives, seeds), as a grid or a seeded random sample; every variant is scheduled in a "
      "process of its own, here (--jobs) or as a Slurm job array (--slurm). A variant already "
      "finished with the same inputs (their SHA-256) is not run again, so a killed study resumes. "
      "Results: results.csv and results.json (a row per variant: its settings, status and "
      "measures) "
      "and results.html (the Pareto fronts of makespan against nozzles, concrete and crew hours, "
      "the "
      "makespan's sensitivity to each axis, a report for each variant on a front). An infeasible "
      "schedule is a result; a crash, bad input or a timeout fails the variant (listed with its "
      "log).\n"
      "Exit code 0 when every variant has a result, 1 when some failed or did not run.\n"
      "Examples:\n"
      "  ccbuild study studies/house-mixes.yaml -o house-study --jobs 2\n"
      "  ccbuild study studies/house-mixes.yaml -o house-study --slurm --partition batch --time 30 "
      "--submit\n"
      "  ccbuild study collect house-study --resubmit --wait");
  command->add_option("STUDY", o->study, "A study file (YAML)");
  command->add_option("-o,--output", o->output, "The results folder (made if missing)")
      ->check(output_path());
  command->add_option("--jobs", o->jobs, "Variants run at once here (each a process of one thread)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  command->add_flag("--force", o->force,
                    "Start over in a folder that holds another study's results");
  command->add_flag(
      "--slurm", o->slurm,
      "Write a Slurm job-array script (<results>/slurm/study.sbatch) instead of running here");
  command->add_flag("--submit", o->submit, "With --slurm: submit it (sbatch) and print its job id");
  command->add_option("--chunk", o->chunk, "With --slurm: variants per array task")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  add_slurm_options(*command, *o);

  CLI::App* run = command->add_subcommand(
      "run", "Run a chunk of a prepared study (what a Slurm array task runs)");
  run->add_option("RESULTS", o->folder, "The results folder `ccbuild study` prepared")->required();
  auto* task =
      run->add_option("--task", o->task, "The chunk: variants task*chunk to task*chunk+chunk-1");
  auto* variant = run->add_option("--variant", o->variant, "One variant, by its index (0-based)");
  task->excludes(variant);
  run->add_option("--jobs", o->jobs, "Variants run at once")->check(CLI::Range(1, 256));
  run->callback([o, &exit_code, task, variant] {
    if (!task->count() && !variant->count())
      throw CLI::ValidationError("--task or --variant", "one of them is required");
    run_task(*o, exit_code);
  });

  CLI::App* collect = command->add_subcommand(
      "collect",
      "Gather a study's results (results.csv, .json, .html); list each variant without one, "
      "with its log and its Slurm task's state; --resubmit runs only those again");
  collect->add_option("RESULTS", o->folder, "The results folder")->required();
  collect->add_flag("--resubmit", o->resubmit,
                    "Submit the failed and missing variants again, one array task each");
  add_slurm_options(*collect, *o);
  collect->callback([o, &exit_code] { run_collect(*o, exit_code); });

  command->require_subcommand(0, 1);
  command->callback([o, &exit_code, run, collect] {
    if (run->parsed() || collect->parsed()) return;
    if (o->study.empty()) throw CLI::RequiredError("STUDY");
    if (o->output.empty()) throw CLI::RequiredError("-o,--output");
    if (o->submit && !o->slurm) throw CLI::ValidationError("--submit", "needs --slurm");
    run_study(*o, exit_code);
  });
}

}  // namespace ccbuild::cli
