#pragma once
// A schedule (its JSON, docs/schedule.md) as the jobs the dispatcher sends, machine by
// machine (docs/dispatch.md): each layer a deposit job per nozzle with its timed path,
// after a travel job per nozzle from where it ended (a straight line over the layer's
// move time); waits, pipes, purges, slabs and each climb's phases as jobs of the first
// gantry. Job ids increase in schedule order (by planned start) in tens, from 10 (the
// nine after each are for the jobs that recover from its faults); the same schedule
// gives the same jobs.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/wire/timed_path.hpp"

namespace ccbuild::dispatch {

/// Gantry k (from 0, in rail order) is machine "gantry-<k+1>".
std::string gantry_id(int nozzle);

/// What a job does. A deposit or travel job has a path; the others are the whole
/// machine's, timed only.
enum class JobKind { kDeposit, kTravel, kPipe, kClimbPhase, kSlab, kWait, kPurge };

/// How a job may take up the run's delay instead of passing it on.
enum class DelayAbsorption {
  kNone,
  /// A layer's wait before it, waiting only for the minimum interval, the strength of the
  /// layers below or working hours (re-checked by the dispatcher from what the machines
  /// laid), on a site without weather: shortened.
  kShortenWait,
  /// Crew work the schedule put later than the work before it ended (a slab's formwork or
  /// pour, a lintel: the next working hours): started once that work has ended, never
  /// before its planned start.
  kStartWhenReady,
};

/// One job for one machine, as the dispatcher plans and journals it (it becomes a job
/// message and its path chunks only when sent: job_messages.hpp).
struct DispatchJob {
  std::int64_t job_id = 0;  ///< unique within a dispatch, increasing in schedule order
  std::string machine_id;   ///< e.g. "gantry-1"
  JobKind kind = JobKind::kWait;
  int floor = -1;           ///< from 0; -1 when the job is not about a layer
  int layer = -1;           ///< within the floor, from 0; -1 likewise
  int nozzle = -1;          ///< from 0 in rail order; -1 for the whole machine
  double start_s = 0.0;     ///< planned start, schedule s
  double duration_s = 0.0;  ///< planned duration, s
  std::string plan;         ///< the schedule's plan key (deposit jobs), else ""
  std::string detail;       ///< what it is, in words
  wire::TimedPath path;     ///< times from the job's start; empty for jobs without a path
  /// A deposit on a planned joint: the layer below's top was treated, so its piece ends are
  /// not held to the maximum interval.
  bool on_planned_joint = false;
  /// A climb phase's kind, as the wire codes it (ccbuild_job_t::PARK ... LIFT; 0 for other
  /// jobs).
  std::int8_t phase = 0;
  std::string unit;    ///< the climbing unit a pipe is cast for or a phase moves, else ""
  std::string anchor;  ///< a pipe's anchor id, else ""
  double z_bottom_m = 0.0, z_top_m = 0.0;  ///< a deposit's layer, m
  /// How the job may absorb the run's delay (docs/dispatch.md, "When the site runs late").
  DelayAbsorption absorbs = DelayAbsorption::kNone;
};

/// Every job of `schedule` (as read_schedule gives it, re-validated), in the order they are
/// to be sent (by planned start, then gantry). Throws InputError when a layer's plan is
/// missing.
std::vector<DispatchJob> jobs_of_schedule(const schedule::ScheduleDocument& schedule);

/// Where each gantry of `ids` (in rail order) is parked before its first job (x, y, z m,
/// heading rad): where its first path starts when it works from the first layer on; else
/// (it joins later) at its park at the far end of the rails, a gantry width from the
/// next (the machine's gantries that never work stand beyond it). Neighbours' homes are
/// kept a gantry width apart.
std::map<std::string, std::array<double, 4>> parking_homes(
    const std::vector<DispatchJob>& jobs, const std::vector<std::string>& ids,
    const schedule::RecordedMachine& machine);

}  // namespace ccbuild::dispatch
