#pragma once
// The outcome of a planning call, as a value (like OMPL's PlannerStatus): it converts to
// true when a plan was found and prints itself with its reason. "No plan" is an answer
// the caller reports (exit code 1), not an exception.

#include <string>
#include <utility>

namespace ccbuild::planner {

class PlanStatus {
 public:
  enum class Code {
    kSolved,           ///< a plan was found and passed every check
    kCollision,        ///< the method's paths collide and it found no way round
    kNotApplicable,    ///< the method does not apply to this layer (e.g. sections too narrow)
    kSearchExhausted,  ///< the method's search budget ran out before it found a plan
    kTimeLimit,        ///< the time limit came before a plan
    kCancelled,        ///< the caller's cancel flag was raised before a plan
  };

  /// Solved.
  PlanStatus() = default;
  PlanStatus(Code code, std::string reason) : code_(code), reason_(std::move(reason)) {}
  static PlanStatus solved() { return {}; }

  explicit operator bool() const { return code_ == Code::kSolved; }
  Code code() const { return code_; }
  /// Why not (empty when solved): "nozzles 1 and 2 collide at t = 12.5 s (...)".
  const std::string& reason() const { return reason_; }
  /// "solved", or the code and the reason: "collision: nozzles 1 and 2 collide ...".
  std::string to_string() const;

 private:
  Code code_ = Code::kSolved;
  std::string reason_;
};

/// "solved", "collision", "not-applicable", "search-exhausted", "time-limit", "cancelled".
std::string to_string(PlanStatus::Code code);

}  // namespace ccbuild::planner
