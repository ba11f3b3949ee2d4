#pragma once
// What a study run does around its variants, for `ccbuild study`: signals that stop it
// cleanly, a results folder put back as it was when a submission fails, the variants run
// here with a progress line each, and the results written with their summary.

#include <signal.h>

#include <array>
#include <atomic>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/study/runner.hpp"
#include "ccbuild/study/slurm.hpp"
#include "ccbuild/study/study.hpp"

namespace ccbuild::study {

/// The signal that asked the study to stop (0: none yet), set while a StopOnSignals lives.
std::atomic<int>& stop_signal();

/// While it lives, SIGTERM, SIGINT and SIGHUP ask the study to stop (stop_signal) instead of
/// ending the process at once, so that it stops its variants (their process groups) and
/// records nothing false first; the command then exits 128 + the signal.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  static constexpr std::array<int, 3> kSignals = {SIGTERM, SIGINT, SIGHUP};
  std::array<struct sigaction, 3> before_{};
};

/// What a run is about to write into a results folder, to put back as it was when a later
/// step fails (sbatch refusing the job): files it made are removed, files it replaced get
/// their bytes back, folders it made are removed.
class Rollback {
 public:
  /// Remembers `file` as it is now, before it is written.
  void file(const std::filesystem::path& path);
  /// Remembers which of `folder` and its parents do not exist yet, before they are made.
  void folder(const std::filesystem::path& path);
  /// Puts back what was remembered; says on `err` what it could not.
  void undo(std::ostream& err) noexcept;

 private:
  struct Saved {
    std::filesystem::path path;
    std::optional<std::string> bytes;  ///< unset: it did not exist
    std::filesystem::file_time_type modified;
  };
  std::vector<Saved> files_;
  std::vector<std::filesystem::path> folders_;
};

/// Runs the variants `indices` of `plan` here, `jobs` at a time, with `ccbuild` as each
/// variant's program; a line per variant on `progress` unless `quiet`.
void run_locally(const Plan& plan, const std::vector<int>& indices, int jobs, bool quiet,
                 const std::filesystem::path& ccbuild, std::ostream& progress);

/// Writes results.csv, results.json and results.html, after a report for each variant on a
/// Pareto front (the page links to it); writes the counts and each variant without a
/// result with its log to `out`. Returns those variants (failed or missing), by index.
std::vector<int> write_results(const Plan& plan, bool slurm, const std::filesystem::path& ccbuild,
                               std::ostream& out, std::ostream& err);

/// A study prepared for Slurm: its plan, its sbatch script and, when submitted, the job.
struct SlurmSubmission {
  Plan plan;
  std::filesystem::path script;
  std::string job;  ///< empty when not submitted
};

/// Prepares `study`'s results folder `output` for a Slurm job array of `chunk` variants a
/// task, writes its sbatch script (for `ccbuild`), and submits it when `submit`; a
/// submission that fails leaves the folder as it was (InputError says so).
SlurmSubmission prepare_slurm_study(const Study& study, const std::filesystem::path& output,
                                    int chunk, bool force, const SlurmOptions& options, bool submit,
                                    const std::filesystem::path& ccbuild, std::ostream& err);

/// Submits the variants `again` of `plan` as a new array (slurm/resubmit-N.sbatch); the
/// script is removed when the submission fails. Returns the script and the job.
std::pair<std::filesystem::path, std::string> resubmit_variants(
    const Plan& plan, const std::vector<int>& again, const SlurmOptions& options,
    const std::filesystem::path& ccbuild, std::ostream& err);

}  // namespace ccbuild::study
