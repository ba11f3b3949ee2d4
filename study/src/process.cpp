#include "process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace ccbuild::study::detail {

namespace {

/// Appends what the pipe holds now (up to 1 MiB in all) to `output`.
void drain(int fd, std::string& output) {
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(fd, buffer, sizeof buffer)) > 0)
    if (output.size() < (1u << 20)) output.append(buffer, static_cast<std::size_t>(n));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                          double timeout_s, const std::atomic<int>* stop, int inherit_fd) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int pipe_fds[2] = {-1, -1};
  int log_fd = -1;
  // Close-on-exec: the children other threads start at the same time must not keep them.
  if (log.empty()) {
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
      throw std::runtime_error("cannot make a pipe for " + argv[0]);
  } else {
    log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log_fd < 0) throw std::runtime_error("cannot write " + log.string());
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {pipe_fds[0], pipe_fds[1], log_fd})
      if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot start " + argv[0]);
  }
  if (pid == 0) {
    // The study's stop handlers are not the child's: a SIGTERM before exec ends it.
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    for (int s : {SIGTERM, SIGINT, SIGHUP}) ::sigaction(s, &default_action, nullptr);
    ::setpgid(0, 0);  // its own group: a timeout or a stop kills its children too
    const int out = log.empty() ? pipe_fds[1] : log_fd;
    ::dup2(out, 1);
    ::dup2(out, 2);
    if (inherit_fd >= 0) ::fcntl(inherit_fd, F_SETFD, 0);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, 0);
    ::execvp(args[0], args.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  ProcessResult result;
  if (log.empty()) {
    ::close(pipe_fds[1]);
    ::fcntl(pipe_fds[0], F_SETFL, O_NONBLOCK);
  } else {
    ::close(log_fd);
  }
  const auto start = std::chrono::steady_clock::now();
  auto stop_sent = start;
  bool killed = false;
  for (;;) {
    if (log.empty()) drain(pipe_fds[0], result.output);
    // Ended? Not reaped yet (WNOWAIT): while it is a zombie its pid, and so its group's id,
    // cannot be taken by another process, so the group can still be killed below.
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == pid) {
      // A signal that stops the study may reach the child first (Slurm's scancel and a
      // hang-up signal every process of the job or session): then it was stopped, not failed.
      const bool by_stop_signal =
          (info.si_code == CLD_KILLED || info.si_code == CLD_DUMPED) &&
          (info.si_status == SIGTERM || info.si_status == SIGINT || info.si_status == SIGHUP);
      if (stop && by_stop_signal && !result.stopped) {
        const auto ended = std::chrono::steady_clock::now();
        while (stop->load() == 0 && seconds_since(ended) < kSignalRace_s)
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        result.stopped = stop->load() != 0;
      }
      break;
    }
    if (seconds_since(start) > timeout_s && !result.timed_out) {
      result.timed_out = true;
      ::kill(-pid, SIGKILL);
      killed = true;
    }
    if (stop && stop->load() != 0 && !result.stopped) {
      result.stopped = true;
      ::kill(-pid, SIGTERM);
      stop_sent = std::chrono::steady_clock::now();
    }
    if (result.stopped && !killed && seconds_since(stop_sent) > kStopGrace_s) {
      ::kill(-pid, SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // What it started and left in its group goes with it.
  if (result.timed_out || result.stopped) ::kill(-pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (log.empty()) {
    drain(pipe_fds[0], result.output);
    ::close(pipe_fds[0]);
  }
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

bool on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string all(path);
  std::size_t begin = 0;
  while (begin <= all.size()) {
    const std::size_t colon = std::min(all.find(':', begin), all.size());
    const std::filesystem::path candidate =
        std::filesystem::path(all.substr(begin, colon - begin)) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    begin = colon + 1;
  }
  return false;
}

}  // namespace ccbuild::study::detail
