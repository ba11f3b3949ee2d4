#pragma once
// The schedule for the tools a site plans in (docs/schedule.md, "Exports"): a CSV task
// list a spreadsheet opens. Dates are local: the schedule's site calendar, or a start
// given at export for a schedule made without one.

#include <cstddef>
#include <optional>
#include <string>

#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::report {

/// A local date and time ("2027-03-01 07:00" or "2027-03-01T07:00:00"), as seconds since
/// 1970-01-01 00:00 of a clock without a time zone. Throws InputError (field `field`) for
/// anything else, or a year outside 1970-9999.
long long parse_local_start(const std::string& text, const std::string& field);

/// How schedule seconds become local date-times: the schedule's calendar, else a start
/// (parse_local_start), else none (the date columns stay empty).
struct ExportDates {
  std::optional<long long> start_local_s;
  /// "2027-03-01 07:00:00", or "" when neither the schedule nor the start dates it.
  std::string local(const schedule::ScheduleDocument& schedule, double t_s) const;
};

/// RFC 4180 CSV, a header and a row per task (tasks_of): id, kind, floor, layer,
/// start, end (local), start_s, end_s, duration_s, who, crew, concrete_m3, detail. `rows`,
/// when given, is set to the number of tasks written.
std::string tasks_csv(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                      std::size_t* rows = nullptr);

}  // namespace ccbuild::report
