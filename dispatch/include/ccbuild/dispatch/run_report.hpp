#pragma once
// Planned against executed, once a dispatch run ends: layer by layer, floor by floor, the
// crew's and the climber's jobs, and the re-plans by kind (docs/dispatch.md; `ccbuild
// dry-run` prints it). Times are schedule seconds.

#include <map>
#include <string>
#include <vector>

#include "ccbuild/dispatch/dispatcher.hpp"

namespace ccbuild::dispatch {

/// A layer started more than this far (s) from its planned start is off its plan.
constexpr double kOffPlan_s = 1.0;

/// One layer: its planned start and end (its schedule jobs'), and when its first job
/// started and its last ended (recovery jobs included); +inf / -inf when none ran.
struct LayerDeviation {
  int floor = 0, layer = 0;
  double planned_start_s = 0.0, planned_end_s = 0.0;
  double started_s = 0.0, ended_s = 0.0;
  bool ran() const;
  double deviation_s() const;  ///< started minus planned start (0 when it never ran)
  bool off_plan() const;       ///< ran, more than kOffPlan_s from its planned start
};

/// One floor's layers together: the span of their plans and of what ran, how many were
/// off their plan or never ran, and the deviation largest in size (with its sign).
struct FloorDeviation {
  int floor = 0;
  int layers = 0, off_plan = 0, not_run = 0;
  double planned_start_s = 0.0, planned_end_s = 0.0, started_s = 0.0, ended_s = 0.0;
  double worst_s = 0.0;
};

/// Jobs of one kind: in the schedule, and run (a pin tried again runs once more).
struct JobCount {
  int planned = 0, ran = 0;
};

struct RunReport {
  std::vector<LayerDeviation> layers;  ///< by floor, then layer
  std::vector<FloorDeviation> floors;  ///< by floor
  int off_plan = 0, not_run = 0;       ///< layers
  double worst_s = 0.0;                ///< the largest deviation's size
  double finished_s = 0.0;             ///< the latest end of a job that ran
  /// "pipes", "slab stages", "purges", "pin insertions", "other climb phases" (those the
  /// schedule has).
  std::map<std::string, JobCount> crew_and_climber;
  /// Re-plans by what they did, and the planned joints' treatments that ran.
  int absorbed = 0, later = 0, planned_joints = 0, treatments_ran = 0;
};

/// What `dispatcher` ran against its schedule's plan, as it stands (at any time).
RunReport report_of(const Dispatcher& dispatcher);

}  // namespace ccbuild::dispatch
