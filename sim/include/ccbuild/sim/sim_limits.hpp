#pragma once
// What `ccbuild-sim` accepts on its command line. `ccbuild dry-run` checks every value it
// would pass against these before it starts a machine, so that a value a machine would
// refuse is an input error up front (exit 2), never a machine that fails to start and is
// started again and again.

#include <charconv>
#include <cstdint>
#include <string>

#include "ccbuild/common/format.hpp"

namespace ccbuild::sim::limits {

/// Simulated seconds per real second.
inline const Range kSpeed = Range::closed(1.0, 1e9);
/// A status every this many simulated seconds.
inline const Range kStatusPeriod_s = Range::closed(0.001, 86400.0);
/// Injected network faults, per message.
inline const Range kDrop = Range::closed(0.0, 0.9);
inline const Range kDuplicate = Range::closed(0.0, 1.0);
inline const Range kReorder = Range::closed(0.0, 0.9);
inline const Range kDelay = Range::closed(0.0, 0.9);
inline const Range kDelayMax_s = Range::closed(0.0, 60.0);
/// The material's interval window and the anchors' age, s.
inline const Range kMinInterval_s = Range::closed(0.0, 1e7);
inline const Range kMaxInterval_s = Range::closed(0.0, 1e9);
inline const Range kAnchorMinAge_s = Range::closed(0.0, 1e9);
/// Injected machine faults.
inline constexpr int kMaxPinFailures = 1000;
inline constexpr long kMaxCrashAfterJobs = 100'000'000;
inline const Range kStallAt_s = Range::closed(0.0, 1e9);
/// Floors and layers a clog may name (FLOOR:LAYER).
inline constexpr int kMaxClogFloor = 10'000;
inline constexpr int kMaxClogLayer = 1'000'000;

/// FLOOR:LAYER, whole numbers from 0 up to kMaxClogFloor and kMaxClogLayer, as
/// `ccbuild-sim --clog-at` and `ccbuild dry-run --inject clog=` take it. False for
/// anything else (then `floor` and `layer` are unspecified).
inline bool parse_floor_layer(const std::string& text, int& floor, int& layer) {
  const auto whole = [](const std::string& part, int max, int& value) {
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    return !part.empty() && ec == std::errc() && end == part.data() + part.size() && value >= 0 &&
           value <= max;
  };
  const std::size_t colon = text.find(':');
  return colon != std::string::npos && whole(text.substr(0, colon), kMaxClogFloor, floor) &&
         whole(text.substr(colon + 1), kMaxClogLayer, layer);
}

}  // namespace ccbuild::sim::limits
