#include "ccbuild/dispatch/job_messages.hpp"

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/wire/path_chunks.hpp"

namespace ccbuild::dispatch {

std::int8_t wire_kind(JobKind kind) {
  using ccbuild_lcm::ccbuild_job_t;
  switch (kind) {
    case JobKind::kDeposit:
      return ccbuild_job_t::DEPOSIT;
    case JobKind::kTravel:
      return ccbuild_job_t::TRAVEL;
    case JobKind::kPipe:
      return ccbuild_job_t::PIPE;
    case JobKind::kClimbPhase:
      return ccbuild_job_t::CLIMB_PHASE;
    case JobKind::kSlab:
      return ccbuild_job_t::SLAB;
    case JobKind::kWait:
      return ccbuild_job_t::WAIT;
    case JobKind::kPurge:
      return ccbuild_job_t::PURGE;
  }
  CCBUILD_CHECK(false, "wire_kind: unknown job kind");
  return 0;
}

JobMessages messages_of(const DispatchJob& d) {
  JobMessages m;
  auto& j = m.job;
  j.utime = 0;
  j.machine_id = d.machine_id;
  j.job_id = d.job_id;
  j.seq = 0;
  j.kind = wire_kind(d.kind);
  j.floor = d.floor;
  j.layer = d.layer;
  j.nozzle = d.nozzle;
  j.start_s = d.start_s;
  j.duration_s = d.duration_s;
  j.plan = d.plan;
  j.detail = d.detail;
  m.chunks = wire::chunks_of(d.path, d.machine_id);
  for (auto& c : m.chunks) c.job_id = d.job_id;
  j.chunk_count = static_cast<std::int32_t>(m.chunks.size());
  j.point_count = static_cast<std::int32_t>(d.path.size());
  j.on_planned_joint = d.on_planned_joint;
  j.phase = d.phase;
  j.unit = d.unit;
  j.anchor = d.anchor;
  return m;
}

}  // namespace ccbuild::dispatch
