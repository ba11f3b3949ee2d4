#include "ccbuild/machine/gantry_yard.hpp"

#include <algorithm>
#include <cmath>

namespace ccbuild::machine {

double straight_move_s(const AxisSpeeds& speeds, const GantryPose& a, const GantryPose& b) {
  const double limit[4] = {speeds.x_m_s, speeds.y_m_s, speeds.z_m_s, speeds.rotation_rad_s};
  double t_s = 0.0;
  for (int k = 0; k < 4; ++k)
    if (limit[k] > 0.0) t_s = std::max(t_s, std::abs(b[k] - a[k]) / limit[k]);
  return t_s;
}

GantryYard::GantryYard(AxisSpeeds speeds, RailAxis rail_axis, double rail_max_m, int gantries,
                       double gantry_width_m)
    : speeds_(speeds),
      rail_axis_(rail_axis),
      rail_max_m_(rail_max_m),
      gantries_(std::max(1, gantries)),
      gantry_width_m_(gantry_width_m) {}

GantryPose GantryYard::park_of(int nozzle, const GantryPose& at) const {
  GantryPose park = at;
  park[rail_axis_ == RailAxis::kY ? 1 : 0] =
      rail_max_m_ - (gantries_ - 1 - nozzle) * gantry_width_m_;
  return park;
}

void GantryYard::moves_before(const std::vector<std::optional<GantryPose>>& starts,
                              std::vector<GantryMove>& parks,
                              std::vector<GantryMove>& to_starts) const {
  parks.clear();
  to_starts.clear();
  const auto works = [&](int n) {
    return n < static_cast<int>(starts.size()) && starts[n].has_value();
  };
  for (const auto& [nozzle, at] : where_) {
    if (works(nozzle) || parked_.count(nozzle)) continue;
    const GantryPose park = park_of(nozzle, at);
    parks.push_back({nozzle, at, park, straight_move_s(speeds_, at, park)});
  }
  for (int n = 0; n < static_cast<int>(starts.size()); ++n) {
    if (!works(n)) continue;
    const auto from = where_.find(n);
    if (from == where_.end()) continue;
    to_starts.push_back(
        {n, from->second, *starts[n], straight_move_s(speeds_, from->second, *starts[n])});
  }
}

double GantryYard::longest_move_before_s(
    const std::vector<std::optional<GantryPose>>& starts) const {
  std::vector<GantryMove> parks, to_starts;
  moves_before(starts, parks, to_starts);
  double longest_s = 0.0;
  for (const auto* moves : {&parks, &to_starts})
    for (const GantryMove& m : *moves) longest_s = std::max(longest_s, m.duration_s);
  return longest_s;
}

void GantryYard::finish_layer(const std::vector<std::optional<GantryPose>>& ends) {
  const auto works = [&](int n) {
    return n < static_cast<int>(ends.size()) && ends[n].has_value();
  };
  for (auto& [nozzle, at] : where_)
    if (!works(nozzle) && !parked_.count(nozzle)) {
      at = park_of(nozzle, at);
      parked_.insert(nozzle);
    }
  for (int n = 0; n < static_cast<int>(ends.size()); ++n)
    if (works(n)) {
      where_[n] = *ends[n];
      parked_.erase(n);
    }
}

}  // namespace ccbuild::machine
