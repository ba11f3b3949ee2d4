#include "ccbuild/schedule/climbs.hpp"

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::schedule {

climb::ClimbStatus ClimbReport::status() const {
  if (!stages.status) return stages.status;
  for (const auto& c : climbs)
    if (!c.status)
      return {c.status.code(),
              printf_string("climb %d -> %d: ", c.from_stage, c.to_stage) + c.status.reason()};
  return {};
}

double ClimbReport::climb_time_s() const {
  double t = 0.0;
  for (const auto& c : climbs) t += c.duration_s;
  return t;
}

double ClimbReport::planning_s() const {
  double t = 0.0;
  for (const auto& c : climbs) t += c.planning_s;
  return t;
}

ClimbReport plan_climbs(const Setup& project, std::optional<int> floor,
                        const climb::ClimbOptions& options) {
  if (floor) check_floor(project, *floor);
  ClimbReport report;
  if (!project.climber) {
    report.fixed_gantry = true;
    return report;
  }
  report.stages = climb::climb_stages(project.building, *project.climber);
  const auto& stages = report.stages.stages;
  for (std::size_t k = 0; k + 1 < stages.size(); ++k) {
    if (floor && stages[k].last.floor != *floor) continue;
    report.climbs.push_back(
        climb::plan_climb(*project.climber, project.building, stages[k], stages[k + 1], options));
  }
  return report;
}

void check_floor(const Setup& setup, int floor) {
  const auto floors = setup.building.floors.size();
  if (floor < 0 || floor >= static_cast<int>(floors))
    throw InputError("", 0, "floor",
                     "no floor " + std::to_string(floor) + "; " + setup.file.string() +
                         " has floors 0 to " + std::to_string(floors - 1));
}

}  // namespace ccbuild::schedule
