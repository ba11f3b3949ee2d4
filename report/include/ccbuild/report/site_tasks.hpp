#pragma once
// A schedule as a site planner's task list: every layer, every wait with its reasons,
// pipe, lintel, planned joint's treatment, purge, slab's formwork and pour, climb and
// each of its phases, and every concrete delivery, in order of start. The exports
// (exports.hpp) write it for the tools a site plans in. Times are schedule seconds.

#include <string>
#include <vector>

#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::report {

/// What a site task is: a layer, the wait before one, a schedule's event (pipe, climb,
/// slab, pour, purge, joint, lintel), a climb's phase, a delivery, a floor's walls finished,
/// or (in a project file) the summary of a floor.
enum class TaskKind {
  kLayer,
  kWait,
  kPipe,
  kClimb,
  kClimbPhase,
  kSlab,
  kPour,
  kPurge,
  kJoint,
  kLintel,
  kDelivery,
  kWallsFinished,
  kFloor
};
/// Its name in the exports: "layer", "wait", "pipe", ..., "climb-phase", "walls-finished".
std::string to_string(TaskKind kind);
/// The kind of a schedule's event.
TaskKind task_kind_of(schedule::Event::Kind kind);

struct SiteTask {
  std::string id;  ///< unique in the list: "L0.12" (a layer), "W0.12" (its wait), "E17"
                   ///< (event 17 of the schedule), "E17.3" (its phase 3), "D4" (delivery)
  TaskKind kind = TaskKind::kLayer;
  int floor = -1, layer = -1;         ///< -1 when not about one
  double start_s = 0.0, end_s = 0.0;  ///< a delivery: both its due time
  /// "machine, 2 nozzles", "machine", "crew of 4", "machine and crew of 2", "site" (a fixed
  /// slab stage), "supplier" (a delivery)
  std::string who;
  int crew = 0;              ///< people on it
  double concrete_m3 = 0.0;  ///< a layer's, a pour's, a delivery's
  std::string title;         ///< what, in a few words, made from its fields (title_of)
  std::string detail;        ///< what and why, in words (a wait: its reasons)
  std::string reasons;       ///< a wait: its reasons' kinds, "min-interval, strength"
};

/// The tasks of `schedule`, by start (then as listed above, for equal starts).
std::vector<SiteTask> tasks_of(const schedule::ScheduleDocument& schedule);

/// A short title for lists and calendars: "Floor 0 layer 12", "Wait before floor 0 layer
/// 12", "Floor 0: formwork lintel over opening W1", "Concrete delivery, 6.00 m³" (yd³
/// where `unit` is feet).
std::string title_of(const SiteTask& task, floors::LengthUnit unit = floors::LengthUnit::kMeter);

/// The unit a schedule's lengths are shown in (its `inputs.units`; m when it names none).
floors::LengthUnit shown_unit(const schedule::ScheduleDocument& schedule);

/// The milestones: each floor's walls finished (kind "walls-finished", id "M<floor>", at the
/// end of its last layer: start_s equals end_s), by floor.
std::vector<SiteTask> milestones_of(const schedule::ScheduleDocument& schedule);

}  // namespace ccbuild::report
