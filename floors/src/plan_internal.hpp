#pragma once
// Pieces of the plan readers shared with the building reader (not public).

#include "ccbuild/common/document.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plan.hpp"

namespace ccbuild::floors {

/// `units:` value; throws InputError unless it is "m" or "ft".
LengthUnit read_units(const Field& field);
/// A length written in `unit`, inside `range_m`; returns metres.
double read_length(const Field& field, const Range& range_m, LengthUnit unit);
/// A vertex or wall id: 1 to limits::kMaxId.
std::int64_t read_id(const Field& field);
/// Throws InputError at `field` when a list holds more than `most` items.
void check_count(const Field& list, std::size_t count, std::size_t most, const char* what);
SourceRef source_of(const Field& field);
Opening read_opening(const Field& field, LengthUnit unit);
/// A wall's `top:`, a height or [offset, height] points (Wall::top_m).
std::vector<std::pair<double, double>> read_wall_top(const Field& field, LengthUnit unit);

/// Diagnostic located at an element's source.
inline Diagnostic at(const SourceRef& source, std::string field_suffix, std::string message) {
  std::string field = source.path;
  if (!field_suffix.empty()) field = field.empty() ? field_suffix : field + "." + field_suffix;
  return Diagnostic{source.file, source.line, std::move(field), std::move(message)};
}

}  // namespace ccbuild::floors
