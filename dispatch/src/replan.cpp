#include "ccbuild/dispatch/replan.hpp"

#include <algorithm>
#include <cmath>

namespace ccbuild::dispatch {}  // namespace ccbuild::dispatch
