#pragma once
// Helpers shared by the tests: fixture paths, expecting an InputError with a message,
// and running the ccbuild binary.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <unistd.h>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::testing {

inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(CCBUILD_SOURCE_DIR) / relative;
}

inline std::string data(const std::string& relative) {
  return (source_path("tests/data") / relative).string();
}

/// A file's whole content.
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// An empty folder of its own for one test: `prefix` and `name` with this process's id
/// (tests of one binary may run in parallel under CTest).
inline std::filesystem::path scratch_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("ccbuild_" + prefix + "_" + name + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `action`, expects an InputError, and returns it for further checks.
inline InputError expect_input_error(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError, none was thrown";
  return InputError("", 0, "", "");
}

/// True when `text` contains `part`; prints both otherwise.
inline ::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << part << "' not found in:\n" << text;
}

}  // namespace ccbuild::testing
