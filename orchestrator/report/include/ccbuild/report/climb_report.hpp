#pragma once
// Reports of a building's climbs on a climbing machine (schedule/climbs.hpp): JSON
// (docs/json.md) and an SVG with the platform, units and pipes in plan and in elevation.

#include <nlohmann/json.hpp>
#include <string>

#include "ccbuild/schedule/climbs.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::report {

/// The machine, the stages, the climbs with their timed joint paths and planning times.
nlohmann::ordered_json climb_report_json(const schedule::Setup& setup,
                                         const schedule::ClimbReport& report);

/// The platform, the units' pins and the walls: in plan (the top floor) and in elevation
/// (x against height: floors, platform stages, pipes), in the building's unit.
std::string climb_report_svg(const schedule::Setup& setup, const schedule::ClimbReport& report);

}  // namespace ccbuild::report
