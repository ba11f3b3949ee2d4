// The schedule model's small functions: the names of its kinds (as the JSON writes them),
// plan keys, totals and the days of a site calendar, all computed from a schedule's layers
// and events alone (the scheduler and read_schedule's rules share them).

#include <algorithm>

#include "ccbuild/common/format.hpp"
#include "ccbuild/rules/crew.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule {

std::string to_string(Objective objective) {
  return objective == Objective::kShortest ? "shortest" : "fewest-nozzles";
}

std::string to_string(WaitKind kind) {
  switch (kind) {
    case WaitKind::kMinInterval:
      return "min-interval";
    case WaitKind::kStrength:
      return "strength";
    case WaitKind::kAnchorStrength:
      return "anchor-strength";
    case WaitKind::kSlab:
      return "slab";
    case WaitKind::kOffShift:
      return "off-shift";
    case WaitKind::kJoint:
      return "joint";
    case WaitKind::kCold:
      return "cold";
    case WaitKind::kWind:
      return "wind";
  }
  return "?";
}

std::string reason_kinds_text(const std::vector<WaitReason>& reasons) {
  std::vector<WaitKind> listed;
  std::string text;
  for (const auto& r : reasons) {
    if (std::find(listed.begin(), listed.end(), r.kind) != listed.end()) continue;
    listed.push_back(r.kind);
    text += (text.empty() ? "" : ", ") + to_string(r.kind);
  }
  return text;
}

namespace {
constexpr WaitKind kWaitKinds[] = {
    WaitKind::kMinInterval, WaitKind::kStrength, WaitKind::kAnchorStrength, WaitKind::kSlab,
    WaitKind::kOffShift,    WaitKind::kJoint,    WaitKind::kCold,           WaitKind::kWind};
}  // namespace

namespace {
constexpr DayEnd kDayEnds[] = {DayEnd::kPlannedJoint, DayEnd::kFloorTop, DayEnd::kFinished,
                               DayEnd::kContinues};
}  // namespace

std::string to_string(DayEnd end) {
  switch (end) {
    case DayEnd::kPlannedJoint:
      return "planned-joint";
    case DayEnd::kFloorTop:
      return "floor-top";
    case DayEnd::kFinished:
      return "finished";
    case DayEnd::kContinues:
      return "continues";
  }
  return "continues";
}

std::optional<DayEnd> day_end_named(const std::string& name) {
  for (DayEnd e : kDayEnds)
    if (to_string(e) == name) return e;
  return std::nullopt;
}

std::string day_end_names() {
  std::string text;
  for (DayEnd e : kDayEnds) text += (text.empty() ? "" : ", ") + to_string(e);
  return text;
}

std::string day_end_text(DayEnd end, int floor, int layer, int next_floor, int next_layer,
                         bool stopped) {
  const std::string at = printf_string("floor %d layer %d", floor, layer);
  const std::string verb = stopped ? "stopped " : "";
  switch (end) {
    case DayEnd::kFinished:
      return "the building's walls are finished with " + at;
    case DayEnd::kFloorTop:
      return verb + printf_string("at the top of floor %d (%s); floor %d starts on its slab", floor,
                                  at.c_str(), next_floor);
    case DayEnd::kPlannedJoint:
      return verb + printf_string("at the end of %s; floor %d layer %d starts on a planned joint",
                                  at.c_str(), next_floor, next_layer);
    case DayEnd::kContinues:
      break;
  }
  return printf_string("%s ends the day; floor %d layer %d follows within its interval", at.c_str(),
                       next_floor, next_layer);
}

std::optional<WaitKind> wait_kind_named(const std::string& name) {
  for (WaitKind k : kWaitKinds)
    if (to_string(k) == name) return k;
  return std::nullopt;
}

const std::vector<WaitKind>& wait_kinds() {
  static const std::vector<WaitKind> kinds(std::begin(kWaitKinds), std::end(kWaitKinds));
  return kinds;
}

std::string wait_kind_names() {
  std::string text;
  for (WaitKind k : kWaitKinds) text += (text.empty() ? "" : ", ") + to_string(k);
  return text;
}

void bind_wait_reasons(std::vector<WaitReason>& reasons) {
  std::vector<double> cuts;
  for (WaitReason& r : reasons) {
    r.binding_s = 0.0;
    cuts.push_back(std::max(0.0, r.from_s));
    cuts.push_back(std::max(0.0, r.required_s));
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    WaitReason* binding = nullptr;
    for (WaitReason& r : reasons)
      if (r.from_s <= a && r.required_s >= b && (!binding || r.required_s > binding->required_s))
        binding = &r;
    if (binding) binding->binding_s += b - a;
  }
}

double binding_s(const std::vector<WaitReason>& reasons, WaitKind kind) {
  double total_s = 0.0;
  for (const WaitReason& r : reasons)
    if (r.kind == kind) total_s += r.binding_s;
  return total_s;
}

std::string to_string(InfeasibilityKind kind) {
  switch (kind) {
    case InfeasibilityKind::kMaxInterval:
      return "max-interval";
    case InfeasibilityKind::kNoPlan:
      return "no-plan";
    case InfeasibilityKind::kStrength:
      return "strength";
    case InfeasibilityKind::kClimb:
      return "climb";
    case InfeasibilityKind::kCalendar:
      return "calendar";
    case InfeasibilityKind::kJoint:
      return "joint";
  }
  return "?";
}

std::optional<InfeasibilityKind> infeasibility_kind_named(const std::string& name) {
  for (InfeasibilityKind k :
       {InfeasibilityKind::kMaxInterval, InfeasibilityKind::kNoPlan, InfeasibilityKind::kStrength,
        InfeasibilityKind::kClimb, InfeasibilityKind::kCalendar, InfeasibilityKind::kJoint})
    if (to_string(k) == name) return k;
  return std::nullopt;
}

std::string PlanKey::to_string() const {
  std::string key =
      follows.empty() ? printf_string("g%dn%d", geometry, nozzles)
                      : printf_string("g%d~%s%s", geometry, follows.c_str(), held_back ? "h" : "");
  return relabelled > 0 ? key + "m" + std::to_string(relabelled) : key;
}

std::string to_string(Event::Kind kind) {
  switch (kind) {
    case Event::Kind::kPipe:
      return "pipe";
    case Event::Kind::kClimb:
      return "climb";
    case Event::Kind::kSlab:
      return "slab";
    case Event::Kind::kPurge:
      return "purge";
    case Event::Kind::kJoint:
      return "joint";
    case Event::Kind::kLintel:
      return "lintel";
    case Event::Kind::kPour:
      return "pour";
  }
  return "?";
}

ScheduleTotals totals_of(const std::vector<ScheduledLayer>& layers,
                         const std::vector<Event>& events) {
  ScheduleTotals tot;
  for (const auto& l : layers) {
    tot.makespan_s = std::max(tot.makespan_s, l.end_s);
    tot.deposition_s += l.deposition_s;
    tot.airtime_s += l.airtime_s;
    tot.waits_s += l.wait_before_s;
    tot.moves_s += l.move_before_s;
    tot.machine_s += l.end_s - l.start_s + l.move_before_s;
    tot.concrete_m3 += l.concrete_m3;
  }
  for (const auto& e : events) {
    tot.makespan_s = std::max(tot.makespan_s, e.end_s);
    const double d = e.end_s - e.start_s;
    tot.crew_h += rules::person_hours(e.crew, d);
    tot.waits_s += e.wait_before_s;
    switch (e.kind) {
      case Event::Kind::kPipe:
        tot.pipes_s += d;
        tot.machine_s += d;
        break;
      case Event::Kind::kSlab:
      case Event::Kind::kPour:
        tot.slabs_s += d;
        break;
      case Event::Kind::kLintel:
        tot.lintels_s += d;
        break;
      case Event::Kind::kPurge:
        tot.purges_s += d;
        tot.machine_s += d;
        break;
      case Event::Kind::kJoint:
        tot.joints_s += d;
        break;
      case Event::Kind::kClimb:
        tot.climbs_s += d;
        tot.machine_s += d;
        if (e.climb) tot.waits_s += e.climb->wait_before_s;
        break;
    }
  }
  return tot;
}

std::vector<WorkDay> work_days(const std::vector<ScheduledLayer>& layers,
                               const std::vector<Event>& events,
                               const std::vector<Delivery>& deliveries,
                               const site::SiteCalendar& calendar) {
  std::vector<WorkDay> days;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const ScheduledLayer& l = layers[i];
    const std::string date = calendar.local_date(l.start_s);
    if (days.empty() || days.back().date != date) {
      WorkDay d;
      d.date = date;
      d.first_floor = l.floor;
      d.first_layer = l.layer;
      days.push_back(d);
    }
    WorkDay& d = days.back();
    ++d.layers;
    d.last_floor = l.floor;
    d.last_layer = l.layer;
    d.printing_s += l.end_s - l.start_s;
    d.concrete_m3 += l.concrete_m3;
    const ScheduledLayer* next = i + 1 < layers.size() ? &layers[i + 1] : nullptr;
    if (next && calendar.local_date(next->start_s) == date) continue;
    d.stop = !next                    ? DayEnd::kFinished
             : next->floor != l.floor ? DayEnd::kFloorTop
             : next->planned_joint    ? DayEnd::kPlannedJoint
                                      : DayEnd::kContinues;
    d.detail = day_end_text(d.stop, l.floor, l.layer, next ? next->floor : l.floor,
                            next ? next->layer : l.layer, true);
  }
  // Each delivery on the day it is due (a day with printing: it feeds a layer that day).
  for (const auto& delivery : deliveries) {
    const std::string date = calendar.local_date(delivery.due_s);
    for (auto& d : days)
      if (d.date == date) ++d.deliveries;
  }
  // Crew hours on the day their task starts (a day without printing has none listed).
  for (const auto& e : events) {
    if (e.crew == 0) continue;
    const std::string date = calendar.local_date(e.start_s);
    for (auto& d : days)
      if (d.date == date) d.crew_h += rules::person_hours(e.crew, e.end_s - e.start_s);
  }
  return days;
}

}  // namespace ccbuild::schedule
