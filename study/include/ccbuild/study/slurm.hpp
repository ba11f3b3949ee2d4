#pragma once
// Running a study as a Slurm job array: one array task per chunk of variants, each running
// `ccbuild study run <results> --task $SLURM_ARRAY_TASK_ID` (or, resubmitted, one variant
// per task with --variant). Jobs submitted are listed in <results>/slurm/jobs.tsv so that
// `collect` can ask Slurm what became of a task that left no result.

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/study/runner.hpp"

namespace ccbuild::study {

struct SlurmOptions {
  std::string partition;  ///< --partition (empty: the cluster's default)
  std::string time;       ///< --time per array task, Slurm's syntax ("30", "2:00:00")
  int array_max = 0;      ///< at most this many tasks at once (the array's %K); 0: no limit
};

/// Checks every value that goes into an sbatch script, before anything is written: no
/// control character (a newline would start a line of its own in the script) in
/// --partition, --time, the study's name, the results folder (`folder_flag` names where it
/// was given: "-o", "RESULTS") or the ccbuild binary's path; --time in Slurm's syntax
/// (minutes, minutes:seconds, hours:minutes:seconds, days-hours[:minutes[:seconds]],
/// infinite). Throws InputError naming the flag (or the study file's `name`).
void check_sbatch_values(const SlurmOptions& options, const Study& study,
                         const std::filesystem::path& folder, const std::string& folder_flag,
                         const std::filesystem::path& ccbuild);

/// The sbatch script for `plan`: array tasks 0..chunks-1, or (variants given) one task per
/// variant index. Values in #SBATCH lines are quoted for sbatch's parser, those in the
/// command line for bash. Throws InputError as check_sbatch_values.
std::string sbatch_script(const Plan& plan, const SlurmOptions& options,
                          const std::filesystem::path& ccbuild,
                          const std::vector<int>& variants = {});

/// The array tasks sbatch_script makes: the chunks 0..n-1, or the variants given.
std::vector<int> array_tasks(const Plan& plan, const std::vector<int>& variants = {});

/// Submits `script` (a file, as sbatch_script wrote it for `variants`) with sbatch; returns
/// the job id and records it with its tasks (chunks, or variants when given) in
/// <results>/slurm/jobs.tsv (rewritten whole). Throws InputError (field "--submit") with
/// sbatch's message when it cannot be run or refuses: the run could not do what was asked,
/// exit code 2; jobs.tsv is then unchanged.
std::string submit(const Plan& plan, const std::filesystem::path& script,
                   const std::vector<int>& variants = {});

/// Waits until none of the plan's jobs is in squeue; `progress` is told now and then.
/// Returns early once `*stop` is non-zero. Throws InputError when jobs.tsv does not read.
void wait_for_jobs(const Plan& plan, const std::function<void(const std::string&)>& progress,
                   const std::atomic<int>* stop = nullptr);

/// What Slurm says of the array task that ran variant `index` (sacct, else scontrol):
/// "COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", ..., with the job id; nullopt when no
/// job of the plan ran it or Slurm no longer knows it. Throws InputError when jobs.tsv
/// does not read.
struct TaskState {
  std::string job;    ///< "123_4"
  std::string state;  ///< Slurm's
  std::filesystem::path log;
};
std::optional<TaskState> task_state(const Plan& plan, int index);

/// Whether Slurm's client commands are on the PATH.
bool slurm_available();

}  // namespace ccbuild::study
