// The scheduler's crew tasks between layers (scheduler.hpp): lintels over the openings
// before the first layer at or over their heads, slabs formed and poured after a floor's
// top layer, each fitted to the site's working hours.

#include <cmath>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/schedule/json_blocks.hpp"
#include "scheduler.hpp"

namespace ccbuild::schedule::detail {

std::optional<Event> Scheduler::crew_task(Event::Kind kind, double& t_s, double duration_s,
                                          int crew, bool needs_crew, const std::string& what,
                                          int floor, int layer) {
  const double ready_s = t_s;
  t_s = crew_start_s(t_s, duration_s, needs_crew, what, floor, layer);
  if (!std::isfinite(t_s)) return std::nullopt;
  Event e;
  e.kind = kind;
  e.wait_before_s = t_s - ready_s;
  e.start_s = t_s;
  e.end_s = t_s += duration_s;
  e.crew = crew;
  return e;
}

double Scheduler::crew_start_s(double t_s, double duration_s, bool needs_crew,
                               const std::string& what, int floor, int layer) {
  if (!calendar_ || !needs_crew) return t_s;
  const double fit_s = calendar_->fit_s(t_s, duration_s);
  if (!std::isfinite(fit_s)) {
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kCalendar;
    inf.floor = floor;
    inf.layer = layer;
    inf.message = printf_string(
        "%s takes %.2f h of crew work, and no working window from %s holds it (the longest is "
        "%.2f h)",
        what.c_str(), duration_s / 3600.0, calendar_->local_text(t_s).c_str(),
        calendar_->longest_window_s() / 3600.0);
    inf.fix = "longer working hours, or a shorter task";
    fail(inf);
    return kInf;
  }
  if (fit_s > t_s + 1e-9) stopped_since_below_ = true;
  return fit_s;
}

double Scheduler::place_lintels(int next, double t_s) {
  const auto it = lintels_before_.find(next);
  if (it == lintels_before_.end()) return t_s;
  const floors::LintelSpec& spec = project_.building.lintels;
  const Slice& before = slices_[next];
  stopped_since_below_ = true;  // printing stops for them: the next layer may start on a joint
  for (const auto& task : it->second) {
    const std::string what = "the lintel over opening " + task.opening;
    const bool needs_crew = !spec.by_arm || printing_attended();
    auto made = crew_task(Event::Kind::kLintel, t_s, spec.place_s, spec.crew, needs_crew, what,
                          before.floor, before.layer.index);
    if (!made) return kInf;
    Event& e = *made;
    // Named after the layer it follows, like every event.
    e.floor = schedule_.layers.back().floor;
    e.layer = schedule_.layers.back().layer;
    e.detail = printf_string(
        "%s lintel over opening %s (wall %lld, %s to %s), head at %s, by %s, before "
        "floor %d layer %d",
        floors::to_string(task.type).c_str(), task.opening.c_str(),
        static_cast<long long>(task.wall), project_.length(task.from_m).c_str(),
        project_.length(task.to_m).c_str(), project_.length(task.head_z_m).c_str(),
        task.by_arm ? "the arm" : printf_string("a crew of %d", spec.crew).c_str(), before.floor,
        before.layer.index);
    e.lintel = task;
    schedule_.events.push_back(std::move(e));
  }
  return t_s;
}

double Scheduler::pour_slab(const ScheduledLayer& top, bool roof, double t_s) {
  const floors::SlabSpec& spec = *project_.building.slabs;
  const floors::Floor* floor = nullptr;
  for (const auto& f : project_.building.floors)
    if (f.index == top.floor) floor = &f;
  const std::string what = roof ? "the roof over floor " + std::to_string(top.floor)
                                : "the slab over floor " + std::to_string(top.floor);
  // Formwork and reinforcement, then one continuous pour, each within working hours.
  auto setup = crew_task(Event::Kind::kSlab, t_s, spec.setup_s, spec.crew, true,
                         "the formwork of " + what, top.floor, top.layer);
  if (!setup) return kInf;
  setup->floor = top.floor;
  setup->layer = top.layer;
  setup->roof = roof;
  setup->detail = "formwork and reinforcement of " + what;
  schedule_.events.push_back(std::move(*setup));

  const double thickness_m = floor ? floor->slab_m : spec.thickness_m;
  const double m3 = rounded((floor ? floors::slab_area_m2(*floor) : 0.0) * thickness_m);
  const double pour_s = m3 / spec.pour_rate_m3_s;
  auto made = crew_task(Event::Kind::kPour, t_s, pour_s, spec.crew, true, "the pour of " + what,
                        top.floor, top.layer);
  if (!made) return kInf;
  Event& pour = *made;
  pour.floor = top.floor;
  pour.layer = top.layer;
  pour.roof = roof;
  pour.concrete_m3 = m3;
  pour.detail =
      printf_string("pour of %s: %s (%s thick) at %s", what.c_str(),
                    floors::volume_text(m3, project_.building.units).c_str(),
                    project_.length(thickness_m).c_str(),
                    floors::flow_text(spec.pour_rate_m3_s, project_.building.units).c_str());
  const double pour_end_s = pour.end_s;
  schedule_.events.push_back(std::move(pour));
  if (!roof) {
    // The next floor's walls start once the slab's concrete carries them (EN 1992-1-1
    // §3.1.2, its age equivalent at 20 °C with the site's weather).
    const double age_s = spec.concrete.age_for_strength_s(spec.ready_mpa);
    slab_ready_s_ = aged_s(pour_end_s, age_s);
    slab_ready_detail_ =
        printf_string("%s reaches %.1f MPa %.1f h (equivalent at 20 °C) after its pour ends at %s",
                      what.c_str(), spec.ready_mpa, age_s / 3600.0, when_text(pour_end_s).c_str());
  }
  return t_s;
}

}  // namespace ccbuild::schedule::detail
