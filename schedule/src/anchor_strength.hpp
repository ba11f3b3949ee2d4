#pragma once
// A climb's youngest anchor's strength from its casting to the climb, as the schedule
// keeps it for the report's chart: taken by the scheduler, checked again by the reader.
// Internal to the schedule library.

#include <vector>

#include "ccbuild/floors/material.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/site/conditions.hpp"

namespace ccbuild::schedule::detail {

/// kAnchorCurvePoints points at equal steps in time from the youngest anchor's casting
/// (the climb's start less its age) to the climb's start, each the strength of `mix` at
/// the anchor's equivalent age then (`maturity` with site weather, else its real age).
/// Empty when the climb has no anchors.
std::vector<ClimbEvent::StrengthPoint> youngest_anchor_strength(
    const ClimbEvent& climb, const floors::MaterialProfile& mix,
    const site::EquivalentAge* maturity);

}  // namespace ccbuild::schedule::detail
