#include "ccbuild/common/input_error.hpp"

#include "ccbuild/common/format.hpp"

namespace ccbuild {
namespace {

/// The most diagnostics one error lists, and the longest message and field it shows: a
/// hostile file can hold millions of mistakes, or one value of megabytes.
constexpr std::size_t kMostDiagnostics = 25;
constexpr std::size_t kLongestMessage = 2000, kLongestField = 200;

std::vector<Diagnostic> bounded(std::vector<Diagnostic> diagnostics) {
  if (diagnostics.size() > kMostDiagnostics) {
    const std::size_t more = diagnostics.size() - (kMostDiagnostics - 1);
    diagnostics.resize(kMostDiagnostics - 1);
    diagnostics.push_back({diagnostics.front().file, 0, "",
                           "and " + std::to_string(more) + " more problems (fix these first)"});
  }
  for (auto& d : diagnostics) {
    if (d.message.size() > kLongestMessage) d.message = echoed(d.message, kLongestMessage);
    if (d.field.size() > kLongestField) d.field = echoed(d.field, kLongestField);
    if (d.file.size() > kLongestField) d.file = echoed(d.file, kLongestField);
  }
  return diagnostics;
}
std::string join(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const auto& d : diagnostics) {
    if (!text.empty()) text += '\n';
    text += d.to_string();
  }
  return text;
}
}  // namespace

std::string Diagnostic::to_string() const {
  std::string text;
  if (!file.empty()) {
    text.append(file);
    if (line > 0) text.append(":").append(std::to_string(line));
    text.append(": ");
  }
  if (!field.empty()) text.append(field).append(": ");
  text.append(message);
  return text;
}

InputError::InputError(Diagnostic diagnostic)
    : InputError(std::vector<Diagnostic>{std::move(diagnostic)}) {}

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : InputError(bounded(std::move(diagnostics)), 0) {}

InputError::InputError(std::vector<Diagnostic> diagnostics, int)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {
  if (diagnostics_.empty()) diagnostics_.push_back({});
}

InputError::InputError(std::string file, int line, std::string field, std::string message)
    : InputError(Diagnostic{std::move(file), line, std::move(field), std::move(message)}) {}

void DiagnosticSink::throw_if_any() const {
  if (diagnostics_.empty()) return;
  if (more_ == 0) throw InputError(diagnostics_);
  std::vector<Diagnostic> listed = diagnostics_;
  listed.push_back({diagnostics_.front().file, 0, "",
                    "and " + std::to_string(more_) + " more problems (the first " +
                        std::to_string(diagnostics_.size()) + " are listed above)"});
  throw InputError(std::move(listed));
}

namespace detail {
void check_failed(const char* condition, const char* file, int line, const std::string& message) {
  throw InternalError("internal check failed at " + std::string(file) + ":" + std::to_string(line) +
                      ": " + message + " (" + condition + ")");
}
}  // namespace detail

}  // namespace ccbuild
