#pragma once
// Reports of a building's climbs on a climbing machine (schedule/climbs.hpp): JSON
// (docs/json.md) and an SVG with the platform, units and pipes in plan and in elevation.

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "ccbuild/climb/fit.hpp"
#include "ccbuild/schedule/climbs.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::report {

/// The machine, the stages, the climbs with their timed joint paths and planning times.
nlohmann::ordered_json climb_report_json(const schedule::Setup& setup,
                                         const schedule::ClimbReport& report);

/// The platform, the units' pins and the walls: in plan (the top floor) and in elevation
/// (x against height: floors, platform stages, pipes), in the building's unit.
std::string climb_report_svg(const schedule::Setup& setup, const schedule::ClimbReport& report);

/// The climbs as `ccbuild climb` prints them: each stage with its pins, each climb with its
/// phases, their times and nearest walls; `floor` when only that floor's climbs were asked.
void write_climb_text(std::ostream& out, const schedule::Project& project,
                      const schedule::ClimbReport& report, const std::string& file,
                      const std::optional<int>& floor);

/// A family's member fitted to a building (`ccbuild fit --json`): the platform, its units,
/// mass, margins and what was tried; `profile` and `urdf` the files written.
nlohmann::ordered_json fit_json(const schedule::Project& project, const climb::FitResult& fit,
                                const std::string& profile, const std::string& urdf);

/// The same as text, `family` the family's file.
void write_fit_text(std::ostream& out, const schedule::Project& project,
                    const climb::FitResult& fit, const std::string& family);

}  // namespace ccbuild::report
