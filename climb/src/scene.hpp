#pragma once
// The world a climb happens in: the walls built so far as boxes, the machine's links as
// FCL shapes, and the validity of a configuration (joint limits, collision with the
// walls and with itself, statics). Internal to climb/.

#include <fcl/fcl.h>

#include <functional>

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"

namespace ccbuild::climb::detail {

/// A wall piece built so far: a box along a-b, its thickness, between two heights.
struct WallBox {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  double thickness_m = 0.0;
  double z_bottom_m = 0.0, z_top_m = 0.0;
  std::int64_t wall_id = 0;
  int floor = 0;
};

/// The walls of every layer up to and including `last` (consecutive layers of one
/// geometry make one box per piece); pieces without a thickness get `default_thickness_m`.
std::vector<WallBox> walls_built(const floors::Building& building, LayerRef last,
                                 double default_thickness_m);

/// Why a configuration is not valid, in words ("" when it is).
struct Verdict {
  bool ok = true;
  std::string why;
  /// What refused it, to group refusals by: "wall 5 of floor 0", "the machine's link u2_boom",
  /// "the stability margin"; empty when `why` says it all.
  std::string obstacle;
  bool unstable = false;  ///< refused by statics, not by a contact or a limit

  static Verdict refused(std::string why, std::string obstacle = "", bool unstable = false) {
    return {false, std::move(why), std::move(obstacle), unstable};
  }
  /// The same refusal, its words put in context ("lift: " + why).
  Verdict within(const std::string& context) const {
    Verdict out = *this;
    out.why = context + why;
    return out;
  }
};

/// Collision and statics checks of the machine among the walls. Not thread-safe (it
/// reuses its FCL objects); use one per thread.
class Scene {
 public:
  /// `pipes`: the anchors whose holes a pin may enter (a pin aligned with one may pass
  /// through that wall).
  Scene(const machine::ClimbingMachine& machine, std::vector<WallBox> walls,
        std::vector<Anchor> pipes);
  ~Scene();

  const machine::ClimbingMachine& machine() const { return machine_; }
  const std::vector<WallBox>& walls() const { return walls_; }

  /// The links in `moving` (robot link indices) against the walls, those in
  /// `self_moving` against the links of the other assemblies (platform, gantry, each unit);
  /// then, when `support` has points, the centre of mass at least the stability margin
  /// inside their convex hull.
  Verdict check(const std::vector<double>& q, const Eigen::Isometry3d& platform,
                const std::vector<int>& moving, const std::vector<int>& self_moving,
                const std::vector<Eigen::Vector2d>& support) const;
  /// The smallest distance from a link in `moving` to a wall, m.
  double clearance(const std::vector<double>& q, const Eigen::Isometry3d& platform,
                   const std::vector<int>& moving) const;

  /// "wall 17 of floor 1" for a wall box.
  std::string describe_wall(int box) const;
  std::string describe_link(int link) const;

 private:
  // A link's collision shape as an FCL object, created once and moved to each pose
  // checked (hence not thread-safe).
  struct Shape {
    std::unique_ptr<fcl::CollisionObjectd> object;
    Eigen::Isometry3d origin;
  };
  bool pin_in_pipe(int link, const Eigen::Isometry3d& pose, int box) const;
  /// Moves `link`'s shapes to `pose` (world).
  void place(int link, const Eigen::Isometry3d& pose) const;

  const machine::ClimbingMachine& machine_;
  std::vector<WallBox> walls_;
  std::vector<Anchor> pipes_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> wall_objects_;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager_;
  std::vector<std::vector<Shape>> link_shapes_;
  std::vector<int> assembly_;       ///< per link: 0 platform, 1 gantry, 2 + u unit u
  std::vector<int> pin_link_unit_;  ///< per link: the unit whose pin it is, -1 otherwise
};

/// Signed distance from `p` to the boundary of the convex hull of `points`: positive
/// inside. Fewer than three points: -infinity.
double inside_hull_m(const Eigen::Vector2d& p, std::vector<Eigen::Vector2d> points);

}  // namespace ccbuild::climb::detail
