#pragma once
// Running a study's variants: each is `ccbuild schedule` in a process (group) of its own (a
// crash or a timeout fails that variant only), with its output in <results>/variants/<id>/.
// A variant already finished with the same inputs (their SHA-256) is not run again, so a
// killed study resumes where it stopped; a variant is locked while it runs (flock on
// variants/<id>/lock, held by the study and by the schedule it started), so two runs of a
// study never run it at once. Local runs and Slurm array tasks run the same code and write
// the same bytes.

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccbuild/study/study.hpp"

namespace ccbuild::study {

/// The results folder's plan (<results>/study.json): the variants, written once by
/// `ccbuild study` and read by every run, local or on Slurm.
struct Plan {
  std::filesystem::path folder;  ///< the results folder (absolute)
  Study study;                   ///< read again from the study file it names
  int chunk = 1;                 ///< variants per Slurm array task
};

/// Checks, writing nothing, that `folder` may take `study`'s results without losing what is
/// there: it is missing or holds no file (empty folders aside), or it holds this study's
/// own plan (study.json: the same study file and variants), which resumes it. Unless
/// `force`, throws InputError naming the folder, what it holds (files the study did not
/// make, another study's results, a study.json that does not read) and --force. With
/// `force`, anything but a file that is not a folder is taken (files are replaced as the
/// study writes them; none is deleted beforehand).
void check_results_folder(const Study& study, const std::filesystem::path& folder, bool force);

/// Writes <folder>/study.json for `study` after check_results_folder (keeping the variants
/// already run there when it is the same study). Throws InputError.
Plan prepare(const Study& study, const std::filesystem::path& folder, int chunk, bool force);

/// Reads <folder>/study.json (typed: a damaged one is an InputError naming it, the line
/// and the JSON pointer) and the study file it names. Throws InputError.
Plan open_plan(const std::filesystem::path& folder);

/// The SHA-256 of what a variant's schedule depends on: its settings and the bytes of
/// the files it names (a building's own plan files and a profile's URDF are checked by
/// the schedule's recorded inputs when it is read back).
std::string inputs_sha256(const Variant& variant);

struct RunOptions {
  std::filesystem::path ccbuild;  ///< the binary that schedules a variant
  /// Set non-zero (a signal number) to stop: the variants running are stopped (their
  /// process groups killed), nothing is recorded for them, no other variant is started.
  /// Read by every thread; may be set from a signal handler.
  const std::atomic<int>* stop = nullptr;
};

/// What a variant came to: feasible, infeasible (a result: the schedule says why), or
/// failed (a crash, a timeout, bad input; the reason and the log say which).
enum class VariantStatus { kFeasible, kInfeasible, kFailed };
/// "feasible", "infeasible", "failed": a result.json's `status`.
std::string to_string(VariantStatus status);
std::optional<VariantStatus> variant_status_named(const std::string& name);

/// What running a variant came to: its status, or none when it was stopped or is being run
/// by another process.
struct Outcome {
  std::optional<VariantStatus> status;
  std::string reason;
  double elapsed_s = 0.0;
  bool skipped = false;  ///< finished before with the same inputs
  bool stopped = false;  ///< stopped by RunOptions::stop: no result written
  bool locked = false;   ///< another process holds its lock (runs it now): not run here
};

/// The file a variant's runner holds locked (flock) while it runs.
std::filesystem::path variant_lock_file(const Plan& plan, int index);

/// Runs variant `index` unless it finished before with the same inputs or another process
/// holds its lock; writes <folder>/variants/<id>/{schedule.json,log.txt,result.json} (a
/// variant run again replaces its own files).
Outcome run_variant(const Plan& plan, int index, const RunOptions& options);

/// Whether variant `index` has a result with the same inputs (feasible or infeasible).
bool finished(const Plan& plan, int index);

/// Writes variant `index`'s report (report.html beside its schedule, `ccbuild report`'s
/// output appended to its log). Returns whether it was written.
bool write_report(const Plan& plan, int index, const RunOptions& options);

/// Runs `indices` on `jobs` processes at once; `progress` is told after each one. Once
/// `options.stop` is set no variant is started.
void run_variants(const Plan& plan, const std::vector<int>& indices, int jobs,
                  const RunOptions& options,
                  const std::function<void(int index, const Outcome&)>& progress);

}  // namespace ccbuild::study
