#include "ccbuild/rules/weather.hpp"

namespace ccbuild::rules {

bool placeable_at(double temperature_c, double min_c, double max_c) {
  return temperature_c >= min_c - 1e-9 && temperature_c <= max_c + 1e-9;
}

bool climbable_in(double wind_m_s, double limit_m_s) {
  return wind_m_s <= limit_m_s + 1e-9;
}

}  // namespace ccbuild::rules
