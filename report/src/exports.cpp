#include "ccbuild/report/exports.hpp"

#include <map>

#include <cmath>
#include <cstdio>
#include <ctime>

#include "ccbuild/common/dates.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::report {

std::string civil_text(long long s) {
  return date_time_text(s);
}

long long parse_local_start(const std::string& text, const std::string& field) {
  const auto start_s = parse_date_time(text);
  if (!start_s)
    throw InputError("", 0, field,
                     printf_string("expected a local date and time from %d to %d, as 2027-03-01 "
                                   "07:00 (or 2027-03-01T07:00:00), got '",
                                   kFirstDateYear, kLastDateYear) +
                         echoed(text, 40) + "'");
  return *start_s;
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
    out += csv_field(t.id) + "," + to_string(t.kind) + "," + number(t.floor) + "," +
           number(t.layer) + "," + dates.local(schedule, t.start_s) + "," +
           dates.local(schedule, t.end_s) + "," +
           printf_string("%.6f,%.6f,%.6f", t.start_s, t.end_s, t.end_s - t.start_s) + "," +
           csv_field(t.who) + "," + std::to_string(t.crew) + "," +
           printf_string("%.6f", t.concrete_m3) + "," + csv_field(t.detail) + "\r\n";
  }
  return out;
}

const std::vector<std::string>& export_formats() {
  static const std::vector<std::string> kFormats = {"csv", "ical", "mspdi", "days"};
  return kFormats;
}

bool export_needs_dates(const std::string& format) {
  return format != "csv";
}

std::string export_format_of(const std::filesystem::path& path, const std::string& field) {
  static const std::map<std::string, std::string> kByExtension = {
      {".csv", "csv"}, {".ics", "ical"}, {".xml", "mspdi"}, {".txt", "days"}};
  const auto it = kByExtension.find(path.extension().string());
  if (it == kByExtension.end())
    throw InputError("", 0, field,
                     "'" + path.string() +
                         "': the file's extension says what to export: .csv (a task list), .ics "
                         "(iCalendar), .xml (MS Project XML) or .txt (work packages by day)");
  return it->second;
}

std::string write_export(const schedule::ScheduleDocument& document, const ExportDates& dates,
                         const std::string& format, const std::filesystem::path& path,
                         OutputClaims& outputs) {
  std::size_t count = 0, links = 0;
  std::string text, what, as;
  if (format == "csv") {
    text = tasks_csv(document, dates, &count);
    what = printf_string("%zu tasks", count);
    as = "CSV";
  } else if (format == "ical") {
    text = tasks_ical(document, dates, &count);
    what = printf_string("%zu crew tasks and milestones", count);
    as = document.inputs.calendar ? "iCalendar"
                                  : "iCalendar (floating local times: no site "
                                    "calendar, so no time zone)";
  } else if (format == "days") {
    text = work_packages_text(document, dates, &count);
    what = printf_string("the work packages of %zu days", count);
    as = "text";
  } else {
    text = tasks_mspdi(document, dates, &count, &links);
    what = printf_string("%zu tasks and %zu finish-to-start links", count, links);
    as = "MS Project XML";
  }
  outputs.write(path, text);
  return what + " written to " + path.string() + " as " + as;
}

}  // namespace ccbuild::report
