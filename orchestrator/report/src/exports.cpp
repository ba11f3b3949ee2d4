#include "ccbuild/report/exports.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/schedule/site.hpp"

namespace ccbuild::report {

namespace {

/// Days since 1970-01-01 of a proleptic Gregorian date (Howard Hinnant's algorithm).
long long days_from_civil(long long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long long>(doe) - 719468;
}

/// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string civil_text(long long s) {
  std::time_t t = static_cast<std::time_t>(s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char out[32];
  std::strftime(out, sizeof out, "%Y-%m-%d %H:%M:%S", &tm);
  return out;
}

long long parse_local_start(const std::string& text, const std::string& field) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0, used = 0;
  char sep = 0;
  const int n =
      std::sscanf(text.c_str(), "%4d-%2d-%2d%c%2d:%2d%n", &y, &mo, &d, &sep, &h, &mi, &used);
  bool ok = n == 6 && (sep == ' ' || sep == 'T');
  if (ok && used < static_cast<int>(text.size())) {
    int more = 0;
    ok = std::sscanf(text.c_str() + used, ":%2d%n", &sec, &more) == 1 &&
         used + more == static_cast<int>(text.size());
  }
  static const int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  ok = ok && y >= 1970 && y <= 9999 && mo >= 1 && mo <= 12 && d >= 1 &&
       d <= (mo == 2 && !leap ? 28 : kDays[mo - 1]) && h >= 0 && h <= 23 && mi >= 0 && mi <= 59 &&
       sec >= 0 && sec <= 59;
  if (!ok)
    throw InputError("", 0, field,
                     "expected a local date and time from 1970 to 9999, as 2027-03-01 07:00 (or "
                     "2027-03-01T07:00:00), got '" +
                         text + "'");
  return days_from_civil(y, mo, d) * 86400 + h * 3600LL + mi * 60LL + sec;
}

std::string ExportDates::local(const schedule::ScheduleDocument& schedule, double t_s) const {
  if (const auto& calendar = schedule.inputs.calendar) {
    std::string iso = calendar->timestamp(t_s);  // "2027-03-01T07:00:00+01:00"
    iso = iso.substr(0, 19);
    iso[10] = ' ';
    return iso;
  }
  if (!start_local_s) return "";
  return civil_text(*start_local_s + std::llround(t_s));
}

void ExportDates::require(const schedule::ScheduleDocument& schedule,
                          const std::string& format) const {
  if (!dated(schedule))
    throw InputError("", 0, "--start",
                     "the schedule was made without a site calendar, and " + format +
                         " needs dates: give the local date and time its second 0 is, as "
                         "--start 2027-03-01T07:00 (or schedule it with --site FILE)");
}

std::string tasks_csv(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                      std::size_t* rows) {
  std::string out =
      "id,kind,floor,layer,start,end,start_s,end_s,duration_s,who,crew,concrete_m3,detail\r\n";
  const auto number = [](int v) { return v < 0 ? std::string() : std::to_string(v); };
  const std::vector<SiteTask> tasks = tasks_of(schedule);
  if (rows) *rows = tasks.size();
  for (const SiteTask& t : tasks) {
    out += csv_field(t.id) + "," + t.kind + "," + number(t.floor) + "," + number(t.layer) + "," +
           dates.local(schedule, t.start_s) + "," + dates.local(schedule, t.end_s) + "," +
           printf_string("%.6f,%.6f,%.6f", t.start_s, t.end_s, t.end_s - t.start_s) + "," +
           csv_field(t.who) + "," + std::to_string(t.crew) + "," +
           printf_string("%.6f", t.concrete_m3) + "," + csv_field(t.detail) + "\r\n";
  }
  return out;
}

}  // namespace ccbuild::report
