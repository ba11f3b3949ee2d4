#include "ccbuild/dispatch/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild_lcm/ccbuild_job_t.hpp"

namespace ccbuild::dispatch {

bool LayerDeviation::ran() const {
  return std::isfinite(started_s);
}

double LayerDeviation::deviation_s() const {
  return ran() ? started_s - planned_start_s : 0.0;
}

bool LayerDeviation::off_plan() const {
  return ran() && std::abs(deviation_s()) > kOffPlan_s;
}

RunReport report_of(const Dispatcher& dispatcher) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  RunReport report;
  const auto& jobs = dispatcher.jobs();
  const auto& executed = dispatcher.executed();
  std::map<std::pair<int, int>, LayerDeviation> layers;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const DispatchJob& j = jobs[k];
    const auto ran = executed.find(j.job_id);
    if (ran != executed.end()) report.finished_s = std::max(report.finished_s, ran->second.second);
    const bool scheduled = dispatcher.origin_of(k) == k;  // not a recovery job
    if (j.kind != JobKind::kDeposit) {
      const char* what =
          j.kind == JobKind::kPipe    ? "pipes"
          : j.kind == JobKind::kSlab  ? "slab stages"
          : j.kind == JobKind::kPurge ? "purges"
          : j.kind == JobKind::kClimbPhase
              ? (j.phase == ccbuild_lcm::ccbuild_job_t::INSERT ? "pin insertions"
                                                               : "other climb phases")
              : nullptr;
      if (!what) continue;
      JobCount& c = report.crew_and_climber[what];
      c.planned += scheduled;
      c.ran += ran != executed.end();
      continue;
    }
    auto [at, made] = layers.try_emplace({j.floor, j.layer});
    LayerDeviation& l = at->second;
    if (made) {
      l.floor = j.floor;
      l.layer = j.layer;
      l.planned_start_s = l.started_s = inf;
      l.planned_end_s = l.ended_s = -inf;
    }
    if (scheduled) {
      l.planned_start_s = std::min(l.planned_start_s, j.start_s);
      l.planned_end_s = std::max(l.planned_end_s, j.start_s + j.duration_s);
    }
    if (ran == executed.end()) continue;
    l.started_s = std::min(l.started_s, ran->second.first);
    l.ended_s = std::max(l.ended_s, ran->second.second);
  }
  for (const auto& [key, l] : layers) {
    report.layers.push_back(l);
    report.off_plan += l.off_plan();
    report.not_run += !l.ran();
    report.worst_s = std::max(report.worst_s, std::abs(l.deviation_s()));
    if (report.floors.empty() || report.floors.back().floor != l.floor) {
      FloorDeviation f;
      f.floor = l.floor;
      f.planned_start_s = f.started_s = inf;
      f.planned_end_s = f.ended_s = -inf;
      report.floors.push_back(f);
    }
    FloorDeviation& f = report.floors.back();
    ++f.layers;
    f.off_plan += l.off_plan();
    f.not_run += !l.ran();
    if (std::abs(l.deviation_s()) > std::abs(f.worst_s)) f.worst_s = l.deviation_s();
    f.planned_start_s = std::min(f.planned_start_s, l.planned_start_s);
    f.planned_end_s = std::max(f.planned_end_s, l.planned_end_s);
    f.started_s = std::min(f.started_s, l.started_s);
    f.ended_s = std::max(f.ended_s, l.ended_s);
  }
  for (const Replan& r : dispatcher.replans()) {
    report.absorbed += r.what == "absorbed";
    report.later += r.what == "later";
    report.planned_joints += r.what == "planned joint";
    report.treatments_ran += r.treatment_job_id != 0 && executed.count(r.treatment_job_id) > 0;
  }
  return report;
}

}  // namespace ccbuild::dispatch
