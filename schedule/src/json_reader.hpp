#pragma once
// The located JSON reader is common's (ccbuild/common/json_reader.hpp, shared with the
// study's files); the schedule's readers name it here as they always have.

#include "ccbuild/common/json_reader.hpp"

namespace ccbuild::schedule::detail {

using ccbuild::check_nesting;
using ccbuild::JsonAt;
using ccbuild::JsonText;
using ccbuild::parse_located;
using ccbuild::pointer_to;

}  // namespace ccbuild::schedule::detail
