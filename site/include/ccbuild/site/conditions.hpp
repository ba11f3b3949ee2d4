#pragma once
// The weather on site and what it does to the concrete: air temperature and wind, a
// constant or an hourly series (each reading holds until the next), and the concrete's
// equivalent age at 20 °C by the maturity method (ASTM C1074): age accrues at the
// material's age-function rate at the air temperature, so a warm afternoon ages it faster
// and a cold night slower. docs/schedule.md (Weather and equivalent age) says more.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ccbuild/floors/material.hpp"
#include "ccbuild/rules/age_clock.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::site {

/// One reading, from `t_s` (schedule seconds) until the next one.
struct WeatherReading {
  double t_s = 0.0;
  double temperature_c = 20.0;
  double wind_m_s = 0.0;
};

struct SiteConditions {
  /// By time, at least one. Before the first reading its values hold, and after the last.
  std::vector<WeatherReading> readings;
  std::filesystem::path file;  ///< the CSV they came from; empty for constants
  std::string source;          ///< "constant 8.0 °C, wind 3.0 m/s" or the file, for people
};

/// The most readings a weather file may hold (ten years, hourly).
inline constexpr std::size_t kMaxWeatherReadings = 100'000;

/// Reads a weather CSV: a header `timestamp,temperature_c,wind_m_s`, then one row per
/// reading, timestamps strictly increasing, ISO 8601 with an offset
/// (2027-03-01T07:00:00+01:00, or Z) or local to the site's zone (2027-03-01 07:00).
/// Throws InputError naming the file, the line and the column: an unreadable timestamp,
/// a temperature outside -60..60 °C, a wind outside 0..80 m/s, too many rows.
SiteConditions read_weather_csv(const std::filesystem::path& path, const SiteCalendar& calendar);

/// Constant conditions.
SiteConditions constant_conditions(double temperature_c, double wind_m_s);

/// Equivalent age at 20 °C on site, as a function of the schedule's time: piecewise
/// linear, its slope the age function's rate at each reading's temperature.
class EquivalentAge {
 public:
  EquivalentAge(const SiteConditions& conditions, const floors::MaturityFunction& function);

  /// Equivalent seconds accrued from 0 to `t_s`.
  double at(double t_s) const { return clock_.at(t_s); }
  /// The equivalent age at `to_s` of concrete placed at `from_s`.
  double age(double from_s, double to_s) const { return clock_.age(from_s, to_s); }
  /// The earliest time at which concrete placed at `from_s` is `age_s` old in equivalent
  /// age; +infinity when it never is (a Nurse-Saul rate of 0 for ever).
  double after(double from_s, double age_s) const { return clock_.after(from_s, age_s); }
  /// The same as a clock the dispatcher and the machines take (rules/age_clock.hpp).
  const rules::AgeClock& clock() const { return clock_; }

  const SiteConditions& conditions() const { return *conditions_; }
  const floors::MaturityFunction& function() const { return function_; }
  /// The reading in force at `t_s`.
  const WeatherReading& reading_at(double t_s) const;
  /// The earliest start from `from_s` at which every reading in force over
  /// [start, start + length_s] is `ok`; +infinity when none is.
  double fit_s(double from_s, double length_s,
               const std::function<bool(const WeatherReading&)>& ok) const;

 private:
  const SiteConditions* conditions_;
  floors::MaturityFunction function_;
  rules::AgeClock clock_;
};

/// When concrete placed at `from_s` is `age_s` old: in equivalent age by `maturity` (site
/// weather), else in real time (20 °C). The one statement of "old enough" that layers,
/// slabs and anchors are held to; +infinity when it never is.
double age_reached_s(const EquivalentAge* maturity, double from_s, double age_s);

}  // namespace ccbuild::site
