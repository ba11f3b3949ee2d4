#pragma once
// Runs the ccbuild binary (or any command) and captures exit code, stdout and stderr.

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ccbuild::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ccbuild_binary() {
  return std::string(CCBUILD_BINARY_DIR) + "/ccbuild";
}

/// Runs `command` through /bin/sh in the source tree.
inline CommandResult run_shell(const std::string& command) {
  const auto err_path = std::filesystem::temp_directory_path() /
                        ("ccbuild_test_err_" + std::to_string(::getpid()) + ".txt");
  const std::string full = "cd '" + std::string(CCBUILD_SOURCE_DIR) + "' && " + command + " 2> '" +
                           err_path.string() + "'";
  CommandResult result;
  FILE* pipe = ::popen(full.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  std::stringstream text;
  text << err.rdbuf();
  result.err = text.str();
  std::filesystem::remove(err_path);
  return result;
}

/// Runs `ccbuild ARGS`.
inline CommandResult run_ccbuild(const std::string& args) {
  return run_shell(ccbuild_binary() + " " + args);
}

}  // namespace ccbuild::testing
