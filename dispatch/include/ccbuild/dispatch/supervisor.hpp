#pragma once
// The simulated machines of a dry-run, one `ccbuild-sim` process each (docs/dispatch.md):
// started with their flags, parked where `parking_homes` says, stopped (SIGTERM) when the
// supervisor goes and never outliving the process that started them. One that ends by
// itself (a crash) is started again on its own record, without an injected crash, at most
// kMostRestarts times; one that refuses its input (exit code 2) is not started again.

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace ccbuild::dispatch {

class MachineSupervisor {
 public:
  /// A machine ending more often than this is not started again: the run stops.
  static constexpr int kMostRestarts = 10;

  /// Starts `sim` once per machine of `ids` with `--machine-id`, `--state
  /// <state_dir>/<id>.state`, `common` flags, `--home` from `homes` and each machine's own
  /// `faults` flags. Throws InputError when `sim` is not there.
  MachineSupervisor(const std::filesystem::path& sim, const std::vector<std::string>& ids,
                    const std::map<std::string, std::array<double, 4>>& homes,
                    std::vector<std::string> common,
                    const std::map<std::string, std::vector<std::string>>& faults,
                    const std::filesystem::path& state_dir);
  ~MachineSupervisor();
  MachineSupervisor(const MachineSupervisor&) = delete;
  MachineSupervisor& operator=(const MachineSupervisor&) = delete;

  /// Starts again the machines that ended; returns what happened, in words. Throws
  /// InputError when a machine refused its input (exit code 2: its own message is above)
  /// or could not be started (127), and sets `given_up` when one ended more often than
  /// kMostRestarts (then it stays down).
  std::vector<std::string> restart_ended(std::optional<std::string>& given_up);
  /// Restarts so far, all machines together.
  int restarts() const;

 private:
  pid_t start(std::vector<std::string> args);
  struct Running {
    std::string id;
    std::vector<std::string> args;
    pid_t pid;
    int restarts = 0;
  };
  std::filesystem::path sim_;
  std::vector<Running> running_;
};

}  // namespace ccbuild::dispatch
