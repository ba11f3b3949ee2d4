#pragma once
// The outcome of a planning call, as a value: it converts to true when a plan was found
// and prints itself with its reason ("collision: nozzles 1 and 2 collide at t = 12.5 s").
// "No plan" is an answer the caller reports (exit code 1), not an exception.

#include <string>

#include "ccbuild/common/status.hpp"

namespace ccbuild::planner {

enum class PlanCode {
  kSolved,           ///< a plan was found and passed every check
  kCollision,        ///< the method's paths collide and it found no way round
  kNotApplicable,    ///< the method does not apply to this layer (e.g. sections too narrow)
  kSearchExhausted,  ///< the method's search budget ran out before it found a plan
  kTimeLimit,        ///< the time limit came before a plan
  kCancelled,        ///< the caller's cancel flag was raised before a plan
};

/// "solved", "collision", "not-applicable", "search-exhausted", "time-limit", "cancelled".
std::string to_string(PlanCode code);

/// PlanStatus() is solved; PlanStatus::Code is PlanCode.
using PlanStatus = Status<PlanCode, PlanCode::kSolved, &to_string>;

}  // namespace ccbuild::planner
