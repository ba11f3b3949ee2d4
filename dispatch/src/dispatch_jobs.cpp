#include "ccbuild/dispatch/dispatch_jobs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/gantry_yard.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"

namespace ccbuild::dispatch {
namespace {

using schedule::Event;
using schedule::Schedule;
using schedule::ScheduledLayer;
using schedule::ScheduleDocument;
using schedule::SchedulePlan;
using schedule::WaitKind;
using schedule::WaitReason;

DispatchJob job_of(JobKind kind, const std::string& machine, double start_s, double duration_s,
                   int floor, int layer, int nozzle, const std::string& plan,
                   const std::string& detail, wire::TimedPath path = {}) {
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
wire::TimedPath timed_path(const std::vector<planner::Waypoint>& waypoints) {
  wire::TimedPath path;
  for (const auto& w : waypoints)
    path.push_back(w.t_s, w.position_m.x(), w.position_m.y(), w.z_m, w.heading_rad, w.extruding,
                   w.wall, w.piece);
  return path;
}

/// A climb phase's kind as the job message codes it.
std::int8_t wire_phase(climb::ClimbPhase::Kind kind) {
  using K = climb::ClimbPhase::Kind;
  using J = ccbuild_lcm::ccbuild_job_t;
  switch (kind) {
    case K::kPark:
      return J::PARK;
    case K::kBalance:
      return J::BALANCE;
    case K::kRelease:
      return J::RELEASE;
    case K::kTransit:
      return J::TRANSIT;
    case K::kInsert:
      return J::INSERT;
    case K::kLift:
      return J::LIFT;
  }
  return J::NO_PHASE;
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
  const auto unit_name = [&](int unit) {
    return unit >= 0 && unit < static_cast<int>(document.inputs.unit_names.size())
               ? document.inputs.unit_names[unit]
               : std::string();
  };
  const schedule::RecordedMachine& machine = document.inputs.machine;
  // Parks for every gantry of the machine (one never used stays at the far end).
  int gantries = std::max(1, machine.nozzles);
  for (const auto& [key, plan] : schedule.plans)
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n)
      if (!plan.waypoints[n].empty()) gantries = std::max(gantries, static_cast<int>(n) + 1);
  // Where each gantry stands once its last job ends, and its moves before each layer: the
  // scheduler's rule for the layer's move time (machine::GantryYard).
  machine::GantryYard yard(
      machine::AxisSpeeds{machine.x_speed_m_s, machine.y_speed_m_s, machine.z_speed_m_s,
                          machine.rotation_speed_rad_s},
      machine.rail_axis,
      machine::rail_coordinate(machine.x_max_m, machine.y_max_m, machine.rail_axis), gantries,
      machine.gantry_width_m);
  const auto travel = [](const machine::GantryPose& a, const machine::GantryPose& b,
                         double duration_s) {
    wire::TimedPath move;
    move.push_back(0.0, a[0], a[1], a[2], a[3], false, 0, 0);
    move.push_back(duration_s, b[0], b[1], b[2], b[3], false, 0, 0);
    return move;
  };
  std::vector<machine::GantryMove> parks, to_starts;
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
      if (!document.inputs.conditions &&
          std::all_of(l.wait_reasons.begin(), l.wait_reasons.end(), [](const WaitReason& r) {
            return r.kind == WaitKind::kMinInterval || r.kind == WaitKind::kStrength ||
                   r.kind == WaitKind::kOffShift;
          }))
        jobs.back().absorbs = DelayAbsorption::kShortenWait;
    }
    const double moves_from_s = waited_from_s - move_s;
    std::vector<wire::TimedPath> paths(plan.waypoints.size());
    std::vector<std::optional<machine::GantryPose>> starts(plan.waypoints.size()),
        ends(plan.waypoints.size());
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
      paths[n] = timed_path(plan.waypoints[n]);
      wire::TimedPath& path = paths[n];
      if (path.size() == 0) continue;
      for (double& z_m : path.z_m) z_m += dz_m;  // this layer's height
      const std::size_t end = path.size() - 1;
      starts[n] = machine::GantryPose{path.x_m[0], path.y_m[0], path.z_m[0], path.heading_rad[0]};
      ends[n] =
          machine::GantryPose{path.x_m[end], path.y_m[end], path.z_m[end], path.heading_rad[end]};
    }
    yard.moves_before(starts, parks, to_starts);
    for (const machine::GantryMove& m : parks)
      if (m.duration_s > 0.0)
        jobs.push_back(job_of(JobKind::kTravel, gantry_id(m.nozzle), moves_from_s, m.duration_s,
                              floor, layer, m.nozzle, "",
                              printf_string("nozzle %d parks clear at the far end of the rails "
                                            "(idle on floor %d layer %d)",
                                            m.nozzle + 1, floor, layer),
                              travel(m.from, m.to, m.duration_s)));
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
      const int nozzle = static_cast<int>(n);
      if (!starts[n]) continue;
      // The move from where this gantry stands to where it starts, in a straight line,
      // over the layer's move time (which the scheduler made long enough for it).
      for (const machine::GantryMove& m : to_starts)
        if (m.nozzle == nozzle && (move_s > 0.0 || m.duration_s > 1e-6)) {
          // The scheduler made the layer's move at least as long as the yard's moves; a
          // schedule that says less (beyond the JSON's rounding, absorbed below) was not
          // made by it for this machine.
          if (m.duration_s > move_s + 1e-3)
            throw InputError("", 0, "move_before_s",
                             printf_string("floor %d layer %d moves in %.3f s, but nozzle %d's "
                                           "axes need %.3f s to reach its start",
                                           floor, layer, move_s, nozzle + 1, m.duration_s));
          const double travel_s = std::max(move_s, m.duration_s);
          jobs.push_back(job_of(
              JobKind::kTravel, gantry_id(nozzle), moves_from_s, travel_s, floor, layer, nozzle, "",
              printf_string("move to floor %d layer %d, nozzle %d", floor, layer, nozzle + 1),
              travel(m.from, m.to, travel_s)));
        }
      const double duration_s = paths[n].t_s.back();
      jobs.push_back(job_of(JobKind::kDeposit, gantry_id(nozzle), start_s, duration_s, floor, layer,
                            nozzle, l.plan,
                            printf_string("floor %d layer %d, nozzle %d", floor, layer, nozzle + 1),
                            std::move(paths[n])));
      jobs.back().on_planned_joint = l.planned_joint;
      jobs.back().z_bottom_m = l.z_bottom_m;
      jobs.back().z_top_m = l.z_top_m;
    }
    yard.finish_layer(ends);
  }
  for (const Event& e : schedule.events) {
    if (e.kind == Event::Kind::kClimb && e.climb) {
      double t = e.start_s;
      for (const auto& p : e.climb->plan.phases) {
        const std::string unit = unit_name(p.unit);
        jobs.push_back(
            job_of(JobKind::kClimbPhase, gantry_id(0), t, p.duration_s, e.floor, e.layer, -1, "",
                   e.detail + ": " + climb::to_string(p.kind) + (unit.empty() ? "" : " " + unit)));
        jobs.back().phase = wire_phase(p.kind);
        jobs.back().unit = unit;
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
    // Crew work with nothing of the machines' to wait for: a slab stage and a lintel may
    // start as soon as the work before them ended (not a planned joint's treatment: it
    // waits for the age of the layer below).
    if (e.kind == Event::Kind::kSlab || e.kind == Event::Kind::kPour ||
        e.kind == Event::Kind::kLintel)
      jobs.back().absorbs = DelayAbsorption::kStartWhenReady;
    if (e.kind == Event::Kind::kPipe && e.anchor) {
      jobs.back().unit = unit_name(e.anchor->unit);
      jobs.back().anchor = e.anchor->id;
    }
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

std::map<std::string, std::array<double, 4>> parking_homes(
    const std::vector<DispatchJob>& jobs, const std::vector<std::string>& ids,
    const schedule::RecordedMachine& machine) {
  const machine::RailAxis rail_axis = machine.rail_axis;
  const double gantry_width_m = machine.gantry_width_m;
  const int rail = rail_axis == machine::RailAxis::kY ? 1 : 0;
  const double rail_max_m = machine::rail_coordinate(machine.x_max_m, machine.y_max_m, rail_axis);
  double first_s = std::numeric_limits<double>::infinity();
  for (const auto& j : jobs)
    if (j.kind == JobKind::kDeposit) first_s = std::min(first_s, j.start_s);
  std::map<std::string, std::array<double, 4>> homes;
  std::map<std::string, bool> from_first;
  for (const auto& id : ids)
    for (const auto& j : jobs)
      if (j.machine_id == id && j.path.size() > 0) {
        const auto& c = j.path;
        homes[id] = {c.x_m[0], c.y_m[0], c.z_m[0], c.heading_rad[0]};
        from_first[id] = j.start_s == first_s;
        break;
      }
  // Gantries never used (beyond `ids`) stand at the far end of the rails.
  const int count = std::max(static_cast<int>(ids.size()), machine.nozzles);
  const machine::GantryYard yard({}, rail_axis, rail_max_m, count, gantry_width_m);
  for (int k = 0; k < static_cast<int>(ids.size()); ++k)
    if (homes.count(ids[k]) && !from_first[ids[k]]) homes[ids[k]] = yard.park_of(k, homes[ids[k]]);
  for (int k = 1; k < static_cast<int>(ids.size()); ++k)
    if (homes.count(ids[k]) && homes.count(ids[k - 1]))
      homes[ids[k]][rail] = std::max(homes[ids[k]][rail], homes[ids[k - 1]][rail] + gantry_width_m);
  return homes;
}

}  // namespace ccbuild::dispatch
