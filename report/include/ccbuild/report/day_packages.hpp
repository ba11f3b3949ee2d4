#pragma once
// The work packages by day: for each local day with work, the layers started, the
// concrete trucks due, the crew's tasks and the machine's own, and the waits; shared by
// `ccbuild export --format days` (exports.hpp) and the report's day view.

#include <string>
#include <vector>

#include "ccbuild/report/exports.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::report {

/// One line of a day's package: a floor's layers, the trucks, a run of like tasks back to
/// back (same kind, floor and crew), or a wait. Times are schedule seconds.
struct DayEntry {
  std::string kind;  ///< "print", "deliver", a task's kind (lintel, pipe, ...), "wait"
  std::string what;  ///< "floor 0 layers 0-16", "Floor 0: 20 × lintel", a title
  std::string who;   ///< "machine, 2 nozzles", "crew of 2", "supplier", ...
  int floor = -1;    ///< -1 when not about one (the trucks)
  int first_layer = -1, last_layer = -1;  ///< a print line's
  double start_s = 0.0, end_s = 0.0;
  int count = 1;             ///< layers, trucks or tasks on the line
  double concrete_m3 = 0.0;  ///< printed, delivered, poured
  double person_h = 0.0;     ///< crew times duration
  double printing_h = 0.0;   ///< a print line: the layers' own time
  std::string reasons;       ///< a wait: its reasons' kinds
};

struct DayPackage {
  std::string date;                 ///< "2027-03-01"; "day 3" for a schedule without dates
  std::string weekday;              ///< "Mon"; empty without dates
  double from_s = 0.0, to_s = 0.0;  ///< the day's local midnight to the next, schedule s
  /// The site calendar's working time that day (empty without a calendar).
  std::vector<site::WorkingWindow> working;
  std::vector<DayEntry> print, deliver, crew, machine, waits;
  std::string stop;  ///< on a site calendar: where printing stopped, in words
};

/// The packages of every day on which a task starts, in date order. Days are the site
/// calendar's local days, else those of `dates`' start, else days of 24 h from second 0
/// ("day 1" first).
std::vector<DayPackage> work_packages(const schedule::ScheduleDocument& schedule,
                                      const ExportDates& dates);

}  // namespace ccbuild::report
