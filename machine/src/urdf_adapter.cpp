#include "ccbuild/machine/urdf_adapter.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cstring>
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
void check_xml_shape(const std::string& xml, const std::string& path) {
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
      if (!self_closing && ++depth > limits::kMaxNestingDepth)
        throw InputError(path, line, "",
                         "XML elements are nested more than " +
                             std::to_string(limits::kMaxNestingDepth) +
                             " levels deep; not a plausible URDF");
      i = j + 1;
    }
  }
}

}  // namespace

const JointInfo* UrdfInfo::find(const std::string& name) const {
  for (const auto& j : joints)
    if (j.name == name) return &j;
  return nullptr;
}

UrdfInfo read_urdf(const std::string& path) {
  const std::string xml = read_text_file(path);
  check_xml_shape(xml, path);
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
