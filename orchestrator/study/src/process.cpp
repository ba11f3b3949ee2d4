#include "process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace ccbuild::study::detail {

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                          double timeout_s) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int pipe_fds[2] = {-1, -1};
  int log_fd = -1;
  if (log.empty()) {
    if (::pipe(pipe_fds) != 0) throw std::runtime_error("cannot make a pipe for " + argv[0]);
  } else {
    log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log_fd < 0) throw std::runtime_error("cannot write " + log.string());
  }
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv[0]);
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group: a timeout kills its children too
    const int out = log.empty() ? pipe_fds[1] : log_fd;
    ::dup2(out, 1);
    ::dup2(out, 2);
    if (log.empty()) {
      ::close(pipe_fds[0]);
      ::close(pipe_fds[1]);
    }
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
  int status = 0;
  for (;;) {
    if (log.empty()) {
      char buffer[4096];
      ssize_t n;
      while ((n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0)
        if (result.output.size() < (1u << 20)) result.output.append(buffer, n);
    }
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed_s > timeout_s && !result.timed_out) {
      result.timed_out = true;
      ::kill(-pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (log.empty()) {
    char buffer[4096];
    ssize_t n;
    while ((n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0)
      if (result.output.size() < (1u << 20)) result.output.append(buffer, n);
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
