#pragma once
// The schedule for the tools a site plans in (docs/schedule.md, "Exports"): a CSV task
// list a spreadsheet opens, an iCalendar file a calendar subscribes to, an MS Project XML
// file project tools import, and the day-by-day work packages. Dates are local: the
// schedule's site calendar, or a start given at export for a schedule made without one.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/common/atomic_file.hpp"

#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::report {

/// A local date and time ("2027-03-01 07:00" or "2027-03-01T07:00:00"), as seconds since
/// 1970-01-01 00:00 of a clock without a time zone. Throws InputError (field `field`) for
/// anything else (common/dates.hpp: years kFirstDateYear to kLastDateYear).
long long parse_local_start(const std::string& text, const std::string& field);

/// "2027-03-01 07:00:00" of seconds since 1970-01-01 00:00 of a clock without a time zone.
std::string civil_text(long long s);

/// How schedule seconds become local date-times: the schedule's calendar, else a start
/// (parse_local_start), else none (the date columns stay empty).
struct ExportDates {
  std::optional<long long> start_local_s;
  /// "2027-03-01 07:00:00", or "" when neither the schedule nor the start dates it.
  std::string local(const schedule::ScheduleDocument& schedule, double t_s) const;
  /// Whether the schedule's times can be dated (a calendar or a start).
  bool dated(const schedule::ScheduleDocument& schedule) const {
    return schedule.inputs.calendar || start_local_s;
  }
  /// Throws InputError (field --start) when the schedule cannot be dated: `format` needs
  /// dates.
  void require(const schedule::ScheduleDocument& schedule, const std::string& format) const;
};

/// RFC 4180 CSV, a header and a row per task (tasks_of): id, kind, floor, layer,
/// start, end (local), start_s, end_s, duration_s, who, crew, concrete_m3, detail. `rows`,
/// when given, is set to the number of tasks written.
std::string tasks_csv(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                      std::size_t* rows = nullptr);

/// iCalendar (RFC 5545): a VEVENT for each of the crew's tasks (crew > 0, slab stages,
/// pours, climbs) and each milestone (milestones_of), in the site's time zone (a VTIMEZONE
/// of the offsets over the schedule), or in floating local time from a start. `events`,
/// when given, is set to the number of VEVENTs. Throws InputError when it cannot be dated.
std::string tasks_ical(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                       std::size_t* events = nullptr);

/// MS Project XML (MSPDI): a summary task per floor over its tasks (tasks_of and
/// milestones_of; a climb over its phases), each with its local start and finish, its
/// duration in whole seconds, a start-no-earlier-than constraint at its planned start, and
/// its finish-to-start predecessors: on the site's one line of work, each task follows the
/// one that ended last before it started; a floor's milestone follows its last layer; a
/// climb follows the pipes it pins into. Two calendars: the site's working week with its
/// holidays (tasks within one working window), and 24 hours (the rest, and every task of a
/// schedule without a site calendar). `tasks` and `links`, when given, are set to the
/// counts written. Throws InputError when it cannot be dated.
std::string tasks_mspdi(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                        std::size_t* tasks = nullptr, std::size_t* links = nullptr);

/// The work packages by day, as text for people: for each local day with work, the layers
/// started (per floor: first start to last end, printing hours, m³), the concrete trucks
/// due, the crew's tasks and the machine's own (like tasks run together on one line, with
/// person-hours), the waits that start, and on a site calendar where printing stopped.
/// `days`, when given, is set to the number of days. Throws InputError when it cannot be
/// dated.
std::string work_packages_text(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                               std::size_t* days = nullptr);

/// The export formats: csv, ical, mspdi, days.
const std::vector<std::string>& export_formats();
/// Whether `format` needs dates (a site calendar or --start): all but csv.
bool export_needs_dates(const std::string& format);
/// The format of an export file by its extension: .csv csv, .ics ical, .xml mspdi, .txt
/// days. Throws InputError (field `field`) for another.
std::string export_format_of(const std::filesystem::path& path, const std::string& field);

/// Writes `format` of `document` for `path` (claimed in `outputs`, in place when they are
/// committed), and returns what was written, in words ("870 crew tasks and milestones ...
/// as iCalendar"). Throws InputError when it cannot be dated or written.
std::string write_export(const schedule::ScheduleDocument& document, const ExportDates& dates,
                         const std::string& format, const std::filesystem::path& path,
                         OutputClaims& outputs);

}  // namespace ccbuild::report
