#include "ccbuild/machine/kinematics.hpp"

#include <algorithm>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::machine {

Kinematics::Kinematics(UrdfInfo urdf) : urdf_(std::move(urdf)) {
  const int links = link_count();
  parent_joint_.assign(links, -1);
  parent_link_.assign(links, -1);
  for (int j = 0; j < joint_count(); ++j) {
    const JointInfo& joint = urdf_.joints[j];
    const int parent = link(joint.parent_link), child = link(joint.child_link);
    if (parent < 0 || child < 0)
      throw InputError(
          urdf_.source_file, joint.line, "joint[" + joint.name + "]",
          "links '" + joint.parent_link + "' or '" + joint.child_link + "' are not in the URDF");
    parent_joint_[child] = j;
    parent_link_[child] = parent;
  }
  root_ = link(urdf_.root_link);
  if (root_ < 0) throw InputError(urdf_.source_file, 0, "", "the URDF has no root link");
  // Parents before children: a breadth-first walk from the root.
  order_ = {root_};
  for (std::size_t k = 0; k < order_.size(); ++k)
    for (int l = 0; l < links; ++l)
      if (parent_link_[l] == order_[k]) order_.push_back(l);
  if (static_cast<int>(order_.size()) != links)
    throw InputError(urdf_.source_file, 0, "",
                     "some links are not connected to the root link '" + urdf_.root_link + "'");
  for (const auto& l : urdf_.links) total_mass_kg_ += l.mass_kg;
}

int Kinematics::link(const std::string& name) const {
  for (int l = 0; l < link_count(); ++l)
    if (urdf_.links[l].name == name) return l;
  return -1;
}

int Kinematics::joint(const std::string& name) const {
  for (int j = 0; j < joint_count(); ++j)
    if (urdf_.joints[j].name == name) return j;
  return -1;
}

bool Kinematics::is_ancestor(int ancestor, int link) const {
  for (int l = link; l >= 0; l = parent_link_[l])
    if (l == ancestor) return true;
  return false;
}

std::vector<Eigen::Isometry3d> Kinematics::link_poses(const Eigen::Isometry3d& base,
                                                      const std::vector<double>& q) const {
  CCBUILD_CHECK(q.size() == urdf_.joints.size(), "a value for every joint");
  std::vector<Eigen::Isometry3d> poses(link_count(), Eigen::Isometry3d::Identity());
  for (int l : order_) {
    const int j = parent_joint_[l];
    if (j < 0) {
      poses[l] = base;
      continue;
    }
    const JointInfo& joint = urdf_.joints[j];
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d axis =
        joint.axis.norm() > 0 ? joint.axis.normalized() : Eigen::Vector3d::UnitZ();
    if (joint.type == "prismatic")
      motion.translation() = axis * q[j];
    else if (joint.type == "revolute" || joint.type == "continuous")
      motion.linear() = Eigen::AngleAxisd(q[j], axis).toRotationMatrix();
    poses[l] = poses[parent_link_[l]] * joint.origin * motion;
  }
  return poses;
}

Eigen::Vector3d Kinematics::centre_of_mass(const std::vector<Eigen::Isometry3d>& poses) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int l = 0; l < link_count(); ++l)
    sum += urdf_.links[l].mass_kg * (poses[l] * urdf_.links[l].centre_of_mass_m);
  return total_mass_kg_ > 0 ? Eigen::Vector3d(sum / total_mass_kg_) : Eigen::Vector3d::Zero();
}

}  // namespace ccbuild::machine
