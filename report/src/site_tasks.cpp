#include "ccbuild/report/site_tasks.hpp"

#include <algorithm>

#include "ccbuild/common/format.hpp"

namespace ccbuild::report {

using schedule::Event;

namespace {

std::string crew_text(int crew, bool machine) {
  if (crew <= 0) return machine ? "machine" : "site";  // a fixed slab stage names no crew
  return printf_string("%screw of %d", machine ? "machine and " : "", crew);
}

}  // namespace

std::string to_string(TaskKind kind) {
  switch (kind) {
    case TaskKind::kLayer:
      return "layer";
    case TaskKind::kWait:
      return "wait";
    case TaskKind::kClimbPhase:
      return "climb-phase";
    case TaskKind::kDelivery:
      return "delivery";
    case TaskKind::kWallsFinished:
      return "walls-finished";
    case TaskKind::kFloor:
      return "floor";
    case TaskKind::kPipe:
      return schedule::to_string(Event::Kind::kPipe);
    case TaskKind::kClimb:
      return schedule::to_string(Event::Kind::kClimb);
    case TaskKind::kSlab:
      return schedule::to_string(Event::Kind::kSlab);
    case TaskKind::kPour:
      return schedule::to_string(Event::Kind::kPour);
    case TaskKind::kPurge:
      return schedule::to_string(Event::Kind::kPurge);
    case TaskKind::kJoint:
      return schedule::to_string(Event::Kind::kJoint);
    case TaskKind::kLintel:
      return schedule::to_string(Event::Kind::kLintel);
  }
  return "layer";
}

TaskKind task_kind_of(Event::Kind kind) {
  switch (kind) {
    case Event::Kind::kPipe:
      return TaskKind::kPipe;
    case Event::Kind::kClimb:
      return TaskKind::kClimb;
    case Event::Kind::kSlab:
      return TaskKind::kSlab;
    case Event::Kind::kPurge:
      return TaskKind::kPurge;
    case Event::Kind::kJoint:
      return TaskKind::kJoint;
    case Event::Kind::kLintel:
      return TaskKind::kLintel;
    case Event::Kind::kPour:
      return TaskKind::kPour;
  }
  return TaskKind::kPipe;
}

namespace {

// What an event is, in a few words, from its fields: "pipe A1 for unit U1", "formwork lintel
// over opening W1", "climb from stage 0 to 1", "pour of the slab over floor 2".
// `waited_for`: as the thing a wait comes before ("wait before planned joint").
std::string event_name(const Event& e, const schedule::ScheduleDocument& document,
                       bool waited_for = false) {
  const auto& names = document.inputs.unit_names;
  const std::string over = printf_string("the %s over floor %d", e.roof ? "roof" : "slab", e.floor);
  switch (e.kind) {
    case Event::Kind::kPipe: {
      const int unit = e.anchor ? e.anchor->unit : -1;
      return "pipe " + (e.anchor ? e.anchor->id : std::string("?")) +
             (unit >= 0 && unit < static_cast<int>(names.size()) ? " for unit " + names[unit]
                                                                 : std::string());
    }
    case Event::Kind::kClimb:
      return e.climb ? printf_string("climb from stage %d to %d", e.climb->from_stage,
                                     e.climb->to_stage)
                     : "climb";
    case Event::Kind::kSlab:
      return document.inputs.slabs ? "formwork and reinforcement of " + over
                                   : printf_string("slab over floor %d", e.floor);
    case Event::Kind::kPour:
      return "pour of " + over;
    case Event::Kind::kPurge:
      return waited_for ? "purge" : "purge the nozzle";
    case Event::Kind::kJoint:
      return waited_for ? "planned joint" : "treat the planned joint";
    case Event::Kind::kLintel:
      return e.lintel
                 ? floors::to_string(e.lintel->type) + " lintel over opening " + e.lintel->opening
                 : "lintel";
  }
  return schedule::to_string(e.kind);
}

std::string capitalised(std::string text) {
  if (!text.empty() && text[0] >= 'a' && text[0] <= 'z') text[0] = static_cast<char>(text[0] - 32);
  return text;
}

}  // namespace

std::vector<SiteTask> tasks_of(const schedule::ScheduleDocument& document) {
  const schedule::Schedule& s = document.schedule;
  const double purge_s = document.inputs.machine.purge_s;
  const double treatment_s = document.inputs.material.planned_joint.treatment_s;
  std::vector<SiteTask> tasks;
  for (const auto& l : s.layers) {
    const std::string key = printf_string("%d.%d", l.floor, l.layer);
    if (l.wait_before_s > 0.0) {
      // The wait ends where the layer's planned joint treatment, purge and deposit begin.
      SiteTask w;
      w.id = "W" + key;
      w.kind = TaskKind::kWait;
      w.floor = l.floor;
      w.layer = l.layer;
      w.end_s =
          l.start_s - (l.purge_before ? purge_s : 0.0) - (l.planned_joint ? treatment_s : 0.0);
      w.start_s = w.end_s - l.wait_before_s;
      w.who = "machine";
      for (const auto& r : l.wait_reasons)
        w.detail += (w.detail.empty() ? "" : "; ") + schedule::to_string(r.kind) + ": " + r.detail;
      w.reasons = schedule::reason_kinds_text(l.wait_reasons);
      w.detail = printf_string("before floor %d layer %d: ", l.floor, l.layer) + w.detail;
      w.title = printf_string("Wait before floor %d layer %d", l.floor, l.layer);
      tasks.push_back(std::move(w));
    }
    SiteTask t;
    t.id = "L" + key;
    t.kind = TaskKind::kLayer;
    t.floor = l.floor;
    t.layer = l.layer;
    t.start_s = l.start_s;
    t.end_s = l.end_s;
    t.who = printf_string("machine, %d nozzle%s", l.nozzles, l.nozzles == 1 ? "" : "s");
    t.concrete_m3 = l.concrete_m3;
    t.detail = printf_string("floor %d layer %d (plan %s%s)", l.floor, l.layer, l.plan.c_str(),
                             l.planned_joint ? ", on a planned joint" : "");
    t.title = printf_string("Floor %d layer %d", l.floor, l.layer);
    tasks.push_back(std::move(t));
  }
  for (std::size_t k = 0; k < s.events.size(); ++k) {
    const Event& e = s.events[k];
    const std::string id = "E" + std::to_string(k + 1);
    const double waited_s = e.wait_before_s + (e.climb ? e.climb->wait_before_s : 0.0);
    if (waited_s > 0.0) {
      SiteTask w;
      w.id = "W" + id;
      w.kind = TaskKind::kWait;
      w.floor = e.floor;
      w.start_s = e.start_s - waited_s;
      w.end_s = e.start_s;
      w.who = "machine";
      std::string why;
      if (e.climb)
        for (const auto& r : e.climb->wait_reasons)
          why += (why.empty() ? "" : "; ") + schedule::to_string(r.kind) + ": " + r.detail;
      // A crew's task waits for working hours; a climb says why it waited.
      w.reasons = e.climb ? schedule::reason_kinds_text(e.climb->wait_reasons) : "off-shift";
      w.detail = "before " + e.detail + (why.empty() ? "" : ": " + why);
      w.title = "Wait before " + event_name(e, document, true);
      tasks.push_back(std::move(w));
    }
    SiteTask t;
    t.id = id;
    t.kind = task_kind_of(e.kind);
    t.floor = e.floor;
    t.start_s = e.start_s;
    t.end_s = e.end_s;
    const bool machine = e.kind == Event::Kind::kPipe || e.kind == Event::Kind::kPurge ||
                         e.kind == Event::Kind::kClimb ||
                         (e.kind == Event::Kind::kLintel && e.crew == 0);
    t.crew = e.crew;
    t.who = crew_text(e.crew, machine);
    t.concrete_m3 = e.kind == Event::Kind::kPour ? e.concrete_m3 : 0.0;
    t.detail = e.detail;
    t.title = printf_string("Floor %d: %s", e.floor, capitalised(event_name(e, document)).c_str());
    tasks.push_back(std::move(t));
    if (e.climb) {
      double at_s = e.start_s;
      const auto& phases = e.climb->plan.phases;
      for (std::size_t p = 0; p < phases.size(); ++p) {
        SiteTask phase;
        phase.id = id + "." + std::to_string(p + 1);
        phase.kind = TaskKind::kClimbPhase;
        phase.floor = e.floor;
        phase.start_s = at_s;
        phase.end_s = at_s + phases[p].duration_s;
        phase.who = "machine";
        const int unit = phases[p].unit;
        const auto& names = document.inputs.unit_names;
        const std::string what =
            climb::to_string(phases[p].kind) + (unit >= 0 && unit < static_cast<int>(names.size())
                                                    ? " " + names[unit]
                                                    : std::string());
        phase.detail = e.detail + ": " + what;
        phase.title = capitalised(what);
        at_s = phase.end_s;
        tasks.push_back(std::move(phase));
      }
    }
  }
  for (std::size_t k = 0; k < s.deliveries.size(); ++k) {
    const schedule::Delivery& d = s.deliveries[k];
    SiteTask t;
    t.id = "D" + std::to_string(k + 1);
    t.kind = TaskKind::kDelivery;
    t.floor = d.floor;
    t.layer = d.layer;
    t.start_s = t.end_s = d.due_s;
    t.who = "supplier";
    t.concrete_m3 = d.m3;
    t.detail =
        printf_string("%s of concrete due for floor %d layer %d",
                      floors::volume_text(d.m3, shown_unit(document)).c_str(), d.floor, d.layer);
    t.title = "Concrete delivery, " + floors::volume_text(d.m3, shown_unit(document));
    tasks.push_back(std::move(t));
  }
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const SiteTask& a, const SiteTask& b) { return a.start_s < b.start_s; });
  return tasks;
}

floors::LengthUnit shown_unit(const schedule::ScheduleDocument& schedule) {
  return floors::parse_length_unit(schedule.inputs.units).value_or(floors::LengthUnit::kMeter);
}

std::string title_of(const SiteTask& t, floors::LengthUnit unit) {
  // A delivery's volume in the unit asked for; every other title is made with its task.
  if (t.kind == TaskKind::kDelivery)
    return "Concrete delivery, " + floors::volume_text(t.concrete_m3, unit);
  return t.title;
}

std::vector<SiteTask> milestones_of(const schedule::ScheduleDocument& document) {
  std::vector<SiteTask> milestones;
  for (const auto& l : document.schedule.layers) {
    if (milestones.empty() || milestones.back().floor != l.floor) {
      SiteTask m;
      m.id = printf_string("M%d", l.floor);
      m.kind = TaskKind::kWallsFinished;
      m.floor = l.floor;
      m.who = "machine";
      milestones.push_back(std::move(m));
    }
    SiteTask& m = milestones.back();
    m.layer = l.layer;
    m.start_s = m.end_s = l.end_s;
    m.detail =
        printf_string("the walls of floor %d finished (layer %d, the last)", l.floor, l.layer);
    m.title = printf_string("Floor %d walls finished", l.floor);
  }
  return milestones;
}

}  // namespace ccbuild::report
