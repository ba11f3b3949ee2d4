#pragma once
// The dispatcher's edge to the wire (docs/dispatch.md): a job as the LCM messages that
// carry it, a ccbuild_job_t and its path in ccbuild_path_chunk_t messages of at most
// MAX_POINTS waypoints each, so that every message stays under 64 kB.

#include <vector>

#include "ccbuild/dispatch/dispatch_jobs.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"

namespace ccbuild::dispatch {

struct JobMessages {
  ccbuild_lcm::ccbuild_job_t job;
  std::vector<ccbuild_lcm::ccbuild_path_chunk_t> chunks;  ///< job.chunk_count of them
};

/// `job` as its messages, with utime and seq 0 (set when sent).
JobMessages messages_of(const DispatchJob& job);

/// The job message's kind code for `kind` (ccbuild_job_t::DEPOSIT, ...).
std::int8_t wire_kind(JobKind kind);

}  // namespace ccbuild::dispatch
