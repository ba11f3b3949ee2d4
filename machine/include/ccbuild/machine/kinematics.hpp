#pragma once
// A robot's kinematic tree in ccbuild's own types: forward kinematics of every link,
// collision shapes and masses, from a URDF read by the adapter. Poses are Eigen
// isometries in metres; joint values are metres (prismatic) or radians (revolute).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "ccbuild/machine/urdf_adapter.hpp"

namespace ccbuild::machine {

class Kinematics {
 public:
  /// Orders the tree from its root. Throws InputError (naming the URDF) for a link
  /// without a parent other than the root, or a joint whose links are missing.
  explicit Kinematics(UrdfInfo urdf);

  const UrdfInfo& urdf() const { return urdf_; }
  int link_count() const { return static_cast<int>(urdf_.links.size()); }
  int joint_count() const { return static_cast<int>(urdf_.joints.size()); }
  /// Index of a link or joint by name, -1 when there is none.
  int link(const std::string& name) const;
  int joint(const std::string& name) const;
  const LinkInfo& link_info(int link) const { return urdf_.links[link]; }
  const JointInfo& joint_info(int joint) const { return urdf_.joints[joint]; }
  int root() const { return root_; }
  /// The joint whose child is `link` (-1 for the root) and the link above it.
  int parent_link(int link) const { return parent_link_[link]; }
  /// True when `ancestor` is `link` or lies on its path to the root.
  bool is_ancestor(int ancestor, int link) const;

  /// Joint values of every joint, all zero (fixed joints keep their zero).
  std::vector<double> zero() const { return std::vector<double>(urdf_.joints.size(), 0.0); }
  /// Every link's pose in the world, the root placed at `base`, each movable joint at
  /// `q[joint index]` (fixed joints ignore theirs).
  std::vector<Eigen::Isometry3d> link_poses(const Eigen::Isometry3d& base,
                                            const std::vector<double>& q) const;
  double total_mass_kg() const { return total_mass_kg_; }
  /// The centre of mass of the whole robot in the world, for poses from link_poses().
  Eigen::Vector3d centre_of_mass(const std::vector<Eigen::Isometry3d>& poses) const;

 private:
  UrdfInfo urdf_;
  int root_ = 0;
  std::vector<int> order_;  ///< links, parents before children
  std::vector<int> parent_joint_, parent_link_;
  double total_mass_kg_ = 0.0;
};

}  // namespace ccbuild::machine
