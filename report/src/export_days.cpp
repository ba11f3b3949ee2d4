// The day-by-day work packages: for each local day with work, what is printed, the
// concrete and its deliveries, the crew's tasks and the machine's, and the waits, for a
// foreman's clipboard and for the report's day view.

#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/report/day_packages.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/rules/crew.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::report {

namespace {

const char* weekday_of_day(long long day) {
  return site::weekday_names()[site::weekday_of(day)];
}

/// The local day of schedule seconds, and its bounds: days since 1970-01-01 on a calendar
/// or from a start, else whole days from second 0.
struct DayClock {
  const schedule::ScheduleDocument& schedule;
  const ExportDates& dates;
  long long day_of(double t_s) const {
    if (const auto& c = schedule.inputs.calendar) return c->local_day(t_s);
    if (dates.start_local_s)
      return (*dates.start_local_s + std::llround(t_s)) / 86400;  // from 1970: not negative
    return static_cast<long long>(std::floor(std::llround(t_s) / 86400.0));
  }
  double start_of(long long day) const {
    if (const auto& c = schedule.inputs.calendar)
      return c->seconds_of_utc(c->utc_of_local(day * 86400));
    if (dates.start_local_s) return static_cast<double>(day * 86400 - *dates.start_local_s);
    return day * 86400.0;
  }
  bool dated() const { return dates.dated(schedule); }
};

std::string plural(int n, const std::string& one, const std::string& many) {
  return printf_string("%d %s", n, (n == 1 ? one : many).c_str());
}

}  // namespace

std::vector<DayPackage> work_packages(const schedule::ScheduleDocument& schedule,
                                      const ExportDates& dates) {
  const DayClock clock{schedule, dates};
  std::map<long long, std::vector<SiteTask>> by_day;  // tasks by start, per day
  for (SiteTask& t : tasks_of(schedule))
    if (t.kind != TaskKind::kClimbPhase) by_day[clock.day_of(t.start_s)].push_back(std::move(t));
  std::map<std::string, const schedule::WorkDay*> stops;
  for (const schedule::WorkDay& d : schedule.schedule.days) stops[d.date] = &d;
  const auto& calendar = schedule.inputs.calendar;

  std::vector<DayPackage> packages;
  for (const auto& [day, tasks] : by_day) {
    DayPackage p;
    if (clock.dated()) {
      p.date = site::local_date_text(static_cast<std::int32_t>(day));
      p.weekday = weekday_of_day(day);
    } else {
      p.date = printf_string("day %lld", day + 1);
    }
    p.from_s = clock.start_of(day);
    p.to_s = clock.start_of(day + 1);
    if (calendar)
      for (const site::WorkingWindow& w : calendar->windows())
        if (w.to_s > p.from_s && w.from_s < p.to_s)
          p.working.push_back({std::max(w.from_s, p.from_s), std::min(w.to_s, p.to_s)});
    // Printing, per floor.
    std::map<int, DayEntry> print;
    for (const SiteTask& t : tasks) {
      if (t.kind != TaskKind::kLayer) continue;
      auto [it, first] = print.try_emplace(t.floor);
      DayEntry& e = it->second;
      if (first) {
        e.kind = "print";
        e.start_s = t.start_s;
        e.count = 0;
        e.who = t.who;
        e.floor = t.floor;
        e.first_layer = t.layer;
      }
      ++e.count;
      e.last_layer = t.layer;
      e.what = e.count == 1
                   ? printf_string("floor %d layer %d", t.floor, t.layer)
                   : printf_string("floor %d layers %d-%d", t.floor, e.first_layer, t.layer);
      if (e.who != t.who) e.who = "machine";  // layers of different nozzle counts
      e.end_s = std::max(e.end_s, t.end_s);
      e.printing_h += (t.end_s - t.start_s) / 3600.0;
      e.concrete_m3 += t.concrete_m3;
    }
    for (auto& [floor, e] : print) p.print.push_back(std::move(e));
    // Deliveries.
    for (const SiteTask& t : tasks) {
      if (t.kind != TaskKind::kDelivery) continue;
      if (p.deliver.empty()) {
        DayEntry e;
        e.kind = "deliver";
        e.who = "supplier";
        e.start_s = t.start_s;
        e.count = 0;
        p.deliver.push_back(e);
      }
      DayEntry& e = p.deliver.back();
      ++e.count;
      e.end_s = t.start_s;
      e.concrete_m3 += t.concrete_m3;
      e.what = plural(e.count, "truck", "trucks");
    }
    // The crew's tasks and the machine's own, like ones back to back on one line.
    for (const SiteTask& t : tasks) {
      if (t.kind == TaskKind::kLayer || t.kind == TaskKind::kDelivery) continue;
      if (t.kind == TaskKind::kWait) {
        DayEntry e;
        e.kind = "wait";
        e.floor = t.floor;
        e.what = title_of(t, shown_unit(schedule));
        e.who = t.who;
        e.start_s = t.start_s;
        e.end_s = t.end_s;
        e.reasons = t.reasons;
        p.waits.push_back(std::move(e));
        continue;
      }
      const bool by_crew = t.crew > 0 || t.kind == TaskKind::kSlab;
      std::vector<DayEntry>& list = by_crew ? p.crew : p.machine;
      const bool joins = !list.empty() && list.back().kind == to_string(t.kind) &&
                         list.back().floor == t.floor && list.back().who == t.who &&
                         t.start_s <= list.back().end_s + 1e-6;
      if (!joins) {
        DayEntry e;
        e.kind = to_string(t.kind);
        e.floor = t.floor;
        e.what = title_of(t, shown_unit(schedule));
        e.who = t.who;
        e.start_s = t.start_s;
        e.count = 0;
        list.push_back(std::move(e));
      }
      DayEntry& e = list.back();
      ++e.count;
      if (e.count > 1)
        e.what = printf_string("Floor %d: %d × %s", t.floor, e.count, to_string(t.kind).c_str());
      e.end_s = t.end_s;
      e.person_h += rules::person_hours(t.crew, t.end_s - t.start_s);
      if (t.kind == TaskKind::kPour) e.concrete_m3 += t.concrete_m3;
    }
    if (const auto it = stops.find(p.date); it != stops.end()) {
      const schedule::WorkDay& d = *it->second;
      // The layer after the day's last, named in the words.
      const auto& layers = schedule.schedule.layers;
      int next_floor = d.last_floor, next_layer = d.last_layer;
      for (std::size_t k = 0; k + 1 < layers.size(); ++k)
        if (layers[k].floor == d.last_floor && layers[k].layer == d.last_layer)
          next_floor = layers[k + 1].floor, next_layer = layers[k + 1].layer;
      p.stop =
          schedule::day_end_text(d.stop, d.last_floor, d.last_layer, next_floor, next_layer, false);
    }
    packages.push_back(std::move(p));
  }
  return packages;
}

std::string work_packages_text(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                               std::size_t* days) {
  dates.require(schedule, "the work packages by day");
  const auto& calendar = schedule.inputs.calendar;
  const std::vector<DayPackage> packages = work_packages(schedule, dates);
  const floors::LengthUnit unit = shown_unit(schedule);
  // "07:00"; "Tue 2027-03-02 07:00" when on another day than the package's.
  const DayClock clock{schedule, dates};
  const auto at = [&](double t_s, const DayPackage& p) {
    const std::string local = dates.local(schedule, t_s);
    return local.compare(0, 10, p.date) == 0
               ? local.substr(11, 5)
               : weekday_of_day(clock.day_of(t_s)) + std::string(" ") + local.substr(0, 16);
  };
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
  for (const DayPackage& p : packages) {
    out += printf_string("\n%s %s\n", p.weekday.c_str(), p.date.c_str());
    const auto line = [&](const char* label, bool first, const DayEntry& e,
                          const std::string& rest) {
      out += printf_string("  %-7s  %s-%s  %s\n", first ? label : "", at(e.start_s, p).c_str(),
                           at(e.end_s, p).c_str(), rest.c_str());
    };
    for (const DayEntry& e : p.print)
      line("print", true, e,
           printf_string("%s (%s), %.2f h printing, %s", e.what.c_str(),
                         plural(e.count, "layer", "layers").c_str(), e.printing_h,
                         floors::volume_text(e.concrete_m3, unit).c_str()));
    for (const DayEntry& e : p.deliver)
      line("deliver", true, e, e.what + ", " + floors::volume_text(e.concrete_m3, unit));
    for (const auto& [label, list] :
         {std::pair<const char*, const std::vector<DayEntry>*>{"crew", &p.crew},
          {"machine", &p.machine}}) {
      bool first = true;
      for (const DayEntry& e : *list) {
        std::string rest = e.what + ", " + e.who;
        if (e.person_h > 0.0) rest += printf_string(", %.1f person-h", e.person_h);
        if (e.concrete_m3 > 0.0) rest += ", " + floors::volume_text(e.concrete_m3, unit);
        line(label, first, e, rest);
        first = false;
      }
    }
    bool first = true;
    for (const DayEntry& e : p.waits) {
      line("wait", first, e, e.what + (e.reasons.empty() ? "" : " (" + e.reasons + ")"));
      first = false;
    }
    if (!p.stop.empty()) out += "  stop     " + p.stop + "\n";
  }
  if (days) *days = packages.size();
  return out;
}

}  // namespace ccbuild::report
