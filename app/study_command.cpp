// ccbuild study STUDY.yaml -o results/: a design study of whole buildings, run here
// (--jobs) or as a Slurm job array (--slurm); `study run` is what an array task runs,
// `study collect` gathers what finished (docs/studies.md).

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/runner.hpp"
#include "ccbuild/study/session.hpp"
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

/// When a signal asked the study to stop: says so and sets the exit code (128 + signal).
bool stopped(int& exit_code) {
  const int signal_number = study::stop_signal().load();
  if (signal_number == 0) return false;
  std::cerr << printf_string(
      "study: stopped by signal %d (%s): the variants running were stopped and recorded as "
      "nothing; run the same command again to go on\n",
      signal_number, strsignal(signal_number));
  exit_code = 128 + signal_number;
  return true;
}

/// This binary, for the variants' processes and the array tasks' scripts.
fs::path self() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path("ccbuild") : exe;
}

std::vector<int> write_results(const study::Plan& plan, bool slurm) {
  return study::write_results(plan, slurm, self(), std::cout, std::cerr);
}

int exit_code_of(const std::vector<int>& lacking) {
  return lacking.empty() ? kExitOk : kExitNo;
}

void run_locally(const study::Plan& plan, const std::vector<int>& indices, int jobs, bool quiet) {
  study::run_locally(plan, indices, jobs, quiet, self(), std::cerr);
}

void run_study(const StudyOptions& o, int& exit_code) {
  const study::StopOnSignals stop_on_signals;
  const study::Study s = study::read_study(o.study);
  // Everything that can be checked is, before anything is written: all or nothing.
  study::check_results_folder(s, o.output, o.force);
  if (o.slurm) study::check_sbatch_values(o.slurm_options, s, o.output, "-o", self());
  if (o.submit && !study::slurm_available())
    throw InputError(
        "", 0, "--submit",
        "sbatch and squeue are not on the PATH (install slurm-client, or run without --slurm); "
        "nothing was written");
  if (!o.slurm) {
    const study::Plan plan = study::prepare(s, o.output, 1, o.force);
    std::cerr << printf_string("study '%s': %zu variants of %lld combinations, results in %s\n",
                               s.name.c_str(), s.variants.size(), s.grid_size, plan.folder.c_str());
    std::vector<int> all(s.variants.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
    run_locally(plan, all, o.jobs, false);
    if (stopped(exit_code)) return;
    exit_code = exit_code_of(write_results(plan, false));
    stopped(exit_code);
    return;
  }
  const study::SlurmSubmission submitted = study::prepare_slurm_study(
      s, o.output, o.chunk, o.force, o.slurm_options, o.submit, self(), std::cerr);
  const fs::path& script = submitted.script;
  const fs::path& folder = submitted.plan.folder;
  if (!o.submit) {
    std::cout << "wrote " << script.string() << "; submit it with `sbatch " << script.string()
              << "` (or pass --submit), then `ccbuild study collect " << folder.string() << "`\n";
    exit_code = kExitOk;
    return;
  }
  const std::string& job = submitted.job;
  std::cout << "submitted job " << job << " (" << script.string() << ")\n";
  if (!o.wait) {
    std::cout << "collect with `ccbuild study collect " << folder.string() << "` once it is done\n";
    exit_code = kExitOk;
    return;
  }
  study::wait_for_jobs(
      submitted.plan, [](const std::string& line) { std::cerr << line << "\n"; },
      &study::stop_signal());
  if (stopped(exit_code)) return;
  exit_code = exit_code_of(write_results(submitted.plan, true));
  stopped(exit_code);
}

void run_task(const StudyOptions& o, int& exit_code) {
  const study::StopOnSignals stop_on_signals;
  const study::Plan plan = study::open_plan(o.folder);
  const int n = static_cast<int>(plan.study.variants.size());
  std::vector<int> indices;
  if (o.variant) {
    if (*o.variant < 0 || *o.variant >= n)
      throw InputError("", 0, "--variant",
                       printf_string("expected 0 to %d, got %d", n - 1, *o.variant));
    indices.push_back(*o.variant);
  } else {
    // Compared before multiplying: task * chunk may not fit an int.
    const int last_task = (n - 1) / plan.chunk;
    if (*o.task < 0 || *o.task > last_task)
      throw InputError("", 0, "--task",
                       printf_string("expected 0 to %d, got %d", last_task, *o.task));
    const int first = *o.task * plan.chunk;
    for (int k = first; k < std::min(n, first + plan.chunk); ++k) indices.push_back(k);
  }
  run_locally(plan, indices, o.jobs, false);
  exit_code = kExitOk;  // each variant's fate is in its result.json
  stopped(exit_code);
}

void run_collect(const StudyOptions& o, int& exit_code) {
  const study::StopOnSignals stop_on_signals;
  const study::Plan plan = study::open_plan(o.folder);
  if (o.resubmit) {  // checked before anything is written
    study::check_sbatch_values(o.slurm_options, plan.study, plan.folder, "RESULTS", self());
    if (!study::slurm_available())
      throw InputError("", 0, "--resubmit",
                       "sbatch and squeue are not on the PATH (install slurm-client); nothing "
                       "was written");
  }
  std::error_code ec;
  const bool slurm = fs::exists(plan.folder / "slurm" / "jobs.tsv", ec);
  if (slurm && o.wait)
    study::wait_for_jobs(
        plan, [](const std::string& line) { std::cerr << line << "\n"; }, &study::stop_signal());
  if (stopped(exit_code)) return;
  const std::vector<int> again = write_results(plan, slurm);
  exit_code = exit_code_of(again);
  if (stopped(exit_code) || !o.resubmit || again.empty()) return;
  const auto [script, job] =
      study::resubmit_variants(plan, again, o.slurm_options, self(), std::cerr);
  std::cout << printf_string("resubmitted %zu variant(s) as job %s (%s)\n", again.size(),
                             job.c_str(), script.c_str());
  if (!o.wait) return;
  study::wait_for_jobs(
      plan, [](const std::string& line) { std::cerr << line << "\n"; }, &study::stop_signal());
  if (stopped(exit_code)) return;
  exit_code = exit_code_of(write_results(plan, true));
  stopped(exit_code);
}

void add_slurm_options(CLI::App& command, StudyOptions& o) {
  command.add_option("--partition", o.slurm_options.partition,
                     "Slurm partition (default: the cluster's); no control characters");
  command.add_option("--time", o.slurm_options.time,
                     "Time limit of each array task, in Slurm's syntax (30, 2:00:00, 1-12)");
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
      "The results folder (-o) must be new or empty, or hold this study's own results (which "
      "resumes it); a folder holding other files or another study's results is refused unless "
      "--force. Each variant runs in a process group of its own and is locked while it runs "
      "(variants/<id>/lock), so two runs of a study never run it at once: the second says so and "
      "leaves it. SIGTERM, SIGINT or SIGHUP stop the study: the variants running are stopped "
      "with it and recorded as nothing.\n"
      "Exit code 0 when every variant has a result, 1 when some failed or did not run, 2 on bad "
      "input or when the run cannot do what was asked (a folder refused, sbatch missing or "
      "refusing the job: nothing is left written), 128 + the signal when a signal stopped it "
      "(143 SIGTERM, 130 SIGINT, 129 SIGHUP).\n"
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
                    "Write into a folder that holds other files or another study's results "
                    "(files of the same names are replaced as the study writes them; none is "
                    "deleted beforehand)");
  command->add_flag(
      "--slurm", o->slurm,
      "Write a Slurm job-array script (<results>/slurm/study.sbatch) instead of running here");
  command->add_flag("--submit", o->submit,
                    "With --slurm: submit it (sbatch) and print its job id; when sbatch is "
                    "missing or refuses the job, exit 2 with the results folder as it was");
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
