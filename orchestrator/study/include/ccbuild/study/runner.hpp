#pragma once
// Running a study's variants: each is `ccbuild schedule` in a process of its own (a crash
// or a timeout fails that variant only), with its output in <results>/variants/<id>/. A
// variant already finished with the same inputs (their SHA-256) is not run again, so a
// killed study resumes where it stopped. Local runs and Slurm array tasks run the same
// code and write the same bytes.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccbuild/study/study.hpp"

namespace ccbuild::study {

/// The results folder's plan (<results>/study.json): the variants, written once by
/// `ccbuild study` and read by every run, local or on Slurm.
struct Plan {
  std::filesystem::path folder;  ///< the results folder (absolute)
  nlohmann::ordered_json json;   ///< study.json as written
  Study study;                   ///< read again from the study file it names
  int chunk = 1;                 ///< variants per Slurm array task
};

/// Writes <folder>/study.json for `study` (keeping the variants already run there when it
/// is the same study; throws InputError when the folder holds another study's results and
/// `force` is false).
Plan prepare(const Study& study, const std::filesystem::path& folder, int chunk, bool force);

/// Reads <folder>/study.json and the study file it names. Throws InputError.
Plan open_plan(const std::filesystem::path& folder);

/// The SHA-256 of what a variant's schedule depends on: its settings and the bytes of
/// the files it names (a building's own plan files and a profile's URDF are checked by
/// the schedule's recorded inputs when it is read back).
std::string inputs_sha256(const Variant& variant);

struct RunOptions {
  std::filesystem::path ccbuild;  ///< the binary that schedules a variant
};

/// What a variant came to: "feasible", "infeasible" (a result: the schedule says why), or
/// "failed" (a crash, a timeout, bad input; `reason` and the log say which).
struct Outcome {
  std::string status;
  std::string reason;
  double elapsed_s = 0.0;
  bool skipped = false;  ///< finished before with the same inputs
};

/// Runs variant `index` unless it finished before with the same inputs; writes
/// <folder>/variants/<id>/{schedule.json,log.txt,result.json}.
Outcome run_variant(const Plan& plan, int index, const RunOptions& options);

/// Whether variant `index` has a result with the same inputs (feasible or infeasible).
bool finished(const Plan& plan, int index);

/// Writes variant `index`'s report (report.html beside its schedule, `ccbuild report`'s
/// output appended to its log). Returns whether it was written.
bool write_report(const Plan& plan, int index, const RunOptions& options);

/// Runs `indices` on `jobs` processes at once; `progress` is told after each one.
void run_variants(const Plan& plan, const std::vector<int>& indices, int jobs,
                  const RunOptions& options,
                  const std::function<void(int index, const Outcome&)>& progress);

}  // namespace ccbuild::study
