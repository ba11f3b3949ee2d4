#pragma once
// The only place that sees urdfdom's types: reads a URDF into ccbuild's own description
// of a robot (joints, links with their collision shapes and masses, the tree), in SI
// units and Eigen poses.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace ccbuild::machine {

struct JointInfo {
  std::string name;
  int line = 0;      ///< of its <joint> element in the file, 1-based; 0 when unknown
  std::string type;  ///< "prismatic", "revolute", "continuous", "fixed", ...
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  ///< in the joint's frame
  bool has_limits = false;
  double lower = 0.0;  ///< m or rad
  double upper = 0.0;
  double velocity = 0.0;  ///< m/s or rad/s
  std::string parent_link;
  std::string child_link;
  /// The joint's frame in its parent link's frame (URDF <origin>).
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

/// A collision primitive of a link, in the link's frame.
struct CollisionShape {
  enum class Kind { kBox, kCylinder, kSphere };
  Kind kind = Kind::kBox;
  /// Box: its three edge lengths; cylinder: radius, length along its z axis, 0; sphere:
  /// radius, 0, 0 (m).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

struct LinkInfo {
  std::string name;
  int line = 0;  ///< of its <link> element in the file, 1-based; 0 when unknown
  std::vector<CollisionShape> collisions;
  int mesh_collisions = 0;  ///< collision meshes, which ccbuild does not check against
  double mass_kg = 0.0;     ///< 0 when the link has no <inertial>
  Eigen::Vector3d centre_of_mass_m = Eigen::Vector3d::Zero();  ///< in the link's frame
};

struct UrdfInfo {
  std::string robot_name;
  std::string source_file;
  std::string root_link;
  std::vector<JointInfo> joints;
  std::vector<LinkInfo> links;
  const JointInfo* find(const std::string& name) const;
};

/// Parses a URDF file with urdfdom. Throws InputError naming the file, with urdfdom's own
/// complaint, when it is missing, not a valid URDF, or nested too deep to parse safely.
UrdfInfo read_urdf(const std::string& path);
/// The same for a URDF held in memory; `path` names it in messages.
UrdfInfo read_urdf_text(const std::string& xml, const std::string& path);

}  // namespace ccbuild::machine
