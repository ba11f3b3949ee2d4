#pragma once
// The only place that sees urdfdom's types: reads the joints ccbuild needs from a URDF.

#include <string>
#include <vector>

namespace ccbuild::machine {

struct JointInfo {
  std::string name;
  std::string type;  ///< "prismatic", "revolute", "continuous", "fixed", ...
  double axis[3] = {0.0, 0.0, 0.0};
  bool has_limits = false;
  double lower = 0.0;  ///< m or rad
  double upper = 0.0;
  double velocity = 0.0;  ///< m/s or rad/s
};

struct UrdfInfo {
  std::string robot_name;
  std::vector<JointInfo> joints;
  const JointInfo* find(const std::string& name) const;
};

/// Parses a URDF file with urdfdom. Throws InputError naming the file, with urdfdom's own
/// complaint, when it is missing or not a valid URDF.
UrdfInfo read_urdf(const std::string& path);

}  // namespace ccbuild::machine
