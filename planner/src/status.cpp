#include "ccbuild/planner/status.hpp"

namespace ccbuild::planner {

std::string to_string(PlanStatus::Code code) {
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

std::string PlanStatus::to_string() const {
  const std::string name = planner::to_string(code_);
  return reason_.empty() ? name : name + ": " + reason_;
}

}  // namespace ccbuild::planner
