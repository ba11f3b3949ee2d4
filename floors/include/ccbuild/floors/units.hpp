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

/// Which way a figure for messages is rounded. A figure a message proposes as a fix is
/// rounded towards the side that passes when applied as written: a least value up, a
/// greatest value down.
enum class Towards { kNearest, kUp, kDown };

/// `value` with `decimals` decimals, rounded as said (within 1e-9 of a step it stays).
double rounded(double value, int decimals, Towards towards);

/// A length for messages, in the user's unit: "3.000 m", "9.843 ft".
std::string length_text(double value_m, LengthUnit unit, int decimals = 3,
                        Towards towards = Towards::kNearest);

/// A length in `unit` (a bare number, for tables whose header names the unit).
constexpr double length_in(double value_m, LengthUnit unit) {
  return value_m / meters_per(unit);
}

/// A small length (a clearance, a gap) where the building's unit would hide it: "24 mm",
/// "0.3 mm" under 10 mm; for feet, inches: "0.94 in", "1.5 in" from an inch up.
std::string fine_length_text(double value_m, LengthUnit unit);

/// Concrete is ordered in cubic metres, or cubic yards where lengths are in feet.
inline constexpr double kCubicMetersPerCubicYard = 0.764554857984;

/// "m³" or "yd³": the volume unit that goes with `unit`.
std::string volume_unit(LengthUnit unit);

/// A volume in the unit that goes with `unit` (a bare number).
constexpr double volume_in(double value_m3, LengthUnit unit) {
  return unit == LengthUnit::kFoot ? value_m3 / kCubicMetersPerCubicYard : value_m3;
}

/// "823.65 m³", "1077.30 yd³".
std::string volume_text(double value_m3, LengthUnit unit, int decimals = 2);

/// A flow of concrete for messages, per hour: "30.0 m³/h", "39.2 yd³/h".
std::string flow_text(double value_m3_s, LengthUnit unit, int decimals = 1);

/// A speed for messages: "0.100 m/s", "0.328 ft/s".
std::string speed_text(double value_m_s, LengthUnit unit, int decimals = 3,
                       Towards towards = Towards::kNearest);

/// Parses a length with an optional unit suffix ("40ft", "12.5 m", "3"); a bare number
/// is in `default_unit`. Returns metres, nullopt when the text is not such a length.
std::optional<double> parse_length_m(const std::string& text, LengthUnit default_unit);

}  // namespace ccbuild::floors
