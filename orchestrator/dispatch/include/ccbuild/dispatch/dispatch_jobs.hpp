#pragma once
// A schedule (its JSON, docs/schedule.md) as the jobs the dispatcher sends, machine by
// machine (docs/dispatch.md): each layer a deposit job per nozzle with its timed path in
// chunks of at most ccbuild_path_chunk_t::MAX_POINTS waypoints, after a travel job per
// nozzle from where it ended (a straight line over the layer's move time); waits, pipes,
// purges, slabs and each climb's phases as jobs of the first gantry. Job ids increase in schedule
// order (by planned start) in tens, from 10 (the nine after each are for the jobs that recover from
// its faults); the same schedule gives the same jobs.

#include <string>
#include <vector>

#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"

namespace ccbuild::dispatch {

/// Gantry k (from 0, in rail order) is machine "gantry-<k+1>".
std::string gantry_id(int nozzle);

struct DispatchJob {
  ccbuild_lcm::ccbuild_job_t job;                         ///< utime and seq are set when sent
  std::vector<ccbuild_lcm::ccbuild_path_chunk_t> chunks;  ///< job.chunk_count of them
};

/// Every job of `schedule` (as read_schedule gives it, re-validated), in the order they are
/// to be sent (by planned start, then gantry). Throws InputError when a layer's plan is
/// missing.
std::vector<DispatchJob> jobs_of_schedule(const schedule::ScheduleDocument& schedule);

}  // namespace ccbuild::dispatch
