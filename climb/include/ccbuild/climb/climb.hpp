#pragma once
// Climbing the building being printed (paper 000 §7). The platform prints the layers
// within its nozzle's reach, then climbs: its units move their pins, one at a time, to
// pipes cast through the walls a few layers earlier, and their legs lift the platform to
// the next stage. climb_stages() says where the platform stands and which pipes each
// stage needs; plan_climb() plans one climb's motions with OMPL against the walls built
// so far (FCL), keeping the machine within its joint limits and statically stable.
// SI units: m, s, rad.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "ccbuild/common/status.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/machine/climbing_machine.hpp"

namespace ccbuild::climb {

enum class ClimbCode {
  kFeasible,
  kNoAnchor,   ///< no pipe a unit can reach at a level the legs allow
  kBlocked,    ///< no collision-free motion found within the phase's budget
  kUnstable,   ///< the centre of mass cannot stay inside the holding units' polygon
  kTimeLimit,  ///< the planning time ran out
  kTooLarge,   ///< the building is larger than the machine family's largest platform
};
/// "feasible", "no-anchor", "blocked", "unstable", "time-limit", "too-large".
std::string to_string(ClimbCode code);

/// The outcome of a climbing question, as a value: true when feasible, and it says why
/// not. ClimbStatus::Code is ClimbCode.
using ClimbStatus = Status<ClimbCode, ClimbCode::kFeasible, &to_string>;

/// A pipe cast horizontally through a wall; a unit's pin goes into it.
struct Anchor {
  std::string id;  ///< the building file's, or "U2-f3" when placed by the default rule
  int unit = 0;
  int floor = -1;            ///< -1: in the foundation
  std::int64_t wall_id = 0;  ///< 0 in the foundation
  int layer = -1;            ///< cast after this layer of its floor (between it and the next)
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< on the wall's centre line
  Eigen::Vector2d outward = Eigen::Vector2d::Zero();   ///< the wall's normal, towards the unit
  double wall_thickness_m = 0.0;
  bool by_default_rule = false;
};

/// Where a layer is: floor and layer within it, from 0.
struct LayerRef {
  int floor = 0;
  int layer = 0;
};

/// One position of the platform and what is printed from it.
struct ClimbStage {
  int index = 0;
  double platform_z_m = 0.0;    ///< the platform's frame (see the machine's URDF)
  LayerRef first, last;         ///< layers printed from here, inclusive
  double top_m = 0.0;           ///< the last printed layer's top
  std::vector<Anchor> anchors;  ///< the units' pins while printing, one per unit
};

struct StagePlan {
  ClimbStatus status;
  std::vector<ClimbStage> stages;  ///< those that could be placed (all when feasible)
};

/// The stages of a building on a climbing machine: each platform position as high as
/// the legs allow and the next layer still in the nozzle's reach (between floors unless
/// the building asks for climbs within a storey, Building::climbs_within_storey); each
/// stage's pipes as low as the legs allow (so they cure while printing goes on), on the
/// building's anchor points, or where it has none by the default rule (docs/formats.md).
/// Throws nothing for a valid building: a stage without a reachable anchor is an answer
/// (kNoAnchor) naming the unit, the stage, the nearest solid wall and what would reach it.
StagePlan climb_stages(const floors::Building& building, const machine::ClimbingMachine& machine);

struct ClimbOptions {
  std::uint64_t seed = 1;      ///< the same seed and inputs give the same paths
  double time_limit_s = 10.0;  ///< for the whole climb's planning
};

/// One motion of a climb: what moves, its path, its timing.
struct ClimbPhase {
  enum class Kind { kPark, kBalance, kRelease, kTransit, kInsert, kLift };
  Kind kind = Kind::kPark;
  int unit = -1;                          ///< the unit moved (balance: the unit about to move)
  std::vector<std::string> joints;        ///< what moves: URDF joint names, or platform_x/y/z
  std::vector<std::vector<double>> path;  ///< values of `joints` at each waypoint
  std::vector<double> t_s;                ///< time of each waypoint from the phase's start
  double duration_s = 0.0;
  double min_clearance_m = 0.0;  ///< nearest approach of a moving link to a wall
  double planning_s = 0.0;
  int strokes = 0;  ///< lift only: the cylinder strokes it takes
  /// Lift only: the units' joints that follow the pins (swing, reach, wrist, stroke of
  /// each unit) and their values at each waypoint of `path`.
  std::vector<std::string> following_joints;
  std::vector<std::vector<double>> following;
};
std::string to_string(ClimbPhase::Kind kind);

struct ClimbPlan {
  ClimbStatus status;
  int from_stage = 0;
  int to_stage = 0;
  std::vector<ClimbPhase> phases;  ///< in order (up to the failing one when infeasible)
  double duration_s = 0.0;
  double planning_s = 0.0;
  double min_clearance_m = 0.0;
};

/// Plans the climb from `from` to `to` (consecutive stages of climb_stages), the walls
/// built up to `from.last`: park the gantry, then for each unit (units_per_transfer at a
/// time) move the gantry to balance the platform, release the pin, move to the new pipe,
/// insert the pin; then lift the platform. Every motion is planned by OMPL (RRTConnect)
/// in the joint space of what moves, valid when within the URDF's limits, free of
/// collision with the walls and the machine itself (FCL), and statically stable; each
/// returned path is re-checked at four times the planner's resolution. Durations come
/// from the paths and the joints' velocity limits, pin times and the loaded stroke speed.
ClimbPlan plan_climb(const machine::ClimbingMachine& machine, const floors::Building& building,
                     const ClimbStage& from, const ClimbStage& to,
                     const ClimbOptions& options = {});

/// Re-checks a planned climb independently of its planner: every phase's path walked at
/// steps of at most `step_m` metres and `step_rad` radians per joint, each state within the
/// joints' limits (the strokes by their end margin), free of collision with the walls and
/// the machine, and stable. Returns the first problem.
ClimbStatus verify_climb(const machine::ClimbingMachine& machine, const floors::Building& building,
                         const ClimbStage& from, const ClimbStage& to, const ClimbPlan& plan,
                         double step_m = 0.005, double step_rad = 0.005);

}  // namespace ccbuild::climb
