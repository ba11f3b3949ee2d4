#include "anchor_strength.hpp"

#include <algorithm>

namespace ccbuild::schedule::detail {

std::vector<ClimbEvent::StrengthPoint> youngest_anchor_strength(
    const ClimbEvent& climb, const floors::MaterialProfile& mix,
    const site::EquivalentAge* maturity) {
  std::vector<ClimbEvent::StrengthPoint> out;
  if (climb.anchors.empty()) return out;
  const auto youngest =
      std::min_element(climb.anchors.begin(), climb.anchors.end(),
                       [](const ClimbEvent::AnchorLoad& a, const ClimbEvent::AnchorLoad& b) {
                         return a.age_s < b.age_s;
                       });
  const double cast_s = climb.start_s - youngest->age_s;
  const int steps = kAnchorCurvePoints - 1;
  for (int k = 0; k <= steps; ++k) {
    // The last point is the climb's start itself, not cast_s + age_s rounded.
    const double t_s = k == steps ? climb.start_s : cast_s + youngest->age_s * k / steps;
    const double age_s = maturity ? maturity->age(cast_s, t_s) : t_s - cast_s;
    out.push_back({t_s, mix.strength_at_mpa(age_s)});
  }
  return out;
}

}  // namespace ccbuild::schedule::detail
