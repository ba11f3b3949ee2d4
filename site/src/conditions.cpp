#include "ccbuild/site/conditions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "ccbuild/common/dates.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::site {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const Range kTemperature_c = Range::closed(-60.0, 60.0);
const Range kWind_m_s = Range::closed(0.0, 80.0);

/// Seconds since the epoch (UTC) of an ISO 8601 timestamp; without an offset it is local
/// to the calendar's zone. Nothing when it cannot be read.
std::optional<std::int64_t> parse_timestamp(const std::string& text, const SiteCalendar& calendar) {
  // The date and time, then what is left: "", "Z", "+01:00", "-05:00".
  std::size_t end = text.size();
  std::optional<int> offset_s;
  if (!text.empty() && (text.back() == 'Z' || text.back() == 'z')) {
    offset_s = 0;
    end -= 1;
  } else if (text.size() > 6 && (text[text.size() - 6] == '+' || text[text.size() - 6] == '-')) {
    offset_s = parse_utc_offset(std::string_view(text).substr(text.size() - 6));
    if (!offset_s) return std::nullopt;
    end -= 6;
  }
  const auto local = parse_local_start(text.substr(0, end));
  if (!local) return std::nullopt;
  return offset_s ? *local - *offset_s : calendar.utc_of_local(*local);
}

}  // namespace

SiteConditions constant_conditions(double temperature_c, double wind_m_s) {
  SiteConditions c;
  c.readings.push_back({0.0, temperature_c, wind_m_s});
  c.source = printf_string("constant %.1f °C, wind %.1f m/s", temperature_c, wind_m_s);
  return c;
}

SiteConditions read_weather_csv(const std::filesystem::path& path, const SiteCalendar& calendar) {
  const std::string text = read_text_file(path);
  const std::string file = path.string();
  SiteConditions c;
  c.file = path;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) {
      const auto a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    if (!header) {
      if (cells != std::vector<std::string>{"timestamp", "temperature_c", "wind_m_s"})
        throw InputError(
            file, number, "header",
            "expected the header `timestamp,temperature_c,wind_m_s`, got '" + echoed(line) + "'");
      header = true;
      continue;
    }
    if (cells.size() != 3)
      throw InputError(file, number, "",
                       printf_string("expected 3 values (timestamp, temperature_c, wind_m_s), got "
                                     "%zu",
                                     cells.size()));
    if (c.readings.size() >= kMaxWeatherReadings)
      throw InputError(
          file, number, "",
          printf_string("more than %zu readings (ten years, hourly)", kMaxWeatherReadings));
    const auto utc = parse_timestamp(cells[0], calendar);
    if (!utc)
      throw InputError(
          file, number, "timestamp",
          "expected an ISO 8601 date and time, with an offset (2027-03-01T07:00:00+01:00) "
          "or local to the site's time zone (2027-03-01 07:00), got '" +
              echoed(cells[0]) + "'");
    WeatherReading r;
    r.t_s = calendar.seconds_of_utc(*utc);
    const auto number_in = [&](const std::string& cell, const char* column, const Range& range,
                               const char* unit) {
      char* stop = nullptr;
      const double v = std::strtod(cell.c_str(), &stop);
      if (cell.empty() || *stop != '\0' || !std::isfinite(v))
        throw InputError(file, number, column, "expected a number, got '" + echoed(cell) + "'");
      const std::string wrong = range.violation(v, cell, unit);
      if (!wrong.empty()) throw InputError(file, number, column, wrong);
      return v;
    };
    r.temperature_c = number_in(cells[1], "temperature_c", kTemperature_c, "°C");
    r.wind_m_s = number_in(cells[2], "wind_m_s", kWind_m_s, "m/s");
    if (!c.readings.empty() && r.t_s <= c.readings.back().t_s)
      throw InputError(file, number, "timestamp",
                       "timestamps must increase down the file ('" + cells[0] +
                           "' is not after the "
                           "row before)");
    c.readings.push_back(r);
  }
  if (c.readings.empty()) throw InputError(file, number, "", "no readings");
  c.source = printf_string("%s (%zu readings)", file.c_str(), c.readings.size());
  return c;
}

EquivalentAge::EquivalentAge(const SiteConditions& conditions,
                             const floors::MaturityFunction& function)
    : conditions_(&conditions), function_(function) {
  // Each reading's rate from its time on; the age accrued to each reading.
  const auto& r = conditions.readings;
  std::vector<rules::AgeClock::Breakpoint> points(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    points[i].t_s = r[i].t_s;
    points[i].rate = function.rate(r[i].temperature_c);
    points[i].e_s =
        i == 0 ? 0.0 : points[i - 1].e_s + points[i - 1].rate * (r[i].t_s - r[i - 1].t_s);
  }
  // Counted from the schedule's start: E(0) = 0.
  const double at_zero = rules::AgeClock(points).at(0.0);
  for (auto& p : points) p.e_s -= at_zero;
  clock_ = rules::AgeClock(std::move(points));
}

const WeatherReading& EquivalentAge::reading_at(double t_s) const {
  const auto& r = conditions_->readings;
  const auto it = std::upper_bound(r.begin(), r.end(), t_s,
                                   [](double t, const WeatherReading& w) { return t < w.t_s; });
  return it == r.begin() ? r.front() : *(it - 1);
}

double EquivalentAge::fit_s(double from_s, double length_s,
                            const std::function<bool(const WeatherReading&)>& ok) const {
  const auto& r = conditions_->readings;
  double start_s = from_s;
  auto it = std::upper_bound(r.begin(), r.end(), start_s,
                             [](double t, const WeatherReading& w) { return t < w.t_s; });
  std::size_t i = it == r.begin() ? 0 : static_cast<std::size_t>(it - r.begin()) - 1;
  while (true) {
    // Every reading in force over [start, start + length): from i on.
    std::size_t bad = r.size();
    for (std::size_t k = i; k < r.size(); ++k) {
      if (k > i && r[k].t_s >= start_s + length_s - 1e-9) break;
      if (!ok(r[k])) {
        bad = k;
        break;
      }
    }
    if (bad == r.size()) return start_s;
    if (bad + 1 >= r.size()) return kInf;  // the last reading holds for ever
    i = bad + 1;
    start_s = r[i].t_s;
  }
}

double age_reached_s(const EquivalentAge* maturity, double from_s, double age_s) {
  return maturity ? maturity->after(from_s, age_s) : from_s + age_s;
}

}  // namespace ccbuild::site
