#include "ccbuild/dispatch/dispatch_jobs.hpp"

#include <algorithm>
#include <array>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::dispatch {
namespace {

using schedule::Event;
using schedule::Schedule;
using schedule::ScheduledLayer;
using schedule::ScheduleDocument;
using schedule::SchedulePlan;

DispatchJob job_of(JobKind kind, const std::string& machine, double start_s, double duration_s,
                   int floor, int layer, int nozzle, const std::string& plan,
                   const std::string& detail, machine::TimedPath path = {}) {
  DispatchJob j;
  j.machine_id = machine;
  j.kind = kind;
  j.floor = floor;
  j.layer = layer;
  j.nozzle = nozzle;
  j.start_s = start_s;
  j.duration_s = duration_s;
  j.plan = plan;
  j.detail = detail;
  j.path = std::move(path);
  return j;
}

/// A plan's waypoints as a timed path.
machine::TimedPath timed_path(const std::vector<planner::Waypoint>& waypoints) {
  machine::TimedPath path;
  for (const auto& w : waypoints)
    path.push_back(w.t_s, w.position_m.x(), w.position_m.y(), w.z_m, w.heading_rad, w.extruding,
                   w.wall, w.piece);
  return path;
}

}  // namespace

std::string gantry_id(int nozzle) {
  return "gantry-" + std::to_string(nozzle + 1);
}

std::vector<DispatchJob> jobs_of_schedule(const ScheduleDocument& document) {
  std::vector<DispatchJob> jobs;
  const Schedule& schedule = document.schedule;
  const double purge_s = document.inputs.machine.purge_s;
  const double treatment_s = document.inputs.material.planned_joint.treatment_s;
  // Nozzle -> its last position (x, y, z, heading), if it deposited the layer before.
  std::map<int, std::array<double, 4>> last, ending;
  for (const ScheduledLayer& l : schedule.layers) {
    const auto plan_it = schedule.plans.find(l.plan);
    if (plan_it == schedule.plans.end())
      throw InputError("", 0, "schedule", "layer plan '" + l.plan + "' is not among the plans");
    const SchedulePlan& plan = plan_it->second;
    const int floor = l.floor, layer = l.layer;
    const double start_s = l.start_s;
    const double dz_m = l.z_top_m - plan.z_top_m;
    // Before the layer: the move to it, the wait (the machine idle, with its reasons),
    // then a planned joint's treatment and the purge (events of their own).
    const double wait_s = l.wait_before_s;
    const double move_s = l.move_before_s;
    const double waited_from_s =
        start_s - (l.purge_before ? purge_s : 0.0) - (l.planned_joint ? treatment_s : 0.0) - wait_s;
    if (wait_s > 0.0) {
      std::string why;
      for (const auto& r : l.wait_reasons) why += (why.empty() ? "" : "; ") + r.detail;
      jobs.push_back(
          job_of(JobKind::kWait, gantry_id(0), waited_from_s, wait_s, floor, layer, -1, "",
                 printf_string("wait before floor %d layer %d: %s", floor, layer, why.c_str())));
    }
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
      const int nozzle = static_cast<int>(n);
      machine::TimedPath path = timed_path(plan.waypoints[n]);
      if (path.size() == 0) continue;
      for (double& z_m : path.z_m) z_m += dz_m;  // this layer's height
      // The move from where this nozzle ended to where it starts, in a straight line.
      const auto from = last.find(nozzle);
      if (from != last.end() && move_s > 0.0) {
        const auto& [x0, y0, z0, h0] = from->second;
        machine::TimedPath move;
        move.push_back(0.0, x0, y0, z0, h0, false, 0, 0);
        move.push_back(move_s, path.x_m[0], path.y_m[0], path.z_m[0], path.heading_rad[0], false, 0,
                       0);
        jobs.push_back(
            job_of(JobKind::kTravel, gantry_id(nozzle), waited_from_s - move_s, move_s, floor,
                   layer, nozzle, "",
                   printf_string("move to floor %d layer %d, nozzle %d", floor, layer, nozzle + 1),
                   std::move(move)));
      }
      const std::size_t end = path.size() - 1;
      ending[nozzle] = {path.x_m[end], path.y_m[end], path.z_m[end], path.heading_rad[end]};
      const double duration_s = path.t_s.back();
      jobs.push_back(job_of(JobKind::kDeposit, gantry_id(nozzle), start_s, duration_s, floor, layer,
                            nozzle, l.plan,
                            printf_string("floor %d layer %d, nozzle %d", floor, layer, nozzle + 1),
                            std::move(path)));
      jobs.back().on_planned_joint = l.planned_joint;
    }
    last.swap(ending);  // a nozzle idle for a layer moves without a job (as planned)
    ending.clear();
  }
  for (const Event& e : schedule.events) {
    if (e.kind == Event::Kind::kClimb && e.climb) {
      double t = e.start_s;
      for (const auto& p : e.climb->plan.phases) {
        const std::string unit =
            p.unit >= 0 && p.unit < static_cast<int>(document.inputs.unit_names.size())
                ? " " + document.inputs.unit_names[p.unit]
                : "";
        jobs.push_back(job_of(JobKind::kClimbPhase, gantry_id(0), t, p.duration_s, e.floor, e.layer,
                              -1, "", e.detail + ": " + climb::to_string(p.kind) + unit));
        t += p.duration_s;
      }
      continue;
    }
    // The machine waits through crew work (joints, lintels); a slab's formwork and pour
    // are the slab stage.
    const JobKind kind = e.kind == Event::Kind::kPipe ? JobKind::kPipe
                         : e.kind == Event::Kind::kSlab || e.kind == Event::Kind::kPour
                             ? JobKind::kSlab
                         : e.kind == Event::Kind::kPurge ? JobKind::kPurge
                                                         : JobKind::kWait;
    jobs.push_back(job_of(kind, gantry_id(0), e.start_s, e.end_s - e.start_s, e.floor, e.layer, -1,
                          "", e.detail));
  }
  // Schedule order: by planned start, then gantry; stable for equal keys.
  std::stable_sort(jobs.begin(), jobs.end(), [](const DispatchJob& a, const DispatchJob& b) {
    if (a.start_s != b.start_s) return a.start_s < b.start_s;
    return a.machine_id < b.machine_id;
  });
  for (std::size_t k = 0; k < jobs.size(); ++k)
    jobs[k].job_id = static_cast<std::int64_t>(10 * (k + 1));
  return jobs;
}

}  // namespace ccbuild::dispatch
