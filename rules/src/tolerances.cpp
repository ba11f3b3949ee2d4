#include "ccbuild/rules/tolerances.hpp"

#include <cmath>

namespace ccbuild::rules {

bool faster_than(double delta, double dt_s, double limit, double rounding) {
  return std::abs(delta) - rounding > limit * (dt_s + rounding) * (1.0 + 1e-9);
}

}  // namespace ccbuild::rules
