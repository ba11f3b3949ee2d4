#include "ccbuild/machine/urdf_adapter.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <mutex>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"

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

}  // namespace

const JointInfo* UrdfInfo::find(const std::string& name) const {
  for (const auto& j : joints)
    if (j.name == name) return &j;
  return nullptr;
}

UrdfInfo read_urdf(const std::string& path) {
  const std::string xml = read_text_file(path);
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
  for (const auto& [name, joint] : model->joints_) {
    JointInfo j;
    j.name = name;
    switch (joint->type) {
      case urdf::Joint::PRISMATIC:
        j.type = "prismatic";
        break;
      case urdf::Joint::REVOLUTE:
        j.type = "revolute";
        break;
      case urdf::Joint::CONTINUOUS:
        j.type = "continuous";
        break;
      case urdf::Joint::FIXED:
        j.type = "fixed";
        break;
      case urdf::Joint::FLOATING:
        j.type = "floating";
        break;
      case urdf::Joint::PLANAR:
        j.type = "planar";
        break;
      default:
        j.type = "unknown";
        break;
    }
    j.axis[0] = joint->axis.x;
    j.axis[1] = joint->axis.y;
    j.axis[2] = joint->axis.z;
    if (joint->limits) {
      j.has_limits = true;
      j.lower = joint->limits->lower;
      j.upper = joint->limits->upper;
      j.velocity = joint->limits->velocity;
    }
    info.joints.push_back(j);
  }
  return info;
}

}  // namespace ccbuild::machine
