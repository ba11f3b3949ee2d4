#pragma once
// The names a print spec may hold (docs/formats.md, "What is printed"): the rule the
// building file's `print:` is read with and `ccbuild import` checks its flags with, so
// that an import never writes a building that does not read back.

#include <string>

namespace ccbuild::floors {

/// Why NAME cannot be one of `print.wall_types` (an IFC entity name: "Ifc" and letters or
/// digits, at most 64 characters); empty when it can.
std::string wall_type_name_fault(const std::string& name);

/// Why NAME cannot be one of `print.exclude_materials` (1 to 100 characters, no control
/// characters); empty when it can.
std::string excluded_material_name_fault(const std::string& name);

}  // namespace ccbuild::floors
