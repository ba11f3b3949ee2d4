#include "ccbuild/floors/print_names.hpp"

#include <algorithm>
#include <cctype>

#include "ccbuild/common/format.hpp"

namespace ccbuild::floors {

std::string wall_type_name_fault(const std::string& name) {
  const bool ok = name.size() > 3 && name.size() <= 64 && name.rfind("Ifc", 0) == 0 &&
                  std::all_of(name.begin(), name.end(),
                              [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
  return ok ? ""
            : "expected an IFC entity name (IfcWall, IfcWallStandardCase), got '" + echoed(name) +
                  "'";
}

std::string excluded_material_name_fault(const std::string& name) {
  const bool ok = !name.empty() && name.size() <= 100 &&
                  std::none_of(name.begin(), name.end(),
                               [](char c) { return std::iscntrl(static_cast<unsigned char>(c)); });
  return ok ? ""
            : "expected a material's name (1 to 100 characters, no control characters), got '" +
                  echoed(name) + "'";
}

}  // namespace ccbuild::floors
