#pragma once
// Where each gantry of a machine stands between layers, and the moves that take it to the
// next layer's start: one rule for the scheduler (a layer's move time) and the dispatcher
// (the travel and park jobs it sends).

#include <array>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "ccbuild/machine/machine_model.hpp"

namespace ccbuild::machine {

/// A gantry's pose: layout x and y (m), nozzle height z (m), cumulative heading (rad).
using GantryPose = std::array<double, 4>;

/// The velocity limits of the four axes a straight move drives, m/s and rad/s.
struct AxisSpeeds {
  double x_m_s = 0.0, y_m_s = 0.0, z_m_s = 0.0, rotation_rad_s = 0.0;
};

/// Time of a straight move from `a` to `b` with every axis within its velocity limit: as
/// long as the slowest axis needs, s. An axis without a positive limit is not counted.
double straight_move_s(const AxisSpeeds& speeds, const GantryPose& a, const GantryPose& b);

/// One gantry's move before a layer.
struct GantryMove {
  int nozzle = 0;  ///< 0-based
  GantryPose from{}, to{};
  double duration_s = 0.0;  ///< straight_move_s, s
};

/// The gantries of one machine on common rails, each where its last move or path ended.
/// A gantry idle in a layer first parks at the far end of the rails (each a gantry width
/// from the next), so that a plan on fewer nozzles has them out of its way. A gantry that
/// has not moved yet stands nowhere and needs no move.
class GantryYard {
 public:
  /// `rail_max_m`: the rail axis's upper travel limit; `gantries`: how many there are.
  GantryYard(AxisSpeeds speeds, RailAxis rail_axis, double rail_max_m, int gantries,
             double gantry_width_m);

  /// Where gantry `nozzle` parks from `at`: only its rail coordinate changes.
  GantryPose park_of(int nozzle, const GantryPose& at) const;

  /// The moves before a layer whose gantries start at `starts` (index: nozzle; none: idle
  /// in it): the idle ones not parked yet to their parks (`parks`, in nozzle order), the
  /// working ones that stand somewhere to their starts (`to_starts`, in nozzle order).
  void moves_before(const std::vector<std::optional<GantryPose>>& starts,
                    std::vector<GantryMove>& parks, std::vector<GantryMove>& to_starts) const;

  /// The longest of the moves before such a layer, s (0 when none).
  double longest_move_before_s(const std::vector<std::optional<GantryPose>>& starts) const;

  /// The layer is done: the idle gantries stand at their parks, the working ones where
  /// their paths ended (`ends`, index: nozzle; none: idle).
  void finish_layer(const std::vector<std::optional<GantryPose>>& ends);

 private:
  AxisSpeeds speeds_;
  RailAxis rail_axis_;
  double rail_max_m_;
  int gantries_;
  double gantry_width_m_;
  std::map<int, GantryPose> where_;
  std::set<int> parked_;
};

}  // namespace ccbuild::machine
