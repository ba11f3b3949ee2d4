#include "ccbuild/common/input_error.hpp"

namespace ccbuild {
namespace {
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
