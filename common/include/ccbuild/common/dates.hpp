#pragma once
// The one strict reader (and writer) of dates and clocks in files and flags: a site's
// start and holidays, its working hours, weather timestamps, `export --start`. Exactly the
// digits the format shows, ASCII only (no sign, no space, no fewer digits: `2027-03-+1`,
// `2027- 3- 1` and `7:00` are refused), each field in its range, days in their month.
// Days count from 1970-01-01 (day 0) in the proleptic Gregorian calendar.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ccbuild {

/// The years a date may name: a building site's programme, with room for a long one.
inline constexpr int kFirstDateYear = 1971;
inline constexpr int kLastDateYear = 2200;

/// Days since 1970-01-01 of `year`-`month`-`day` (any valid civil date).
std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day);

/// Days since 1970-01-01 of "YYYY-MM-DD" from kFirstDateYear to kLastDateYear; nothing
/// otherwise.
std::optional<std::int32_t> parse_date(std::string_view text);
/// Minutes after midnight of "HH:MM", 00:00 to 24:00 (the end of a day); nothing otherwise.
std::optional<int> parse_clock(std::string_view text);
/// Seconds since 1970-01-01 00:00 (a local time, no zone) of "YYYY-MM-DD HH:MM",
/// "YYYY-MM-DDTHH:MM" or either with ":SS"; 24:00 is refused. Nothing otherwise.
std::optional<std::int64_t> parse_date_time(std::string_view text);
/// Seconds east of UTC of "Z", "+HH:MM" or "-HH:MM" (at most 18:00); nothing otherwise.
std::optional<int> parse_utc_offset(std::string_view text);

/// "YYYY-MM-DD" of a day since 1970-01-01.
std::string date_text(std::int64_t day);
/// "YYYY-MM-DD HH:MM:SS" of seconds since 1970-01-01 00:00.
std::string date_time_text(std::int64_t s);

}  // namespace ccbuild
