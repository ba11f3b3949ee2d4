#pragma once
// The site's programme: when work starts (a local date and time in an IANA time zone), the
// working calendar (working hours per weekday, holidays) and which work needs a crew
// present. SiteCalendar turns it into working windows in the schedule's seconds, with the
// zone's daylight-saving changes (the date library on the system's tzdata), and writes
// seconds as ISO 8601 local timestamps with their offset. Without a programme the
// schedule runs around the clock from "day 1 00:00", as before.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/common/document.hpp"

namespace ccbuild::site {

/// Working hours on a local day: from `from_min` to `to_min` minutes after midnight
/// (to_min up to 1440).
struct WorkingHours {
  int from_min = 0, to_min = 0;
  bool operator==(const WorkingHours&) const = default;
};

/// A site's programme, as the building's `site:` or `--site FILE` states it.
struct SiteProgramme {
  /// The local start, seconds since 1970-01-01 00:00 local ("2027-03-01 07:00").
  std::int64_t start_local_s = 0;
  std::string time_zone;  ///< IANA name, "Europe/Berlin"
  /// Monday first; empty on a day off. Several spans a day may not overlap.
  std::array<std::vector<WorkingHours>, 7> week;
  std::vector<std::int32_t> holidays;  ///< local dates, days since 1970-01-01, sorted
  /// Printing needs a crew present (attended) or runs through the night (unattended).
  bool printing_attended = true;
  /// Pipe placing needs a crew (the machine's arm places them unattended otherwise).
  bool pipes_need_crew = true;
  /// The weather: constants (`temperature_c`, `wind_m_s`), or an hourly CSV (`weather`,
  /// resolved against the file that names it); none: 20 °C and calm.
  std::optional<double> temperature_c, wind_m_s;
  std::string weather_file;
  std::string source;  ///< "file:line" of the programme, for messages
};

/// Reads the programme keys of a site map (`start`, `time_zone`, `working_hours`,
/// `holidays`, `printing`, `pipes`, `temperature_c`, `wind_m_s`, `weather`); `placement_keys` are
/// the ones the building's reader has already taken (and are refused where the map is a `--site`
/// file). Returns nothing when the map has no programme key. Throws InputError naming the file,
/// line and key: an unknown time zone, a time that is not HH:MM, spans that overlap, a week without
/// working hours.
std::optional<SiteProgramme> read_site_programme(const Field& site,
                                                 const std::vector<std::string>& placement_keys);
/// The same from a `--site FILE`. Throws InputError as above, or when the file has no
/// `start`.
SiteProgramme load_site_programme(const std::string& path);

/// A stretch of working time, in seconds from the schedule's start.
struct WorkingWindow {
  double from_s = 0.0, to_s = 0.0;
};

/// A stretch of time over which the zone's offset from UTC holds.
struct ZoneOffset {
  std::int64_t from_utc_s = 0;  ///< when it took effect, seconds since the epoch (UTC)
  int offset_s = 0;             ///< local time minus UTC
  int previous_offset_s = 0;    ///< the offset before it took effect
  bool daylight = false;        ///< daylight-saving (summer) time
  std::string abbreviation;     ///< "CET", "CEST"
};

/// The programme's calendar: working windows, timestamps. Immutable once made (shared by
/// threads).
class SiteCalendar {
 public:
  /// The windows of the first `horizon_days` days from the start (back-to-back windows,
  /// across midnight, are one). Throws InputError when the time zone is not in the
  /// system's tzdata.
  explicit SiteCalendar(SiteProgramme programme, int horizon_days = kHorizonDays);
  static constexpr int kHorizonDays = 3653;  ///< ten years

  const SiteProgramme& programme() const { return programme_; }
  const std::vector<WorkingWindow>& windows() const { return windows_; }
  /// The earliest time from `from_s` at which `duration_s` of work fits in one working
  /// window; +infinity when none within the horizon does.
  double fit_s(double from_s, double duration_s) const;
  /// The longest working window, s (what the longest uninterrupted task may last).
  double longest_window_s() const { return longest_window_s_; }
  /// Whether [from_s, to_s] lies in one working window.
  bool within_one_window(double from_s, double to_s) const;
  /// "2027-03-01T07:00:00+01:00": the local time at `t_s`, to the second (rounded).
  std::string timestamp(double t_s) const;
  /// "2027-03-01": the local date at `t_s`.
  std::string local_date(double t_s) const;
  /// "Mon 2027-03-01 07:00" ("Mon 2027-03-01 07:00:09" with seconds): for people.
  std::string local_text(double t_s, bool with_seconds = false) const;
  /// Days since 1970-01-01 of the local date at `t_s`.
  std::int32_t local_day(double t_s) const;
  /// Schedule seconds of a UTC time (seconds since the epoch).
  double seconds_of_utc(std::int64_t utc_s) const {
    return static_cast<double>(utc_s - start_utc_s_);
  }
  /// The UTC time (seconds since the epoch) of a local time in the zone (a time in a
  /// spring-forward gap is the change; one that occurs twice, its first).
  std::int64_t utc_of_local(std::int64_t local_s) const;
  /// The UTC time (seconds since the epoch) at `t_s`, rounded to the second.
  std::int64_t utc_of(double t_s) const { return start_utc_s_ + std::llround(t_s); }
  /// The zone's offsets in force from `from_s` to `to_s`: the first is the one in force at
  /// `from_s` (it took effect before), then one per change, in order.
  std::vector<ZoneOffset> zone_offsets(double from_s, double to_s) const;
  /// The version of the tzdata the windows were computed with ("2025b").
  std::string tzdb_version() const;
  /// "Mon-Fri 07:00-17:00", the week in words.
  std::string week_text() const;

 private:
  SiteProgramme programme_;
  const void* zone_ = nullptr;    ///< the date library's time_zone (static), kept opaque
  std::int64_t start_utc_s_ = 0;  ///< seconds since the epoch (UTC)
  std::vector<WorkingWindow> windows_;
  double longest_window_s_ = 0.0;
};

/// A schedule time for people: the calendar's local date and time when there is one
/// ("Mon 2027-03-01 07:00"), else the day and time from day 1 00:00 ("day 3 07:00");
/// seconds too when asked.
std::string time_text(const SiteCalendar* calendar, double t_s, bool with_seconds = false);

/// "07:00-17:00".
std::string to_string(const WorkingHours& hours);
/// "07:00-17:00" back, or nothing.
std::optional<WorkingHours> parse_working_hours(const std::string& text);
/// "2027-03-01 07:00" (or with a T, or with seconds: 07:00:30) as seconds since
/// 1970-01-01 00:00 local, or nothing.
std::optional<std::int64_t> parse_local_start(const std::string& text);
/// "2027-03-01" as days since 1970-01-01, or nothing.
std::optional<std::int32_t> parse_local_date(const std::string& text);
/// The inverses: "2027-03-01 07:00", "2027-03-01".
std::string local_start_text(std::int64_t local_s);
std::string local_date_text(std::int32_t day);
/// The weekday keys, Monday first: "mon", ..., "sun".
const std::array<const char*, 7>& weekday_keys();
/// The weekdays as the text and the exports name them, Monday first: "Mon", ..., "Sun".
const std::array<const char*, 7>& weekday_names();
/// The weekday of `day`, days since 1970-01-01 (a Thursday), Monday first: 0 ... 6.
int weekday_of(std::int64_t day);

}  // namespace ccbuild::site
