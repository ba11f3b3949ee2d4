#include "ccbuild/site/site.hpp"

#include <date/tz.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "ccbuild/common/dates.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::site {
namespace {

using std::chrono::minutes;
using std::chrono::seconds;

constexpr std::array<const char*, 7> kDayNames = {"mon", "tue", "wed", "thu", "fri", "sat", "sun"};
constexpr std::size_t kMostHolidays = 2000;
constexpr std::size_t kMostSpansPerDay = 8;
/// A task may end this much after its window does (rounding of the schedule's seconds).
constexpr double kWindowSlack_s = 1e-6;

const std::vector<std::string> kProgrammeKeys = {"start",         "time_zone", "working_hours",
                                                 "holidays",      "printing",  "pipes",
                                                 "temperature_c", "wind_m_s",  "weather"};

std::string clock_text(int minutes_of_day) {
  return printf_string("%02d:%02d", minutes_of_day / 60, minutes_of_day % 60);
}

/// "HH:MM-HH:MM" as its two clocks, in any order; nothing when either is no clock.
std::optional<std::pair<int, int>> split_span(const std::string& text) {
  const auto dash = text.find('-');
  if (dash == std::string::npos) return std::nullopt;
  const auto from = parse_clock(text.substr(0, dash)), to = parse_clock(text.substr(dash + 1));
  if (!from || !to) return std::nullopt;
  return std::make_pair(*from, *to);
}

WorkingHours read_span(const Field& f) {
  const std::string text = f.as_string();
  const auto span = split_span(text);
  if (!span)
    f.fail("expected working hours as HH:MM-HH:MM (e.g. 07:00-17:00), got '" + echoed(text) + "'");
  if (span->second <= span->first)
    f.fail("'" + text +
           "' ends before it starts; a span lies within one day (a night shift is "
           "22:00-24:00 on one day and 00:00-06:00 on the next, which join)");
  return {span->first, span->second};
}

/// The weekdays a `working_hours` key names: "mon", "mon-fri", "sat-sun".
std::vector<int> read_days(const Field& where, const std::string& key) {
  const auto index = [](const std::string& name) {
    for (int d = 0; d < 7; ++d)
      if (name == kDayNames[d]) return d;
    return -1;
  };
  const auto dash = key.find('-');
  const int first = index(key.substr(0, dash));
  const int last = dash == std::string::npos ? first : index(key.substr(dash + 1));
  if (first < 0 || last < 0 || last < first)
    where.fail("'" + key +
               "' is not a weekday or a range of them: expected mon, tue, wed, thu, fri, sat, "
               "sun or a range such as mon-fri");
  std::vector<int> days;
  for (int d = first; d <= last; ++d) days.push_back(d);
  return days;
}

void read_week(const Field& f, SiteProgramme& p) {
  if (!f.is_map())
    f.fail("expected a map of weekdays to working hours, e.g. {mon-fri: 07:00-17:00, sat: off}");
  std::array<bool, 7> named{};
  for (const auto& [key, node] : f.node().entries) {
    const Field value = f.child(node, join_path(f.path(), key));
    std::vector<WorkingHours> spans;
    if (value.is_scalar() && value.as_string() == "off") {
    } else if (value.is_sequence()) {
      const auto items = value.items();
      if (items.size() > kMostSpansPerDay)
        value.fail(printf_string("at most %zu spans a day", kMostSpansPerDay));
      for (const auto& item : items) spans.push_back(read_span(item));
    } else {
      spans.push_back(read_span(value));
    }
    std::sort(spans.begin(), spans.end(),
              [](const WorkingHours& a, const WorkingHours& b) { return a.from_min < b.from_min; });
    for (std::size_t k = 1; k < spans.size(); ++k)
      if (spans[k].from_min < spans[k - 1].to_min)
        value.fail("spans " + to_string(spans[k - 1]) + " and " + to_string(spans[k]) + " overlap");
    for (int d : read_days(value, key)) {
      if (named[d]) value.fail(std::string(kDayNames[d]) + " is given working hours twice");
      named[d] = true;
      p.week[d] = spans;
    }
  }
  if (std::all_of(p.week.begin(), p.week.end(), [](const auto& day) { return day.empty(); }))
    f.fail("no working hours on any day of the week: nothing could ever be built");
}

}  // namespace

std::string to_string(const WorkingHours& hours) {
  return clock_text(hours.from_min) + "-" + clock_text(hours.to_min);
}

std::optional<WorkingHours> parse_working_hours(const std::string& text) {
  const auto span = split_span(text);
  if (!span || span->second <= span->first) return std::nullopt;
  return WorkingHours{span->first, span->second};
}

std::optional<std::int64_t> parse_local_start(const std::string& text) {
  return parse_date_time(text);
}

std::optional<std::int32_t> parse_local_date(const std::string& text) {
  return parse_date(text);
}

std::string local_date_text(std::int32_t day) {
  return date_text(day);
}

std::string local_start_text(std::int64_t local_s) {
  const auto day = static_cast<std::int32_t>(local_s / 86400);  // from 1971 on: positive
  const auto in_day = static_cast<int>(local_s - day * 86400LL);
  const std::string text = local_date_text(day) + " " + clock_text(in_day / 60);
  return in_day % 60 == 0 ? text : text + printf_string(":%02d", in_day % 60);
}

const std::array<const char*, 7>& weekday_keys() {
  return kDayNames;
}

const std::array<const char*, 7>& weekday_names() {
  static constexpr std::array<const char*, 7> kNames = {"Mon", "Tue", "Wed", "Thu",
                                                        "Fri", "Sat", "Sun"};
  return kNames;
}

int weekday_of(std::int64_t day) {
  return static_cast<int>(((day % 7) + 7 + 3) % 7);  // day 0 was a Thursday (3)
}

std::optional<SiteProgramme> read_site_programme(const Field& site,
                                                 const std::vector<std::string>& placement_keys) {
  std::vector<std::string> allowed = kProgrammeKeys;
  allowed.insert(allowed.end(), placement_keys.begin(), placement_keys.end());
  MapReader map(site, allowed);
  map.reject_unknown();
  bool any = false;
  for (const auto& key : kProgrammeKeys) any = any || map.has(key);
  if (!any) return std::nullopt;

  SiteProgramme p;
  p.source = site.file() + ":" + std::to_string(site.line());
  const Field start = map.required("start");
  const auto local = parse_local_start(start.as_string());
  if (!local)
    start.fail(
        "expected the local date and time work starts, as YYYY-MM-DD HH:MM[:SS] (e.g. "
        "2027-03-01 07:00; the zone is time_zone's), got '" +
        echoed(start.as_string()) + "'");
  p.start_local_s = *local;
  const Field zone = map.required("time_zone");
  p.time_zone = zone.as_string();
  try {
    date::locate_zone(p.time_zone);
  } catch (const std::exception&) {
    zone.fail("'" + p.time_zone +
              "' is not a time zone of the system's tzdata: expected an IANA name such as "
              "Europe/Berlin or America/New_York (see /usr/share/zoneinfo)");
  }
  if (auto week = map.optional("working_hours")) {
    read_week(*week, p);
  } else {
    for (int d = 0; d < 5; ++d) p.week[d] = {{7 * 60, 17 * 60}};  // Mon-Fri 07:00-17:00
  }
  if (auto holidays = map.optional("holidays")) {
    const auto items = holidays->items();
    if (items.size() > kMostHolidays)
      holidays->fail(printf_string("at most %zu holidays, got %zu", kMostHolidays, items.size()));
    for (const auto& item : items) {
      const auto day = parse_local_date(item.as_string());
      if (!day) item.fail("expected a date as YYYY-MM-DD, got '" + echoed(item.as_string()) + "'");
      p.holidays.push_back(*day);
    }
    std::sort(p.holidays.begin(), p.holidays.end());
    p.holidays.erase(std::unique(p.holidays.begin(), p.holidays.end()), p.holidays.end());
  }
  if (auto printing = map.optional("printing")) {
    const std::string how = printing->as_string();
    if (how != "attended" && how != "unattended")
      printing->fail(
          "expected attended (a crew present: printing only in working hours, the default) or "
          "unattended (printing runs on through the night), got '" +
          echoed(how) + "'");
    p.printing_attended = how == "attended";
  }
  if (auto pipes = map.optional("pipes")) {
    const std::string how = pipes->as_string();
    if (how != "crew" && how != "unattended")
      pipes->fail(
          "expected crew (pipes placed in working hours, the default) or unattended (by the "
          "machine's arm, at any hour), got '" +
          echoed(how) + "'");
    p.pipes_need_crew = how == "crew";
  }
  if (auto t = map.optional("temperature_c"))
    p.temperature_c = t->as_number_in(Range::closed(-60.0, 60.0), "°C");
  if (auto w = map.optional("wind_m_s"))
    p.wind_m_s = w->as_number_in(Range::closed(0.0, 80.0), "m/s");
  if (auto weather = map.optional("weather")) {
    if (p.temperature_c || p.wind_m_s)
      weather->fail(
          "give either an hourly `weather` file or constant `temperature_c` and "
          "`wind_m_s`, not both");
    const std::filesystem::path file = weather->as_string();
    const std::filesystem::path base = std::filesystem::path(site.file()).parent_path();
    p.weather_file = (file.is_absolute() || base.empty() ? file : base / file).string();
    // Named here, with this file and line, when it cannot be read at all (its contents
    // are checked line by line where it is read).
    std::error_code ec;
    const auto status = std::filesystem::status(p.weather_file, ec);
    if (!std::filesystem::exists(status))
      weather->fail("the weather file '" + echoed(p.weather_file) +
                    "' does not exist (a relative path is taken from this file's folder)");
    if (!std::filesystem::is_regular_file(status))
      weather->fail("the weather file '" + echoed(p.weather_file) +
                    "' is not a regular file (a folder, FIFO or device?); expected a CSV file");
    if (::access(p.weather_file.c_str(), R_OK) != 0)
      weather->fail("the weather file '" + echoed(p.weather_file) +
                    "' cannot be read (permissions?)");
  }
  return p;
}

SiteProgramme load_site_programme(const std::string& path) {
  const Document doc = load_document(path);
  const Field root = Field::root(doc);
  if (!root.is_map()) root.fail("expected a map: start, time_zone, working_hours, ...");
  auto p = read_site_programme(root, {});
  if (!p) root.fail("a site file needs at least `start` and `time_zone`");
  return *p;
}

SiteCalendar::SiteCalendar(SiteProgramme programme, int horizon_days)
    : programme_(std::move(programme)) {
  const date::time_zone* zone = nullptr;
  try {
    zone = date::locate_zone(programme_.time_zone);
  } catch (const std::exception&) {
    throw InputError(programme_.source, 0, "time_zone",
                     "'" + programme_.time_zone + "' is not a time zone of the system's tzdata");
  }
  zone_ = zone;
  const auto to_utc_s = [zone](std::int64_t local_s) {
    const date::local_seconds local{seconds(local_s)};
    // A local time in a spring-forward gap is the moment of the change; one that occurs
    // twice in autumn is its first occurrence.
    return zone->to_sys(local, date::choose::earliest).time_since_epoch().count();
  };
  start_utc_s_ = to_utc_s(programme_.start_local_s);
  const std::int64_t first_day = programme_.start_local_s / 86400;
  for (std::int64_t day = first_day; day < first_day + horizon_days; ++day) {
    if (std::binary_search(programme_.holidays.begin(), programme_.holidays.end(),
                           static_cast<std::int32_t>(day)))
      continue;
    // 1970-01-01 was a Thursday (index 3, Monday first).
    const int weekday = static_cast<int>(((day % 7) + 7 + 3) % 7);
    for (const WorkingHours& h : programme_.week[weekday]) {
      const double from_s =
          static_cast<double>(to_utc_s((day * 1440 + h.from_min) * 60) - start_utc_s_);
      const double to_s =
          static_cast<double>(to_utc_s((day * 1440 + h.to_min) * 60) - start_utc_s_);
      if (to_s <= 0.0 || to_s <= from_s) continue;
      const WorkingWindow w{std::max(0.0, from_s), to_s};
      if (!windows_.empty() && windows_.back().to_s >= w.from_s)
        windows_.back().to_s = std::max(windows_.back().to_s, w.to_s);
      else
        windows_.push_back(w);
    }
  }
  for (const auto& w : windows_) longest_window_s_ = std::max(longest_window_s_, w.to_s - w.from_s);
}

double SiteCalendar::fit_s(double from_s, double duration_s) const {
  if (duration_s > longest_window_s_ + kWindowSlack_s)
    return std::numeric_limits<double>::infinity();
  auto it = std::upper_bound(windows_.begin(), windows_.end(), from_s - kWindowSlack_s,
                             [](double t, const WorkingWindow& w) { return t < w.to_s; });
  for (; it != windows_.end(); ++it) {
    const double t = std::max(from_s, it->from_s);
    if (t + duration_s <= it->to_s + kWindowSlack_s) return t;
  }
  return std::numeric_limits<double>::infinity();
}

bool SiteCalendar::within_one_window(double from_s, double to_s) const {
  return fit_s(from_s, to_s - from_s) <= from_s + kWindowSlack_s;
}

namespace {
date::sys_seconds sys_at(std::int64_t start_utc_s, double t_s) {
  return date::sys_seconds{seconds(start_utc_s + std::llround(t_s))};
}
}  // namespace

std::int64_t SiteCalendar::utc_of_local(std::int64_t local_s) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  return zone->to_sys(date::local_seconds{seconds(local_s)}, date::choose::earliest)
      .time_since_epoch()
      .count();
}

std::string SiteCalendar::timestamp(double t_s) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  return date::format("%FT%T%Ez", date::make_zoned(zone, sys_at(start_utc_s_, t_s)));
}

std::string SiteCalendar::local_date(double t_s) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  return date::format("%F", date::make_zoned(zone, sys_at(start_utc_s_, t_s)));
}

std::string SiteCalendar::local_text(double t_s, bool with_seconds) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  return date::format(with_seconds ? "%a %F %H:%M:%S" : "%a %F %H:%M",
                      date::make_zoned(zone, sys_at(start_utc_s_, t_s)));
}

std::string time_text(const SiteCalendar* calendar, double t_s, bool with_seconds) {
  return calendar ? calendar->local_text(t_s, with_seconds) : day_clock_text(t_s, with_seconds);
}

std::int32_t SiteCalendar::local_day(double t_s) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  const auto local = date::make_zoned(zone, sys_at(start_utc_s_, t_s)).get_local_time();
  return static_cast<std::int32_t>(date::floor<date::days>(local).time_since_epoch().count());
}

std::vector<ZoneOffset> SiteCalendar::zone_offsets(double from_s, double to_s) const {
  const auto* zone = static_cast<const date::time_zone*>(zone_);
  std::vector<ZoneOffset> offsets;
  const date::sys_seconds end = sys_at(start_utc_s_, to_s);
  for (date::sys_seconds at = sys_at(start_utc_s_, from_s);;) {
    const date::sys_info info = zone->get_info(at);
    // An offset in force since before 1970 (a zone without changes since, or UTC, whose
    // "since" is the beginning of time) is said to start then, as calendars write it.
    const bool before_1970 = info.begin < date::sys_seconds{seconds(0)};
    const int previous_offset_s =
        before_1970 ? static_cast<int>(info.offset.count())
                    : static_cast<int>(zone->get_info(info.begin - seconds(1)).offset.count());
    offsets.push_back({before_1970 ? 0 : info.begin.time_since_epoch().count(),
                       static_cast<int>(info.offset.count()), previous_offset_s,
                       info.save.count() != 0, info.abbrev});
    if (info.end >= end) break;
    at = info.end;
  }
  return offsets;
}

std::string SiteCalendar::tzdb_version() const {
  std::string version = date::get_tzdb().version;
  if (version != "unknown") return version;
  // Debian's tzdata has no +VERSION file; its tzdata.zi starts "# version 2025b".
  std::FILE* zi = std::fopen("/usr/share/zoneinfo/tzdata.zi", "r");
  if (!zi) return version;
  char line[64] = {};
  char found[32] = {};
  if (std::fgets(line, sizeof line, zi) && std::sscanf(line, "# version %31s", found) == 1)
    version = found;
  std::fclose(zi);
  return version;
}

std::string SiteCalendar::week_text() const {
  // Runs of consecutive days with the same hours: "Mon-Fri 07:00-17:00, Sat 07:00-12:00".
  const auto& kNames = weekday_names();
  std::string out;
  for (int d = 0; d < 7;) {
    int last = d;
    while (last + 1 < 7 && programme_.week[last + 1] == programme_.week[d]) ++last;
    if (!programme_.week[d].empty()) {
      std::string hours;
      for (const auto& h : programme_.week[d]) hours += (hours.empty() ? "" : ", ") + to_string(h);
      out += (out.empty() ? "" : "; ") + std::string(kNames[d]) +
             (last > d ? std::string("-") + kNames[last] : "") + " " + hours;
    }
    d = last + 1;
  }
  return out;
}

}  // namespace ccbuild::site
