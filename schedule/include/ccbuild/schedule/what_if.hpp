#pragma once
// Anchors that hold up the build: each climb's wait for its pipes to reach the anchor
// strength (the climb critical path), and the changes that would shorten those waits,
// each scheduled in full so that its makespan is computed, not guessed.

#include <optional>
#include <string>
#include <vector>

#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule {

/// One climb and the pipes it waited for.
struct AnchorWait {
  int from_stage = 0, to_stage = 0;
  int floor = 0, layer = 0;  ///< the climb comes after this layer
  std::string anchor;        ///< the pipe that was strong last
  int cast_floor = 0, cast_layer = 0;
  double cast_s = 0.0;    ///< when that pipe was cast (its pipe event's end)
  double strong_s = 0.0;  ///< when it reaches the anchor strength
  double ready_s = 0.0;   ///< when the build was ready to climb but for the anchors
  double wait_s = 0.0;    ///< how long the build waited for them
  double required_mpa = 0.0;
};

/// The climbs of a schedule with their anchor waits, in order (empty on a fixed gantry).
std::vector<AnchorWait> anchor_waits(const Setup& setup, const Schedule& schedule);

/// A change that shortens the anchor waits, and the schedule it gives.
struct AnchorWhatIf {
  enum class Kind { kEarlierPipes, kFasterMix, kLowerStrength, kMoreUnits };
  Kind kind = Kind::kEarlierPipes;
  std::string change;  ///< in words, with its numbers
  bool feasible = false;
  double makespan_s = 0.0;
  double anchor_waits_s = 0.0;
  /// The change's number: the legs' extra length (m), the faster mix's age at the anchor
  /// strength (s), the anchor strength (MPa), the units (count).
  double value = 0.0;
};

/// The changes, each scheduled in full with `options`:
/// - pipes cast in the storey below: each climb's pipes in the top layers of the floor
///   under the one they are cast in now, which the legs reach when this much longer;
/// - a faster-hardening mix (`faster_mix`, when given) for the layers the pipes are cast
///   in;
/// - a lower anchor strength: the strength the youngest anchor has when its climb is
///   otherwise ready (if the climbing unit's maker allows loading from it);
/// - more units sharing the load: two more units, each holding anchor loaded in
///   proportion (the climbs' motions as planned for today's units).
/// Empty on a fixed gantry or when no climb waits for its anchors.
std::vector<AnchorWhatIf> anchor_what_ifs(const Setup& setup, const Schedule& base,
                                          const ScheduleOptions& options,
                                          const floors::MaterialProfile* faster_mix = nullptr);

}  // namespace ccbuild::schedule
