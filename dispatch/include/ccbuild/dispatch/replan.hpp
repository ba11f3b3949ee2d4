#pragma once
// Re-planning the rest of a run from what the machines did (docs/dispatch.md, "When the
// site runs late"): when each stretch of wall was actually laid, from which the start
// window that keeps a layer's joints within the material's interval follows (its rule is
// rules/intervals.hpp), and the re-plans the dispatcher makes and journals.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ccbuild/rules/intervals.hpp"
#include "ccbuild/wire/timed_path.hpp"

namespace ccbuild::dispatch {

/// When a layer may start so that its intervals to the layer below keep the material's
/// window: the rule of rules/intervals.hpp, with the times the machines laid it.
using rules::StartWindow;

/// One re-plan, as the journal records it (before it is acted on) and a restarted
/// dispatcher applies it again.
struct Replan {
  std::int64_t job_id = 0;  ///< the job re-planned: a layer's first deposit sent, or a rest
  std::string what;         ///< "later", "planned joint", or "absorbed" (a wait shortened)
  double start_s = 0.0;     ///< its new start, schedule s
  /// The run's delay against the schedule afterwards, s (a layer's re-plan sets it).
  double delay_s = 0.0;
  double duration_s = 0.0;  ///< an absorbing wait's new duration, s (else 0)
  /// A planned joint: the treatment job inserted before the job (0: none), its start and
  /// duration (schedule s).
  std::int64_t treatment_job_id = 0;
  double treatment_start_s = 0.0, treatment_s = 0.0;
  std::string detail;  ///< in words, with the numbers
};

}  // namespace ccbuild::dispatch
