#include "ccbuild/common/input_error.hpp"

#include "ccbuild/common/format.hpp"

namespace ccbuild {
namespace {

/// The longest message and field an error shows: a hostile file can hold one value of
/// megabytes. (How many it lists: limits::kMaxListed.)
constexpr std::size_t kLongestMessage = 2000, kLongestField = 200;

/// The line that counts the problems past the first limits::kMaxListed.
Diagnostic more_problems(const std::string& file, std::size_t more) {
  return {file, 0, "",
          "and " + std::to_string(more) + " more problems (the first " +
              std::to_string(limits::kMaxListed) + " are listed above)"};
}

std::vector<Diagnostic> bounded(std::vector<Diagnostic> diagnostics) {
  // A DiagnosticSink's list already ends with its count (kMaxListed + 1 in all).
  if (diagnostics.size() > limits::kMaxListed + 1) {
    const std::size_t more = diagnostics.size() - limits::kMaxListed;
    diagnostics.resize(limits::kMaxListed);
    diagnostics.push_back(more_problems(diagnostics.front().file, more));
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
  listed.push_back(more_problems(diagnostics_.front().file, more_));
  throw InputError(std::move(listed));
}

namespace detail {
void check_failed(const char* condition, const char* file, int line, const std::string& message) {
  throw InternalError("internal check failed at " + std::string(file) + ":" + std::to_string(line) +
                      ": " + message + " (" + condition + ")");
}
}  // namespace detail

}  // namespace ccbuild
