// The day-by-day work packages: for each local day with work, what is printed, the
// concrete and its deliveries, the crew's tasks and the machine's, and the waits, for a
// foreman's clipboard.

#include <algorithm>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/report/exports.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/schedule/site.hpp"

namespace ccbuild::report {

namespace {

/// "Mon" of a "2027-03-01 ..." date.
std::string weekday_of(const std::string& local) {
  const long long day = parse_local_start(local.substr(0, 10) + " 00:00", "date") / 86400;
  static const char* kNames[] = {"Thu", "Fri", "Sat", "Sun", "Mon", "Tue", "Wed"};
  return kNames[((day % 7) + 7) % 7];  // 1970-01-01 was a Thursday
}

/// "07:00" of a local date-time; "Tue 07:00" when it is on another day than `day`.
std::string clock_on(const std::string& local, const std::string& day) {
  const std::string hhmm = local.substr(11, 5);
  return local.compare(0, 10, day) == 0
             ? hhmm
             : weekday_of(local) + " " + local.substr(0, 10) + " " + hhmm;
}

std::string plural(int n, const std::string& one, const std::string& many) {
  return printf_string("%d %s", n, (n == 1 ? one : many).c_str());
}

/// A run of like tasks on one line: same kind, floor and crew, back to back in the day.
struct Run {
  std::vector<const SiteTask*> tasks;
  bool joins(const SiteTask& t) const {
    const SiteTask& last = *tasks.back();
    return t.kind == last.kind && t.floor == last.floor && t.crew == last.crew &&
           t.start_s <= last.end_s + 1e-6;
  }
};

}  // namespace

std::string work_packages_text(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                               std::size_t* days) {
  dates.require(schedule, "the work packages by day");
  const auto& calendar = schedule.inputs.calendar;
  std::map<std::string, std::vector<SiteTask>> by_day;  // "2027-03-01" -> tasks, by start
  for (SiteTask& t : tasks_of(schedule))
    if (t.kind != "climb-phase")
      by_day[dates.local(schedule, t.start_s).substr(0, 10)].push_back(std::move(t));
  std::map<std::string, const schedule::WorkDay*> stops;
  for (const schedule::WorkDay& d : schedule.schedule.days) stops[d.date] = &d;

  std::string out = "Work packages by day: " + schedule.inputs.name + "\n";
  out += calendar
             ? "Times are local in " + calendar->programme().time_zone + " (" +
                   calendar->week_text() + ").\n"
             : "Times are local from the start given (" + dates.local(schedule, 0.0).substr(0, 16) +
                   "); the schedule has no site calendar and works around the clock.\n";
  out +=
      "Each day lists: print (the layers started that day, per floor: from the first start to "
      "the last end, printing time, concrete), deliver (concrete trucks due), crew (the "
      "crew's tasks, like ones run together, with person-hours), machine (purges, climbs "
      "without a crew), wait (the waits that start that day and why), and on a site calendar "
      "where printing stopped.\n";
  for (const auto& [day, tasks] : by_day) {
    out += printf_string("\n%s %s\n", weekday_of(day).c_str(), day.c_str());
    // Printing, per floor.
    std::map<int, std::vector<const SiteTask*>> layers;
    for (const SiteTask& t : tasks)
      if (t.kind == "layer") layers[t.floor].push_back(&t);
    for (const auto& [floor, list] : layers) {
      double printing_s = 0.0, m3 = 0.0, end_s = 0.0;
      for (const SiteTask* l : list)
        printing_s += l->end_s - l->start_s, m3 += l->concrete_m3,
            end_s = std::max(end_s, l->end_s);
      out += printf_string(
          "  print    %s-%s  floor %d %s (%s), %.2f h printing, %.2f m³\n",
          clock_on(dates.local(schedule, list.front()->start_s), day).c_str(),
          clock_on(dates.local(schedule, end_s), day).c_str(), floor,
          list.size() == 1
              ? printf_string("layer %d", list.front()->layer).c_str()
              : printf_string("layers %d-%d", list.front()->layer, list.back()->layer).c_str(),
          plural(static_cast<int>(list.size()), "layer", "layers").c_str(), printing_s / 3600.0,
          m3);
    }
    // Deliveries.
    std::vector<const SiteTask*> trucks;
    for (const SiteTask& t : tasks)
      if (t.kind == "delivery") trucks.push_back(&t);
    if (!trucks.empty()) {
      double m3 = 0.0;
      for (const SiteTask* t : trucks) m3 += t->concrete_m3;
      out += printf_string("  deliver  %s-%s  %s, %.2f m³\n",
                           clock_on(dates.local(schedule, trucks.front()->start_s), day).c_str(),
                           clock_on(dates.local(schedule, trucks.back()->start_s), day).c_str(),
                           plural(static_cast<int>(trucks.size()), "truck", "trucks").c_str(), m3);
    }
    // The crew's tasks and the machine's own, like ones run together.
    for (const bool crew : {true, false}) {
      std::vector<Run> runs;
      for (const SiteTask& t : tasks) {
        if (t.kind == "layer" || t.kind == "delivery" || t.kind == "wait") continue;
        if ((t.crew > 0 || t.kind == "slab") != crew) continue;
        if (!runs.empty() && runs.back().joins(t))
          runs.back().tasks.push_back(&t);
        else
          runs.push_back({{&t}});
      }
      bool first = true;
      for (const Run& r : runs) {
        const SiteTask& a = *r.tasks.front();
        const SiteTask& b = *r.tasks.back();
        const int n = static_cast<int>(r.tasks.size());
        const std::string what =
            n == 1 ? title_of(a) : printf_string("Floor %d: %d × %s", a.floor, n, a.kind.c_str());
        std::string line = printf_string(
            "  %-7s  %s-%s  %s, %s", first ? (crew ? "crew" : "machine") : "",
            clock_on(dates.local(schedule, a.start_s), day).c_str(),
            clock_on(dates.local(schedule, b.end_s), day).c_str(), what.c_str(), a.who.c_str());
        if (a.crew > 0)
          line += printf_string(", %.1f person-h", a.crew * (b.end_s - a.start_s) / 3600.0);
        if (a.kind == "pour") line += printf_string(", %.2f m³", a.concrete_m3);
        out += line + "\n";
        first = false;
      }
    }
    // The waits that start this day.
    bool first = true;
    for (const SiteTask& t : tasks) {
      if (t.kind != "wait") continue;
      out +=
          printf_string("  %-7s  %s-%s  %s%s\n", first ? "wait" : "",
                        clock_on(dates.local(schedule, t.start_s), day).c_str(),
                        clock_on(dates.local(schedule, t.end_s), day).c_str(), title_of(t).c_str(),
                        t.reasons.empty() ? "" : (" (" + t.reasons + ")").c_str());
      first = false;
    }
    if (const auto it = stops.find(day); it != stops.end())
      out += "  stop     " +
             (it->second->detail.rfind("stopped ", 0) == 0 ? it->second->detail.substr(8)
                                                           : it->second->detail) +
             "\n";
  }
  if (days) *days = by_day.size();
  return out;
}

}  // namespace ccbuild::report
