#include "ccbuild/machine/urdf_adapter.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <mutex>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/limits.hpp"

namespace ccbuild::machine {
namespace {

// urdfdom reports problems through console_bridge and returns null; catch the text so
// the user sees why, in our error, instead of a bare failure on stderr.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN && messages.size() < 3)
      messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::mutex parse_mutex;  // console_bridge's handler is process-global

constexpr std::size_t kMaxUrdfElements = 100'000;

// TinyXML, inside urdfdom, recurses once per level of nesting: a file nested deep enough
// overflows the stack before urdfdom can complain. Measure nesting (and count elements)
// first, skipping comments, CDATA, declarations and quoted attribute values.
// Also notes the line of each <link> and <joint> of the robot, for errors about them.
struct ElementLines {
  std::map<std::string, int> links, joints;
};

// The value of attribute `name` in an opening tag's text, or "".
std::string name_attribute(const std::string& tag) {
  for (std::size_t at = tag.find("name"); at != std::string::npos; at = tag.find("name", at + 4)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(tag[at - 1]))) continue;
    std::size_t k = at + 4;
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (k >= tag.size() || tag[k] != '=') continue;
    ++k;
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
    const std::size_t end = tag.find(tag[k], k + 1);
    if (end == std::string::npos) return "";
    return tag.substr(k + 1, end - k - 1);
  }
  return "";
}

ElementLines check_xml_shape(const std::string& xml, const std::string& path) {
  ElementLines lines;
  int depth = 0, line = 1;
  std::size_t elements = 0;
  auto skip_to = [&](std::size_t from, const char* end) {
    const std::size_t at = xml.find(end, from);
    const std::size_t stop = at == std::string::npos ? xml.size() : at + std::strlen(end);
    line += static_cast<int>(std::count(xml.begin() + from, xml.begin() + stop, '\n'));
    return stop;
  };
  for (std::size_t i = 0; i < xml.size();) {
    const char c = xml[i];
    if (c == '\n') ++line;
    if (c != '<') {
      ++i;
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      i = skip_to(i, "-->");
    } else if (xml.compare(i, 9, "<![CDATA[") == 0) {
      i = skip_to(i, "]]>");
    } else if (xml.compare(i, 2, "<?") == 0) {
      i = skip_to(i, "?>");
    } else if (xml.compare(i, 2, "<!") == 0) {
      i = skip_to(i, ">");
    } else if (xml.compare(i, 2, "</") == 0) {
      --depth;
      i = skip_to(i, ">");
    } else {
      // An opening tag: find its end outside quoted values; "/>" closes it at once.
      const int tag_line = line;
      char quote = 0;
      std::size_t j = i + 1;
      for (; j < xml.size(); ++j) {
        const char d = xml[j];
        if (d == '\n') ++line;
        if (quote) {
          if (d == quote) quote = 0;
        } else if (d == '"' || d == '\'') {
          quote = d;
        } else if (d == '>') {
          break;
        }
      }
      const bool self_closing = j < xml.size() && j > i && xml[j - 1] == '/';
      if (++elements > kMaxUrdfElements)
        throw InputError(path, line, "",
                         "more than " + std::to_string(kMaxUrdfElements) +
                             " XML elements; not a plausible machine description");
      if (depth == 1) {  // a child of <robot>
        const std::string tag = xml.substr(i + 1, j - i - 1);
        const std::string kind = tag.substr(0, tag.find_first_of(" \t\r\n/"));
        if (kind == "link" || kind == "joint")
          (kind == "link" ? lines.links : lines.joints).emplace(name_attribute(tag), tag_line);
      }
      if (!self_closing && ++depth > limits::kMaxNestingDepth)
        throw InputError(path, line, "",
                         "XML elements are nested more than " +
                             std::to_string(limits::kMaxNestingDepth) +
                             " levels deep; not a plausible URDF");
      i = j + 1;
    }
  }
  return lines;
}

}  // namespace

const JointInfo* UrdfInfo::find(const std::string& name) const {
  for (const auto& j : joints)
    if (j.name == name) return &j;
  return nullptr;
}

namespace {

Eigen::Isometry3d to_eigen(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

std::string joint_type(int type) {
  switch (type) {
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::FIXED:
      return "fixed";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    default:
      return "unknown";
  }
}

}  // namespace

UrdfInfo read_urdf(const std::string& path) {
  return read_urdf_text(read_text_file(path), path);
}

UrdfInfo read_urdf_text(const std::string& xml, const std::string& path) {
  const ElementLines lines = check_xml_shape(xml, path);
  urdf::ModelInterfaceSharedPtr model;
  CapturingHandler handler;
  {
    std::lock_guard<std::mutex> lock(parse_mutex);
    console_bridge::useOutputHandler(&handler);
    model = urdf::parseURDF(xml);
    console_bridge::restorePreviousOutputHandler();
  }
  if (!model) {
    std::string why;
    for (const auto& m : handler.messages) why += (why.empty() ? "" : "; ") + m;
    throw InputError(path, 0, "", "not a valid URDF" + (why.empty() ? std::string() : ": " + why));
  }
  UrdfInfo info;
  info.robot_name = model->getName();
  info.source_file = path;
  if (model->getRoot()) info.root_link = model->getRoot()->name;
  // urdfdom keeps maps: names in sorted order, so the description is deterministic.
  for (const auto& [name, joint] : model->joints_) {
    JointInfo j;
    j.name = name;
    if (const auto at = lines.joints.find(name); at != lines.joints.end()) j.line = at->second;
    j.type = joint_type(joint->type);
    j.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
    j.parent_link = joint->parent_link_name;
    j.child_link = joint->child_link_name;
    j.origin = to_eigen(joint->parent_to_joint_origin_transform);
    if (joint->limits) {
      j.has_limits = true;
      j.lower = joint->limits->lower;
      j.upper = joint->limits->upper;
      j.velocity = joint->limits->velocity;
    }
    info.joints.push_back(j);
  }
  for (const auto& [name, link] : model->links_) {
    LinkInfo l;
    l.name = name;
    if (const auto at = lines.links.find(name); at != lines.links.end()) l.line = at->second;
    if (link->inertial) {
      l.mass_kg = link->inertial->mass;
      const Eigen::Isometry3d origin = to_eigen(link->inertial->origin);
      l.centre_of_mass_m = origin.translation();
    }
    for (const auto& collision : link->collision_array) {
      if (!collision || !collision->geometry) continue;
      CollisionShape shape;
      shape.origin = to_eigen(collision->origin);
      switch (collision->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(*collision->geometry);
          shape.kind = CollisionShape::Kind::kBox;
          shape.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision->geometry);
          shape.kind = CollisionShape::Kind::kCylinder;
          shape.size = Eigen::Vector3d(cylinder.radius, cylinder.length, 0.0);
          break;
        }
        case urdf::Geometry::SPHERE: {
          const auto& sphere = static_cast<const urdf::Sphere&>(*collision->geometry);
          shape.kind = CollisionShape::Kind::kSphere;
          shape.size = Eigen::Vector3d(sphere.radius, 0.0, 0.0);
          break;
        }
        default:
          ++l.mesh_collisions;
          continue;
      }
      l.collisions.push_back(shape);
    }
    info.links.push_back(l);
  }
  return info;
}

}  // namespace ccbuild::machine
