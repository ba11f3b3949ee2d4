#pragma once
// Pieces of the plan readers shared with the building reader (not public).

#include "ccbuild/common/document.hpp"
#include "ccbuild/floors/plan.hpp"

namespace ccbuild::floors {

/// `units:` value; throws InputError unless it is "m" or "ft".
LengthUnit read_units(const Field& field);
SourceRef source_of(const Field& field);
Opening read_opening(const Field& field, LengthUnit unit);

/// Diagnostic located at an element's source.
inline Diagnostic at(const SourceRef& source, std::string field_suffix, std::string message) {
  std::string field = source.path;
  if (!field_suffix.empty()) field = field.empty() ? field_suffix : field + "." + field_suffix;
  return Diagnostic{source.file, source.line, std::move(field), std::move(message)};
}

}  // namespace ccbuild::floors
