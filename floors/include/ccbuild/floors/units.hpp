#pragma once
// Length units accepted in building and plan files. Everything inside ccbuild is SI;
// files may say `units: ft` (the papers use feet) and are converted when read.

#include <optional>
#include <string>

namespace ccbuild::floors {

enum class LengthUnit { kMeter, kFoot };

inline constexpr double kMetersPerFoot = 0.3048;

/// Metres per one `unit`.
constexpr double meters_per(LengthUnit unit) {
  return unit == LengthUnit::kFoot ? kMetersPerFoot : 1.0;
}

/// "m" or "ft"; nullopt for anything else.
std::optional<LengthUnit> parse_length_unit(const std::string& text);
std::string to_string(LengthUnit unit);

/// A length for messages, in the user's unit: "3.000 m", "9.843 ft".
std::string length_text(double value_m, LengthUnit unit, int decimals = 3);

/// Parses a length with an optional unit suffix ("40ft", "12.5 m", "3"); a bare number
/// is in `default_unit`. Returns metres, nullopt when the text is not such a length.
std::optional<double> parse_length_m(const std::string& text, LengthUnit default_unit);

}  // namespace ccbuild::floors
