#include "ccbuild/dispatch/supervisor.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::dispatch {

MachineSupervisor::MachineSupervisor(const std::filesystem::path& sim,
                                     const std::vector<std::string>& ids,
                                     const std::map<std::string, std::array<double, 4>>& homes,
                                     std::vector<std::string> common,
                                     const std::map<std::string, std::vector<std::string>>& faults,
                                     const std::filesystem::path& state_dir)
    : sim_(sim) {
  if (!std::filesystem::exists(sim_))
    throw InputError(sim_.string(), 0, "", "ccbuild-sim not found beside ccbuild (build it)");
  for (const auto& id : ids) {
    std::vector<std::string> args = {"ccbuild-sim", "--machine-id", id, "--state",
                                     (state_dir / (id + ".state")).string()};
    args.insert(args.end(), common.begin(), common.end());
    if (const auto home = homes.find(id); home != homes.end()) {
      args.push_back("--home");
      for (const double v : home->second) args.push_back(printf_string("%.17g", v));
    }
    if (const auto it = faults.find(id); it != faults.end())
      args.insert(args.end(), it->second.begin(), it->second.end());
    running_.push_back({id, args, start(args)});
  }
}

MachineSupervisor::~MachineSupervisor() {
  for (const auto& m : running_)
    if (m.pid > 0) ::kill(m.pid, SIGTERM);
  for (const auto& m : running_)
    if (m.pid > 0) ::waitpid(m.pid, nullptr, 0);
}

int MachineSupervisor::restarts() const {
  int n = 0;
  for (const auto& m : running_) n += m.restarts;
  return n;
}

std::vector<std::string> MachineSupervisor::restart_ended(std::optional<std::string>& given_up) {
  std::vector<std::string> said;
  for (auto& m : running_) {
    int status = 0;
    if (m.pid <= 0 || ::waitpid(m.pid, &status, WNOHANG) != m.pid) continue;
    m.pid = -1;
    const bool exited = WIFEXITED(status);
    const int code = exited ? WEXITSTATUS(status) : WTERMSIG(status);
    if (exited && (code == 2 || code == 127))
      throw InputError("", 0, m.id,
                       code == 2 ? "ccbuild-sim refused what it was given (exit code 2; its "
                                   "message is above): nothing was started again"
                                 : "ccbuild-sim could not be started (exit code 127)");
    if (++m.restarts > kMostRestarts) {
      given_up = printf_string("%s ended %d times; not started again", m.id.c_str(), m.restarts);
      continue;
    }
    said.push_back(printf_string("%s ended (%s %d); started again on its own record", m.id.c_str(),
                                 exited ? "exit code" : "signal", code));
    // It crashed once; it runs on without that fault.
    for (std::size_t k = 0; k + 1 < m.args.size(); ++k)
      if (m.args[k] == "--crash-after") m.args.erase(m.args.begin() + k, m.args.begin() + k + 2);
    m.pid = start(m.args);
  }
  return said;
}

pid_t MachineSupervisor::start(std::vector<std::string> args) {
  const pid_t pid = ::fork();
  CCBUILD_CHECK(pid >= 0, "fork failed");
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the dry-run
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(sim_.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

}  // namespace ccbuild::dispatch
