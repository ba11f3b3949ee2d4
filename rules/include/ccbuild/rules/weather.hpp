#pragma once
// The weather rules of printing and climbing, stated once for the scheduler and the
// schedule's re-checks.

namespace ccbuild::rules {

/// Whether concrete may be placed at an air temperature of `temperature_c`, °C: within the
/// mix's placing range [min_c, max_c], both ends included (to 1e-9 °C). The mix states
/// the range (EN 206 leaves it to the specification; ACI 305R and 306R take 35 °C and
/// 5 °C, the bundled mix's defaults).
bool placeable_at(double temperature_c, double min_c, double max_c);

/// Whether a climb may run in a wind of `wind_m_s`, m/s: up to the climbing machine's
/// limit `limit_m_s`, the limit included (to 1e-9 m/s).
bool climbable_in(double wind_m_s, double limit_m_s);

}  // namespace ccbuild::rules
