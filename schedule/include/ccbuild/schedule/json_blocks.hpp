#pragma once
// The JSON blocks the schedule shares with the other reports (docs/json.md,
// docs/schedule.md): numbers rounded for stable bytes, a layer's pieces, timed paths, the
// machine's limits, and the climbing machine's anchors, stages and climbs.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::schedule {

/// Rounded for stable, readable JSON: micrometres, microseconds, microradians.
double rounded(double value);
nlohmann::ordered_json point_json(const Eigen::Vector2d& p);
/// The layer's wall pieces: wall, piece (1-based), piece_count, start_m, end_m, length_m;
/// a bead's kind and width where it is not one pass at `nozzle_width_m` (0: never said of
/// a pass).
nlohmann::ordered_json pieces_json(const floors::Layer& layer, double nozzle_width_m = 0.0);
/// [{t_s, x_m, y_m, z_m, heading_rad, extruding, wall, piece}].
nlohmann::ordered_json waypoints_json(const std::vector<planner::Waypoint>& waypoints);
/// A timed path's digest: its waypoint count and the SHA-256 of waypoints_json's compact text.
PathDigest path_digest(const std::vector<planner::Waypoint>& waypoints);
/// The machine's limits an independent check needs (RecordedMachine's first fields).
RecordedMachine machine_limits(const machine::MachineModel& machine);
nlohmann::ordered_json machine_limits_json(const RecordedMachine& machine);

/// One pipe: id, unit (named by `units`), floor, wall, after_layer (null in the
/// foundation), centre, outward.
nlohmann::ordered_json anchor_json(const std::vector<std::string>& units,
                                   const climb::Anchor& anchor);
/// One stage: platform height, first and last layer printed, top, anchors.
nlohmann::ordered_json stage_json(const std::vector<std::string>& units,
                                  const climb::ClimbStage& stage);
/// One climb: status, duration, clearance, and its phases with their timed joint paths.
/// Planning times only `with_planning_time` (they differ from run to run).
nlohmann::ordered_json climb_plan_json(const std::vector<std::string>& units,
                                       const climb::ClimbPlan& plan, bool with_planning_time);

}  // namespace ccbuild::schedule
