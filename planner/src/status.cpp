#include "ccbuild/planner/status.hpp"

namespace ccbuild::planner {

std::string to_string(PlanCode code) {
  switch (code) {
    case PlanStatus::Code::kSolved:
      return "solved";
    case PlanStatus::Code::kCollision:
      return "collision";
    case PlanStatus::Code::kNotApplicable:
      return "not-applicable";
    case PlanStatus::Code::kSearchExhausted:
      return "search-exhausted";
    case PlanStatus::Code::kTimeLimit:
      return "time-limit";
    case PlanStatus::Code::kCancelled:
      return "cancelled";
  }
  return "?";
}

}  // namespace ccbuild::planner
