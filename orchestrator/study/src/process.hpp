#pragma once
// Child processes for a study: a variant's `ccbuild schedule` (its output to a log file,
// killed with its process group when it runs too long) and Slurm's commands (their
// output captured).

#include <filesystem>
#include <string>
#include <vector>

namespace ccbuild::study::detail {

struct ProcessResult {
  int exit_code = -1;  ///< when it exited
  int signal = 0;      ///< when a signal ended it
  bool timed_out = false;
  std::string output;  ///< stdout and stderr, when captured
};

/// Runs `argv` (argv[0] a path, or a name looked up on PATH) with stdout and stderr to
/// `log` (appended), or captured when `log` is empty; kills it (its process group) after
/// `timeout_s`. Throws std::runtime_error when it cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                          double timeout_s);

/// Whether `name` is an executable on PATH.
bool on_path(const std::string& name);

}  // namespace ccbuild::study::detail
