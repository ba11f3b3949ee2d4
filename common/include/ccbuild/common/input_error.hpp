#pragma once
// The one exception type for bad user input (a file, a flag, a message). It carries
// where the problem is (file, line, field path) and what was expected, so the CLI can
// print it and exit with code 2. Programmer errors use CCBUILD_CHECK instead, which
// throws InternalError (the CLI prints it and exits with code 3).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "ccbuild/common/limits.hpp"

namespace ccbuild {

/// One finding about user input. `line` is 1-based, 0 when unknown; `field` is a path
/// such as `floors[1].openings[0].sill` (empty when the whole file is at fault).
struct Diagnostic {
  std::string file;
  int line = 0;
  std::string field;
  std::string message;

  /// "file:line: field: message", leaving out what is unknown.
  std::string to_string() const;
};

/// Bad user input. Holds one or more diagnostics; what() lists them one per line. At most
/// limits::kMaxListed are kept (one more line says how many others), each message cut to
/// 2,000 characters.
class InputError : public std::runtime_error {
 public:
  explicit InputError(Diagnostic diagnostic);
  explicit InputError(std::vector<Diagnostic> diagnostics);
  InputError(std::string file, int line, std::string field, std::string message);

  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  const Diagnostic& first() const { return diagnostics_.front(); }

 private:
  InputError(std::vector<Diagnostic> bounded_diagnostics, int);
  std::vector<Diagnostic> diagnostics_;
};

/// Collects diagnostics during a validation pass, then throws them together: the first
/// limits::kMaxListed, and one more saying how many others there were.
class DiagnosticSink {
 public:
  void add(Diagnostic diagnostic) {
    if (diagnostics_.size() < limits::kMaxListed)
      diagnostics_.push_back(std::move(diagnostic));
    else
      ++more_;
  }
  bool empty() const { return diagnostics_.empty(); }
  /// Throws InputError with everything collected; does nothing when empty.
  void throw_if_any() const;

 private:
  std::vector<Diagnostic> diagnostics_;
  std::size_t more_ = 0;  ///< added past the limit, counted only
};

/// A broken invariant: a bug in ccbuild, never the user's input. Thrown by CCBUILD_CHECK.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] void check_failed(const char* condition, const char* file, int line,
                               const std::string& message);
}  // namespace detail

}  // namespace ccbuild

/// Always-on invariant check (also in Release): throws ccbuild::InternalError naming the
/// source line and the condition. For programmer errors only; bad user input throws
/// ccbuild::InputError.
#define CCBUILD_CHECK(condition, message)                                                         \
  do {                                                                                            \
    if (!(condition)) ::ccbuild::detail::check_failed(#condition, __FILE__, __LINE__, (message)); \
  } while (false)
