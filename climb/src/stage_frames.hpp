#pragma once
// The parts of stage placement that fitting a machine shares with climb_stages: where the
// platform stands (which depends only on the legs and the nozzle's reach, not on where the
// units hang), the layers each climb's pipes may go in, and whether a unit's pin reaches
// a point of solid wall. Internal to climb/.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::climb::detail {

struct GlobalLayer {
  int floor = 0;
  int layer = 0;
  double z_bottom_m = 0.0, z_top_m = 0.0;
};

/// A place a unit's pin could go: a point on a wall's centre line, and the wall.
struct Candidate {
  std::string id;
  std::int64_t wall_id = 0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();  ///< the wall's direction
  double thickness_m = 0.0;
  bool by_default_rule = false;
};

/// The building's anchor points solid in `layer`, or where it has none, points every 5 cm
/// along its solid wall (the default rule, docs/formats.md).
std::vector<Candidate> candidates(const floors::Floor& floor, const floors::Layer& layer,
                                  double default_thickness_m, double clearance_m);

/// Where a stage's pipes may go: a layer (global index) and the pipes' height in it.
struct AnchorLevel {
  int floor = -1;  ///< -1: the foundation
  int layer = 0;
  double z_m = 0.0;
  std::size_t global = 0;  ///< into StageFrames::layers (the foundation: 0)
};

/// One platform position: the stage without its anchors, and where they may go (lowest
/// first), reachable from `platform_zs` (the stage before and this one).
struct StageFrame {
  ClimbStage stage;
  std::vector<AnchorLevel> levels;
  std::vector<double> platform_zs;
  std::string no_level;  ///< why `levels` is empty (the legs leave no printed layer)
};

struct StageFrames {
  std::vector<GlobalLayer> layers;
  std::vector<std::vector<floors::Layer>> sliced;  ///< per floor
  std::vector<StageFrame> frames;  ///< every stage, stage 0 standing on the foundation
  ClimbStatus status;              ///< kNoAnchor when a stage reaches no layer
};

/// The stages' heights and layers for a machine whose units all have `machine`'s legs.
StageFrames stage_frames(const floors::Building& building, const machine::ClimbingMachine& machine);

/// The stages of `frames` (stage_frames of this building, for a machine whose legs and
/// reach are `machine`'s) with each unit's pipes chosen: climb_stages without slicing again.
StagePlan place_anchors(const floors::Building& building, const machine::ClimbingMachine& machine,
                        const StageFrames& frames);

/// True when unit `u`'s pin reaches `c` at height `anchor_z` with the platform (the
/// robot's root) at `platform`, within the joints' limits; `mount` is the unit's foot at
/// zero in plan, which picks the wall's side; `outward` is then the wall's normal towards
/// the unit.
bool pin_reaches(const machine::ClimbingMachine& machine, int u, const Eigen::Isometry3d& platform,
                 const Eigen::Vector2d& mount, const Candidate& c, double anchor_z,
                 Eigen::Vector2d& outward);

}  // namespace ccbuild::climb::detail
