#pragma once
// Child processes for a study: a variant's `ccbuild schedule` (its output to a log file,
// killed with its process group when it runs too long or the study is asked to stop) and
// Slurm's commands (their output captured).

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

namespace ccbuild::study::detail {

struct ProcessResult {
  int exit_code = -1;  ///< when it exited
  int signal = 0;      ///< when a signal ended it
  bool timed_out = false;
  bool stopped = false;  ///< `stop` was set while it ran: its process group was killed
  std::string output;    ///< stdout and stderr, when captured
};

/// How long a process stopped with SIGTERM may take to end before SIGKILL, s.
inline constexpr double kStopGrace_s = 5.0;
/// How long after a child ended by SIGTERM, SIGINT or SIGHUP the same signal may take to
/// reach this process and set `stop`, s.
inline constexpr double kSignalRace_s = 1.0;

/// Runs `argv` (argv[0] a path, or a name looked up on PATH) in a process group of its own,
/// with stdout and stderr to `log` (appended), or captured when `log` is empty. Kills the
/// group (SIGKILL) after `timeout_s`; when `*stop` becomes non-zero (a signal asked this
/// process to stop), sends the group SIGTERM, then SIGKILL after kStopGrace_s. Either way
/// it returns only once the child is reaped and its group killed, so nothing it started
/// runs on. A child ended by SIGTERM, SIGINT or SIGHUP counts as stopped when `*stop` is
/// set within kSignalRace_s (the signal reached both: a Slurm job cancelled). `inherit_fd` (>= 0),
/// a descriptor opened close-on-exec, is kept open in the child (a lock it holds while it runs).
/// Throws std::runtime_error when it cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                          double timeout_s, const std::atomic<int>* stop = nullptr,
                          int inherit_fd = -1);

/// Whether `name` is an executable on PATH.
bool on_path(const std::string& name);

}  // namespace ccbuild::study::detail
