#pragma once
// The plausible ranges and counts read_schedule holds a schedule's JSON to.

#include <cstddef>
#include <cstdint>

#include "ccbuild/common/format.hpp"

namespace ccbuild::schedule::detail::read_limits {

// Plausible ranges. Far beyond any real schedule, near enough to refuse garbage before it
// overflows a computation.
inline const Range kTime_s = Range::closed(0.0, 1e10);  // 317 years
inline const Range kDuration_s = Range::closed(0.0, 1e10);
inline const Range kCoordinate_m = Range::closed(-1e5, 1e5);
inline const Range kLength_m = Range::closed(0.0, 1e5);
inline const Range kHeading_rad = Range::closed(-1e4, 1e4);
inline const Range kSpeed = Range::above(0.0, 1e4);  // m/s, rad/s
inline const Range kStrength_mpa = Range::closed(0.0, 1e4);
inline const Range kPositive = Range::above(0.0, 1e7);
inline constexpr std::int64_t kMaxFloor = 10'000, kMaxLayer = 1'000'000, kMaxNozzles = 64;
inline constexpr std::int64_t kMaxGeometry = 10'000'000, kMaxPiece = 1'000'000;
inline constexpr std::int64_t kMaxWallId = 9'000'000'000'000'000'000;
inline constexpr std::size_t kMaxItems =
    50'000'000;  // waypoints of one nozzle, the most of anything
inline constexpr std::size_t kMaxLayers = 1'000'000, kMaxPlans = 100'000, kMaxEvents = 1'000'000;
inline constexpr std::size_t kMaxSmall = 10'000;  // files, stages, anchors, phases, joints
inline constexpr std::size_t kMaxText = 100'000;  // characters of a detail or warning

}  // namespace ccbuild::schedule::detail::read_limits
