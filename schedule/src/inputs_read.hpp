#pragma once
// The `inputs` block of a schedule's JSON read back (RecordedInputs): the building, its
// placement, the files and their checksums, the machine's limits and the material.

#include "ccbuild/schedule/schedule_json.hpp"
#include "json_reader.hpp"

namespace ccbuild::schedule::detail {

/// `root`'s `inputs` (and its `ccbuild_version`). Throws InputError at the JSON pointer.
RecordedInputs read_inputs(const JsonAt& root);

/// A recorded lintel's `type` and `by` (in `inputs.lintels` and in lintel events) into
/// `type` and `by_arm`. Throws InputError at the JSON pointer.
void read_lintel_kind(const JsonAt& j, floors::LintelSpec::Type& type, bool& by_arm);

}  // namespace ccbuild::schedule::detail
