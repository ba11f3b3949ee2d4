#pragma once
// The rules every schedule keeps, checked on a schedule read back from its JSON
// (read_schedule), so that a hand-edited or damaged schedule is refused with the rule and
// the place instead of being drawn, compared or sent to machines. Internal.

#include "ccbuild/schedule/schedule_json.hpp"
#include "json_reader.hpp"

namespace ccbuild::schedule::detail {

/// Throws InputError listing (up to 20) broken rules, each with the line and JSON pointer
/// in `text`: plans (pieces, nozzle paths deposit every piece once, within the machine's
/// speeds, stopper and gantry gaps, their layer time), layers (building order, their
/// plan's nozzle count and time, one at a time, start after the events, the move, the
/// wait and the purge, interval and local intervals recomputed from the paths, within the
/// material's window when feasible, waits as long as their longest reason), events (in
/// order, between layers, after the layer they name, climbs as long as their phases),
/// stages, feasibility and totals.
void check_schedule_rules(const ScheduleDocument& document, const JsonText& text);

}  // namespace ccbuild::schedule::detail
