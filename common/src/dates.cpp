#include "ccbuild/common/dates.hpp"

#include <cstdio>

namespace ccbuild {
namespace {

/// The number written by exactly `digits` ASCII digits at `at`, or -1.
int digits_at(std::string_view text, std::size_t at, std::size_t digits) {
  if (at + digits > text.size()) return -1;
  int value = 0;
  for (std::size_t k = at; k < at + digits; ++k) {
    if (text[k] < '0' || text[k] > '9') return -1;
    value = value * 10 + (text[k] - '0');
  }
  return value;
}

bool leap(std::int64_t year) {
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

unsigned days_in_month(std::int64_t year, unsigned month) {
  static const unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && leap(year) ? 29 : kDays[month - 1];
}

/// The civil date of a day since 1970-01-01 (Howard Hinnant's algorithm, in words: count
/// in 400-year eras that start on 1 March, so that the leap day ends a year).
void civil_from_days(std::int64_t z, std::int64_t& year, unsigned& month, unsigned& day) {
  z += 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const auto doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  day = doy - (153 * mp + 2) / 5 + 1;
  month = mp < 10 ? mp + 3 : mp - 9;
  year = static_cast<std::int64_t>(yoe) + era * 400 + (month <= 2);
}

}  // namespace

std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day) {
  year -= month <= 2;
  const std::int64_t era = (year >= 0 ? year : year - 399) / 400;
  const auto yoe = static_cast<unsigned>(year - era * 400);
  const unsigned doy = (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

std::optional<std::int32_t> parse_date(std::string_view text) {
  if (text.size() != 10 || text[4] != '-' || text[7] != '-') return std::nullopt;
  const int year = digits_at(text, 0, 4), month = digits_at(text, 5, 2),
            day = digits_at(text, 8, 2);
  if (year < kFirstDateYear || year > kLastDateYear || month < 1 || month > 12 || day < 1 ||
      static_cast<unsigned>(day) > days_in_month(year, static_cast<unsigned>(month)))
    return std::nullopt;
  return static_cast<std::int32_t>(
      days_from_civil(year, static_cast<unsigned>(month), static_cast<unsigned>(day)));
}

std::optional<int> parse_clock(std::string_view text) {
  if (text.size() != 5 || text[2] != ':') return std::nullopt;
  const int hour = digits_at(text, 0, 2), minute = digits_at(text, 3, 2);
  if (hour < 0 || minute < 0 || minute > 59 || hour > 24 || (hour == 24 && minute != 0))
    return std::nullopt;
  return hour * 60 + minute;
}

std::optional<std::int64_t> parse_date_time(std::string_view text) {
  if (text.size() != 16 && text.size() != 19) return std::nullopt;
  if (text[10] != ' ' && text[10] != 'T') return std::nullopt;
  const auto day = parse_date(text.substr(0, 10));
  const auto clock = parse_clock(text.substr(11, 5));
  if (!day || !clock || *clock >= 24 * 60) return std::nullopt;
  int second = 0;
  if (text.size() == 19) {
    second = text[16] == ':' ? digits_at(text, 17, 2) : -1;
    if (second < 0 || second > 59) return std::nullopt;
  }
  return (static_cast<std::int64_t>(*day) * 1440 + *clock) * 60 + second;
}

std::optional<int> parse_utc_offset(std::string_view text) {
  if (text == "Z" || text == "z") return 0;
  if (text.size() != 6 || (text[0] != '+' && text[0] != '-') || text[3] != ':') return std::nullopt;
  const int hour = digits_at(text, 1, 2), minute = digits_at(text, 4, 2);
  if (hour < 0 || minute < 0 || minute > 59 || hour * 60 + minute > 18 * 60) return std::nullopt;
  return (text[0] == '-' ? -1 : 1) * (hour * 3600 + minute * 60);
}

std::string date_text(std::int64_t day) {
  std::int64_t year = 0;
  unsigned month = 0, d = 0;
  civil_from_days(day, year, month, d);
  char out[32];
  std::snprintf(out, sizeof out, "%04lld-%02u-%02u", static_cast<long long>(year), month, d);
  return out;
}

std::string date_time_text(std::int64_t s) {
  const std::int64_t day = (s >= 0 ? s : s - 86399) / 86400;
  const auto in_day = static_cast<int>(s - day * 86400);
  char clock[32];  // room for any int the compiler cannot rule out
  std::snprintf(clock, sizeof clock, " %02d:%02d:%02d", in_day / 3600, in_day / 60 % 60,
                in_day % 60);
  return date_text(day) + clock;
}

}  // namespace ccbuild
