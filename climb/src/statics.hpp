#pragma once
// The statics of a climb's transfers: where each unit's pin goes, the gantry as the
// counterweight, and the order of the units that keeps the platform most stable. Shared
// by plan_climb (before it plans the motions) and by fitting a machine (which needs only
// the statics). Internal to climb/.

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"

namespace ccbuild::climb::detail {

/// A unit's pin engaged in (or withdrawn from) an anchor: where its foot is, and how far
/// the pin is out.
struct PinTarget {
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();
  double engaged_m = 0.0;
};
PinTarget target(const machine::ClimbingMachine& m, const Anchor& a);

/// The machine standing at `from`: the gantry in the middle of its rails with its nozzle
/// raised (parked), every unit's pin in its pipe. Empty when a unit cannot reach its pipe.
std::vector<double> parked_on(const machine::ClimbingMachine& m, const ClimbStage& from);

class Transfers {
 public:
  /// `q`: the machine parked at `from` (the units in its pipes).
  Transfers(const machine::ClimbingMachine& m, const ClimbStage& from, const ClimbStage& to,
            const Eigen::Isometry3d& platform, const std::vector<double>& q);

  struct Counterweight {
    double x = 0.0, y = 0.0, margin = -std::numeric_limits<double>::infinity();
  };
  /// The best place for the gantry while `group` moves, the units in `moved` already in
  /// their new pipes, from the configuration `q`: the most stable at either end of the
  /// group's motion (margin: the centre of mass inside the holding pins' hull, m).
  Counterweight counterweight(const std::vector<int>& group, const std::vector<char>& moved,
                              const std::vector<double>& q, double x0, double y0) const;

  std::string unreachable;  ///< why a unit cannot reach its new pipe ("" when all can)
  /// Each unit's pose: pin withdrawn from the old pipe, facing the new one withdrawn and
  /// engaged, and where it stands now.
  std::vector<machine::UnitPose> out_old, out_new, in_new, in_old;
  std::vector<int> order;    ///< the units, in the order they transfer
  bool every_order = false;  ///< every order was tried (else one unit at a time, greedily)
  /// The least stable transfer of `order`, the gantry placed best for each (m; below the
  /// profile's stability margin means the climb is unstable).
  double least_margin_m = -std::numeric_limits<double>::infinity();

 private:
  const machine::ClimbingMachine& m_;
  const ClimbStage& from_;
  const ClimbStage& to_;
  Eigen::Isometry3d platform_;
  double mass_x_ = 0.0, mass_y_ = 0.0;
};

}  // namespace ccbuild::climb::detail
