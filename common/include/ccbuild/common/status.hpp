#pragma once
// The outcome of a question whose "no" is an answer, not an error (like OMPL's
// PlannerStatus): a code, true only for the one that means yes, and why not. Each library
// names its codes (planner::PlanStatus, climb::ClimbStatus); the caller reports a "no"
// with exit code 1.

#include <string>
#include <utility>

namespace ccbuild {

/// `CodeT` the library's codes, `kYes` the one that converts to true, `kName` the code's
/// name as the JSON and the messages say it.
template <typename CodeT, CodeT kYes, std::string (*kName)(CodeT)>
class Status {
 public:
  using Code = CodeT;

  /// Yes.
  Status() = default;
  Status(Code code, std::string reason) : code_(code), reason_(std::move(reason)) {}

  explicit operator bool() const { return code_ == kYes; }
  Code code() const { return code_; }
  /// Why not (empty for yes).
  const std::string& reason() const { return reason_; }
  /// The code's name, and the reason after a colon when there is one.
  std::string to_string() const {
    const std::string name = kName(code_);
    return reason_.empty() ? name : name + ": " + reason_;
  }

 private:
  Code code_ = kYes;
  std::string reason_;
};

}  // namespace ccbuild
