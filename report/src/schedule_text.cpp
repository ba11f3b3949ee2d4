// A schedule as text (schedule_text.hpp).

#include "ccbuild/report/schedule_text.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/rules/crew.hpp"
#include "ccbuild/site/conditions.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::report {
namespace {

/// The unit of a column: the one its largest value is read in.
template <typename T, typename Seconds>
TimeUnit column_unit(const T& rows, Seconds seconds_of) {
  double largest_s = 0.0;
  for (const auto& r : rows) largest_s = std::max(largest_s, std::abs(seconds_of(r)));
  return time_unit_for(largest_s);
}

}  // namespace

void write_schedule_text(std::ostream& out, const schedule::Project& project,
                         const schedule::Schedule& s, const ScheduleTextOptions& options) {
  static const std::vector<schedule::AnchorWhatIf> kNone;
  const auto& changes = options.changes ? *options.changes : kNone;
  out << printf_string("%s on %s: %zu layers, %zu distinct plans, %s\n", options.file.c_str(),
                       project.machine_origin.c_str(), s.layers.size(), s.plans.size(),
                       s.feasible ? "feasible" : "NOT feasible");
  if (!s.feasible) out << "not feasible: " << s.infeasibility->message << "\n";
  // Times of day on a site calendar, else time from the start.
  const site::SiteCalendar* calendar = project.calendar.get();
  const auto when = [calendar](double t_s) { return site::time_text(calendar, t_s); };
  if (calendar) {
    const site::SiteProgramme& p = calendar->programme();
    out << printf_string(
        "site: from %s (%s, %s); working hours %s; %zu holiday%s; printing %s, pipes %s\n",
        calendar->local_text(0.0).c_str(), p.time_zone.c_str(),
        calendar->timestamp(0.0).substr(19).c_str(), calendar->week_text().c_str(),
        p.holidays.size(), p.holidays.size() == 1 ? "" : "s",
        p.printing_attended ? "attended" : "unattended",
        p.pipes_need_crew ? "by the crew" : "unattended");
    if (project.conditions)
      out << "weather: " << project.conditions->source << "; concrete ages are equivalent "
          << "ages at 20 °C (" << project.material.maturity.name() << ")\n";
  }
  struct FloorLine {
    int layers = 0, max_nozzles = 0, waits = 0;
    double start_s = 1e300, end_s = 0, wait_s = 0;
    std::map<std::string, double> reasons;
  };
  std::map<int, FloorLine> floors;
  for (const auto& l : s.layers) {
    FloorLine& f = floors[l.floor];
    f.layers += 1;
    f.max_nozzles = std::max(f.max_nozzles, l.nozzles);
    f.start_s = std::min(f.start_s, l.start_s);
    f.end_s = std::max(f.end_s, l.end_s);
    if (l.wait_before_s > 0) {
      f.waits += 1;
      f.wait_s += l.wait_before_s;
      for (const auto& r : l.wait_reasons) f.reasons[schedule::to_string(r.kind)] += 1;
    }
  }
  int width = 5;  // the widest time in the start and end columns ("day 10 02:03" is 12)
  for (const auto& [floor, f] : floors)
    width = std::max(
        {width, static_cast<int>(when(f.start_s).size()), static_cast<int>(when(f.end_s).size())});
  const TimeUnit waited_unit =
      column_unit(floors, [](const auto& entry) { return entry.second.wait_s; });
  out << printf_string("floor  layers  nozzles  %-*s  %-*s  waits  %10s  why\n", width, "start",
                       width, "end", "waited");
  for (const auto& [floor, f] : floors) {
    std::string why;
    for (const auto& [kind, n] : f.reasons)
      why += (why.empty() ? "" : ", ") + printf_string("%s x%.0f", kind.c_str(), n);
    out << printf_string("%5d  %6d  %7d  %-*s  %-*s  %5d  %10s  %s\n", floor, f.layers,
                         f.max_nozzles, width, when(f.start_s).c_str(), width,
                         when(f.end_s).c_str(), f.waits, duration_in(f.wait_s, waited_unit).c_str(),
                         why.c_str());
  }
  out << "  (nozzles: the most a layer of the floor uses; waits: how many of its layers "
         "waited before they started, waited: those waits summed, why: the reasons and "
         "how many layers waited for each, a layer may wait for several)\n";
  if (!s.days.empty()) {
    out << printf_string("%zu working days with printing:\n", s.days.size());
    const TimeUnit printing_unit =
        column_unit(s.days, [](const schedule::WorkDay& d) { return d.printing_s; });
    for (const auto& d : s.days)
      out << printf_string(
          "  %s %s  %3d layer%s, %s printing, %s, %d deliver%s, "
          "%.1f crew person-hours: %s\n",
          site::weekday_names()[site::weekday_of(*site::parse_local_date(d.date))], d.date.c_str(),
          d.layers, d.layers == 1 ? " " : "s", duration_in(d.printing_s, printing_unit).c_str(),
          floors::volume_text(d.concrete_m3, project.building.units).c_str(), d.deliveries,
          d.deliveries == 1 ? "y" : "ies", d.crew_h, d.detail.c_str());
  }
  std::vector<const schedule::Event*> climbs;
  for (const auto& e : s.events)
    if (e.kind == schedule::Event::Kind::kClimb) climbs.push_back(&e);
  const TimeUnit climb_wait_unit =
      column_unit(climbs, [](const schedule::Event* e) { return e->climb->wait_before_s; });
  const TimeUnit climb_motion_unit =
      column_unit(climbs, [](const schedule::Event* e) { return e->climb->plan.duration_s; });
  for (const schedule::Event* e : climbs) {
    const auto& c = *e->climb;
    // Each cause with the time it was the binding one (a night, then the wind, ...).
    std::string why;
    std::vector<schedule::WaitKind> told;
    for (const auto& r : c.wait_reasons) {
      if (std::find(told.begin(), told.end(), r.kind) != told.end()) continue;
      told.push_back(r.kind);
      const double bound_s = schedule::binding_s(c.wait_reasons, r.kind);
      if (bound_s <= 0.0) continue;
      why += (why.empty() ? "" : ", ") + schedule::to_string(r.kind) + " " +
             duration_in(bound_s, climb_wait_unit);  // the wait's column, one unit
    }
    out << printf_string(
        "climb %d -> %d after floor %d layer %d: starts at %s after a wait of %s%s, %s of "
        "motion\n",
        c.from_stage, c.to_stage, e->floor, e->layer, when(e->start_s).c_str(),
        duration_in(c.wait_before_s, climb_wait_unit).c_str(),
        why.empty() ? "" : (" (" + why + ")").c_str(),
        duration_in(c.plan.duration_s, climb_motion_unit).c_str());
  }
  // The climb critical path: what each climb waited for, and the changes that shorten it.
  const auto waits = schedule::anchor_waits(project, s);
  double anchor_wait_s = 0.0;
  for (const auto& w : waits) anchor_wait_s += w.wait_s;
  if (options.what_if && !waits.empty()) {
    out << printf_string(
        "anchors: each climb waits for its latest pipe to reach %.1f MPa (%s after casting)\n",
        waits.front().required_mpa,
        duration_text(waits.front().strong_s - waits.front().cast_s).c_str());
    const TimeUnit waited_unit =
        column_unit(waits, [](const schedule::AnchorWait& w) { return w.wait_s; });
    for (const auto& w : waits)
      out << printf_string(
          "  climb %d -> %d: pipe %s cast at %s (floor %d layer %d), strong at %s; the build "
          "was ready at %s and waited %s\n",
          w.from_stage, w.to_stage, w.anchor.c_str(), when(w.cast_s).c_str(), w.cast_floor,
          w.cast_layer, when(w.strong_s).c_str(), when(w.ready_s).c_str(),
          duration_in(w.wait_s, waited_unit).c_str());
  }
  if (anchor_wait_s > 0.0 && s.totals.makespan_s > 0.0) {
    out << printf_string(
        "anchor waits: %s of the %s (%.0f%%)", duration_text(anchor_wait_s).c_str(),
        duration_text(s.totals.makespan_s).c_str(), 100.0 * anchor_wait_s / s.totals.makespan_s);
    if (!options.what_if)
      out << "; `--what-if anchors` computes the changes that would shorten them";
    out << "\n";
  }
  if (options.what_if) {
    if (changes.empty())
      out << (anchor_wait_s > 0.0
                  ? "what-if anchors: no change the profiles allow gives a feasible "
                    "schedule\n"
                  : "what-if anchors: no climb waits for its anchors; nothing to shorten\n");
    else
      out << "what-if anchors (each change scheduled in full):\n";
    const TimeUnit makespan_unit =
        column_unit(changes, [](const schedule::AnchorWhatIf& w) { return w.makespan_s; });
    const TimeUnit change_unit = column_unit(changes, [&](const schedule::AnchorWhatIf& w) {
      return s.totals.makespan_s - w.makespan_s;
    });
    const TimeUnit waits_unit =
        column_unit(changes, [](const schedule::AnchorWhatIf& w) { return w.anchor_waits_s; });
    for (const auto& w : changes)
      out << printf_string(
          "  %s: %s (%.0f s), %s%s, anchor waits %s\n", w.change.c_str(),
          duration_in(w.makespan_s, makespan_unit).c_str(), w.makespan_s,
          w.makespan_s <= s.totals.makespan_s ? "-" : "+",
          duration_in(std::abs(s.totals.makespan_s - w.makespan_s), change_unit).c_str(),
          duration_in(w.anchor_waits_s, waits_unit).c_str());
  }
  const auto& t = s.totals;
  out << printf_string(
      "total: %s from the first layer to the last%s (machine busy %s: layers, moves, pipes, "
      "purges, climbs); summed over the nozzles: deposition %s, airtime %s; waits %s, climbs "
      "%s, slabs %s, pipes %s, purges %s, lintels %s, joints %s\n",
      duration_text(t.makespan_s).c_str(),
      calendar ? (", finished " + calendar->local_text(t.makespan_s)).c_str() : "",
      duration_text(t.machine_s).c_str(), duration_text(t.deposition_s).c_str(),
      duration_text(t.airtime_s).c_str(), duration_text(t.waits_s).c_str(),
      duration_text(t.climbs_s).c_str(), duration_text(t.slabs_s).c_str(),
      duration_text(t.pipes_s).c_str(), duration_text(t.purges_s).c_str(),
      duration_text(t.lintels_s).c_str(), duration_text(t.joints_s).c_str());
  {
    // Crew tasks: how many of each kind, and the person-hours they take.
    std::map<std::string, std::pair<int, double>> by_kind;  // count, person-hours
    double slab_m3 = 0.0;
    for (const auto& e : s.events) {
      if (e.kind == schedule::Event::Kind::kPour) slab_m3 += e.concrete_m3;
      if (e.crew == 0) continue;
      auto& [count, hours] = by_kind[schedule::to_string(e.kind)];
      ++count;
      hours += rules::person_hours(e.crew, e.end_s - e.start_s);
    }
    std::string kinds;
    for (const auto& [kind, v] : by_kind)
      kinds += printf_string("%s%d %s%s %.1f h", kinds.empty() ? "" : ", ", v.first, kind.c_str(),
                             v.first == 1 ? "" : "s", v.second);
    if (!by_kind.empty())
      out << printf_string(
          "crew: %.1f person-hours (%s)%s\n", t.crew_h, kinds.c_str(),
          slab_m3 > 0.0
              ? ("; slabs poured: " + floors::volume_text(slab_m3, project.building.units)).c_str()
              : "");
  }
  {
    // Quantities: concrete per floor and in all, the pump's peak, the deliveries.
    std::map<int, double> per_floor;
    double peak_m3_s = 0.0;
    for (const auto& l : s.layers) {
      per_floor[l.floor] += l.concrete_m3;
      peak_m3_s = std::max(peak_m3_s, l.peak_flow_m3_s);
    }
    const floors::LengthUnit unit = project.building.units;
    std::string floors_text;
    for (const auto& [floor, m3] : per_floor)
      floors_text += printf_string("%sfloor %d %.2f", floors_text.empty() ? "" : ", ", floor,
                                   floors::volume_in(m3, unit));
    auto per_hour = [unit](double m3_s) { return floors::flow_text(m3_s, unit, 2); };
    out << printf_string(
        "concrete: %s (%s); the nozzles draw at most %s%s; %zu deliveries of %s\n",
        floors::volume_text(t.concrete_m3, unit).c_str(), floors_text.c_str(),
        per_hour(peak_m3_s).c_str(),
        project.machine->pump_capacity_m3_s
            ? (" (the pump: " + per_hour(*project.machine->pump_capacity_m3_s) + ")").c_str()
            : "",
        s.deliveries.size(), floors::volume_text(project.material.delivery_batch_m3, unit).c_str());
    // Against the model's own wall volumes, where the building was imported with them.
    for (std::size_t f = 0; f < s.quantities.size(); ++f)
      if (s.quantities[f].model_m3)
        out << "quantities: "
            << floors::quantities_text(project.building.floors[f].name, s.quantities[f]) << "\n";
  }
}

void write_objectives_line(std::ostream& out, const schedule::Project& project,
                           const schedule::Schedule& s, const schedule::ScheduleOptions& options) {
  // The other objective, scheduled in full, for comparison.
  schedule::ScheduleOptions other = options;
  other.objective = options.objective == schedule::Objective::kShortest
                        ? schedule::Objective::kFewestNozzles
                        : schedule::Objective::kShortest;
  // One nozzle: both objectives choose the same count for every layer.
  const bool same = project.machine->nozzles == 1;
  if (other.progress && !same)
    other.progress("scheduling again with --objective " + to_string(other.objective) +
                   ", to compare");
  other.progress = nullptr;
  const schedule::Schedule alt = same ? s : schedule::build_schedule(project, other);
  const auto most_nozzles = [](const schedule::Schedule& x) {
    int n = 0;
    for (const auto& l : x.layers) n = std::max(n, l.nozzles);
    return n;
  };
  const auto line = [&](const schedule::Schedule& x, schedule::Objective which) {
    return printf_string("%s %s%s (up to %d nozzle%s)", to_string(which).c_str(),
                         duration_text(x.totals.makespan_s).c_str(),
                         x.feasible ? "" : ", NOT feasible", most_nozzles(x),
                         most_nozzles(x) == 1 ? "" : "s");
  };
  out << "objectives: " << line(s, options.objective) << " (this schedule); "
      << line(alt, other.objective) << "\n";
}

}  // namespace ccbuild::report
