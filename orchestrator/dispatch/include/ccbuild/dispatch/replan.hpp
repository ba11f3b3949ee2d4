#pragma once
// Re-planning the rest of a run from what the machines did (docs/dispatch.md, "When the
// site runs late"): when each piece end was actually laid, the start window that keeps a
// deposit's joints within the material's interval, and the re-plans the dispatcher makes
// and journals.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ccbuild/machine/timed_path.hpp"

namespace ccbuild::dispatch {

/// A piece end as a machine laid it: the wall, where (m) and when (schedule s).
struct LaidEnd {
  std::int64_t wall = 0;
  double x_m = 0.0, y_m = 0.0;
  double t_s = 0.0;
};

/// The piece ends a deposit of `path` laid when it started at `started_s` (schedule s):
/// every one, or when it ended on a fault with `stopped_at` waypoints done (>= 0), those
/// up to that waypoint (as the machine counts them).
std::vector<LaidEnd> laid_ends(const machine::TimedPath& path, double started_s,
                               int stopped_at = -1);

/// When a deposit may start (schedule s) so that each of its piece ends above one laid
/// below is covered no sooner than the minimum interval after it and no later than the
/// maximum. Unbounded when it covers none.
struct StartWindow {
  double earliest_s = -std::numeric_limits<double>::infinity();
  double latest_s = std::numeric_limits<double>::infinity();
  int ends_covered = 0;  ///< piece ends of the path above one laid below
  /// The newest piece end it covers was laid then (schedule s; -inf when none): a planned
  /// joint's treatment waits for it to be old enough.
  double newest_below_s = -std::numeric_limits<double>::infinity();
  bool empty() const { return earliest_s > latest_s; }
  /// The window both this one and `other` allow.
  StartWindow& intersect(const StartWindow& other);
};

/// The start window of a deposit of `path` over the piece ends `below` (the same wall,
/// within machine::kPieceEndMatch_m), for a material whose layers bond between
/// `min_interval_s` and `max_interval_s` after they were laid.
StartWindow start_window(const machine::TimedPath& path, const std::vector<LaidEnd>& below,
                         double min_interval_s, double max_interval_s);

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
