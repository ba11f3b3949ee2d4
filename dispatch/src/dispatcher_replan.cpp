// When each job starts: the common starts and their re-plans from what the machines laid
// (docs/dispatch.md, "When the site runs late").

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/dispatch/dispatcher.hpp"

namespace ccbuild::dispatch {

double Dispatcher::start_of(std::size_t index) const {
  // A common start for the jobs released together: planned, plus the delay so far
  // (recovery jobs carry their own starts).
  double start_s = jobs_[index].start_s;
  if (origin_[index] == index) start_s += delay_s_;
  // A job that runs alone starts when the last of its layer's other jobs ended (each
  // machine keeps its own clock), or when it was re-planned to.
  if (after_layer_[index]) {
    const double layer_s = jobs_[origin_[index]].start_s;
    for (std::size_t k = 0; k < jobs_.size(); ++k) {
      const auto it = executed_.find(jobs_[k].job_id);
      if (k != index && jobs_[origin_[k]].start_s == layer_s && it != executed_.end())
        start_s = std::max(start_s, it->second.second);
    }
  }
  if (const auto at = start_at_.find(index); at != start_at_.end())
    start_s = std::max(start_s, at->second);
  return start_s;
}

std::vector<std::size_t> Dispatcher::starting_with(std::size_t index) const {
  const DispatchJob& job = jobs_[index];
  if (origin_[index] != index) return {index};
  std::vector<std::size_t> group;
  if (job.kind == JobKind::kDeposit) {
    // A layer's deposits: schedule jobs with its planned start (adjacent in order).
    for (std::size_t k = 0; k < schedule_jobs_; ++k)
      if (jobs_[k].kind == JobKind::kDeposit && jobs_[k].start_s == job.start_s &&
          jobs_[k].floor == job.floor && jobs_[k].layer == job.layer)
        group.push_back(k);
  } else {
    group.push_back(index);
  }
  return group;
}

void Dispatcher::record_laid(std::size_t index, const JournalRow& row) {
  const DispatchJob& d = jobs_[index];
  if (d.kind != JobKind::kDeposit) return;
  wire::add_deposits(laid_[{d.floor, d.layer}], d.path, row.started_s,
                     row.state == JobState::kDone ? -1 : row.stopped_at);
  auto [at, made] = layer_end_.try_emplace({d.floor, d.layer}, d.z_bottom_m, row.finished_s);
  if (!made) at->second.second = std::max(at->second.second, row.finished_s);
}

namespace {
/// Within the machine's rounding of an interval (it refuses beyond 1 ms).
constexpr double kReplanSlack_s = 5e-4;
}  // namespace

StartWindow Dispatcher::window_below(const std::vector<std::size_t>& deposits) const {
  // The layer's deposits (times from their common start) against what every machine laid
  // below, by the scheduler's rule (rules/intervals.hpp; docs/dispatch.md).
  if (deposits.empty()) return {};
  const DispatchJob& first = jobs_[deposits.front()];
  const auto below = laid_.find({first.floor, first.layer - 1});
  if (below == laid_.end()) return {};
  rules::DepositIndex above;
  for (std::size_t k : deposits) wire::add_deposits(above, jobs_[k].path, 0.0);
  return rules::start_window(rules::interval_offsets(above, below->second), options_.min_interval_s,
                             options_.max_interval_s, &options_.age_clock);
}

void Dispatcher::replan(std::size_t index) {
  // Called before every job's first send: only deposits and absorbing waits go further.
  const DispatchJob& job = jobs_[index];
  const bool schedule_job = origin_[index] == index;
  if (job.absorbs != DelayAbsorption::kNone && schedule_job) {
    if (decided_.insert(job.job_id).second) {
      if (job.absorbs == DelayAbsorption::kShortenWait)
        absorb(index);
      else
        start_when_ready(index);
    }
    return;
  }
  if (job.kind != JobKind::kDeposit || options_.max_interval_s <= 0.0) return;
  if (decided_.count(job.job_id)) return;
  const std::vector<std::size_t> group = starting_with(index);
  for (std::size_t k : group) decided_.insert(jobs_[k].job_id);
  const double start_s = start_of(index);
  const StartWindow w = window_below(group);
  if (w.ends_covered == 0) return;
  Replan r;
  r.job_id = job.job_id;
  r.delay_s = delay_s_;
  const bool on_joint = job.on_planned_joint;
  const double earliest_start_s = std::max(start_s, w.earliest_s);
  double new_start_s = earliest_start_s;
  const bool cold = !on_joint && (w.empty() || new_start_s > w.latest_s + kReplanSlack_s);
  const std::string what =
      schedule_job ? printf_string("floor %d layer %d", job.floor, job.layer) : job.detail;
  if (!cold) {
    if (new_start_s <= start_s + kReplanSlack_s) return;
    r.what = "later";
    r.detail = printf_string(
        "%s starts %.1f s later (at %.1f s): no stretch of wall below is covered sooner than "
        "the minimum %.0f s after the machines laid it",
        what.c_str(), new_start_s - start_s, new_start_s, options_.min_interval_s);
  } else {
    // No start keeps every joint below within the maximum: a planned joint, treated
    // first (once the layer below is old enough), as the schedule plans one.
    r.what = "planned joint";
    r.treatment_s = options_.joint_treatment_s;
    r.treatment_start_s = std::max(start_s, w.newest_below_s + options_.joint_min_age_s);
    new_start_s = std::max(r.treatment_start_s + r.treatment_s, w.earliest_s);
    // An id between the jobs its machine ran before and this one.
    const Queue& q = queues_.at(job.machine_id);
    std::int64_t before_id = 0;
    for (std::size_t k : q.jobs) {
      if (k == index) break;
      before_id = std::max(before_id, jobs_[k].job_id);
    }
    for (std::int64_t id = job.job_id - 1; id > before_id && r.treatment_job_id == 0; --id)
      if (!index_of_.count(id)) r.treatment_job_id = id;
    if (r.treatment_job_id == 0) {
      stop("no job id left for the treatment of a planned joint before job " +
           std::to_string(job.job_id));
      return;
    }
    const std::string why =
        w.empty()
            ? printf_string(
                  "the piece ends below were laid %.1f s apart, more than the "
                  "material's window allows",
                  w.earliest_s - w.latest_s + options_.max_interval_s - options_.min_interval_s)
            : printf_string(
                  "it could start at %.1f s at the earliest, and the last "
                  "start that covers every piece end below within %.0f s "
                  "was %.1f s",
                  earliest_start_s, options_.max_interval_s, w.latest_s);
    r.detail = printf_string(
        "%s on a planned joint: %s; the top of floor %d layer %d treated (%.0f s) from %.1f "
        "s, then it starts at %.1f s",
        what.c_str(), why.c_str(), job.floor, job.layer - 1, r.treatment_s, r.treatment_start_s,
        new_start_s);
  }
  r.start_s = new_start_s;
  if (schedule_job) r.delay_s = new_start_s - job.start_s;
  journal_.record_replan(r);  // before it is acted on
  apply(r);
}

double Dispatcher::carried_from_s(const DispatchJob& deposit, std::string& bound) const {
  const floors::MaterialProfile& mix = *options_.material;
  double from_s = -std::numeric_limits<double>::infinity();
  for (const auto& [key, bottom_end] : layer_end_) {
    const double age_s =
        mix.age_for_strength_s(mix.strength_to_carry_mpa(deposit.z_top_m - bottom_end.first));
    if (!std::isfinite(age_s)) return std::numeric_limits<double>::infinity();
    if (bottom_end.second + age_s > from_s) {
      from_s = bottom_end.second + age_s;
      bound = printf_string("the strength of floor %d layer %d", key.first, key.second);
    }
  }
  return from_s;
}

void Dispatcher::absorb(std::size_t index) {
  const DispatchJob& wait = jobs_[index];
  if (!options_.material || delay_s_ <= kReplanSlack_s || options_.max_interval_s <= 0.0) return;
  // The layer it waits for: its deposits' planned start, and the jobs between (a planned
  // joint's treatment, a purge) keep their planned lengths.
  std::vector<std::size_t> layer;
  for (std::size_t k = index + 1; k < schedule_jobs_; ++k)
    if (jobs_[k].kind == JobKind::kDeposit && jobs_[k].floor == wait.floor &&
        jobs_[k].layer == wait.layer) {
      layer = starting_with(k);
      break;
    }
  if (layer.empty()) return;
  const DispatchJob& first = jobs_[layer.front()];
  const double planned_s = first.start_s;
  const double wait_from_s = start_of(index);
  const double between_s = planned_s - (wait.start_s + wait.duration_s);
  // The earliest start: as planned, never sooner (working hours); once the wait is
  // over; once every layer laid below can carry it (from its last deposit's end: more
  // than the scheduler asks of the layer just below, which it checks piece end by piece
  // end); once no piece end below is covered sooner than the minimum interval.
  double start_s = std::max(planned_s, wait_from_s + between_s);
  std::string bound = "its planned start", carrying;
  const double carried_s = carried_from_s(first, carrying);
  if (!std::isfinite(carried_s) && carried_s > 0.0) return;
  if (carried_s > start_s) {
    start_s = carried_s;
    bound = carrying;
  }
  const StartWindow w = window_below(layer);
  if (w.earliest_s > start_s) {
    start_s = w.earliest_s;
    bound =
        printf_string("the minimum interval over floor %d layer %d", first.floor, first.layer - 1);
  }
  const double absorbed_s = planned_s + delay_s_ - start_s;
  if (absorbed_s <= kReplanSlack_s) return;
  record_absorbed(
      index, wait_from_s, wait.duration_s - absorbed_s, delay_s_ - absorbed_s,
      printf_string("%s: shortened by %.1f s of the run's %.1f s delay; floor %d layer %d starts "
                    "at %.1f s, bound by %s",
                    wait.detail.c_str(), absorbed_s, delay_s_, first.floor, first.layer, start_s,
                    bound.c_str()));
}

void Dispatcher::start_when_ready(std::size_t index) {
  const DispatchJob& work = jobs_[index];
  if (!options_.material || delay_s_ <= kReplanSlack_s) return;
  // It was released: every job planned to start before it has ended. It starts once the
  // last of them did, never before its planned start (the crew is booked for then).
  double start_s = work.start_s;
  std::string bound = "its planned start";
  for (const auto& [id, times] : executed_) {
    const std::size_t k = index_of_.at(id);
    if (jobs_[origin_[k]].start_s < work.start_s && times.second > start_s) {
      start_s = times.second;
      bound = printf_string("the end of job %lld (%s)", static_cast<long long>(id),
                            jobs_[k].detail.c_str());
    }
  }
  // The layer after it starts as much later than planned as this job: no sooner than the
  // layers laid below can carry it (its minimum interval is re-checked when it goes out).
  for (std::size_t k = index + 1; k < schedule_jobs_; ++k) {
    if (jobs_[k].kind != JobKind::kDeposit) continue;
    std::string carrying;
    const double carried_s = carried_from_s(jobs_[k], carrying);
    if (!std::isfinite(carried_s) && carried_s > 0.0) return;
    if (carried_s - jobs_[k].start_s > start_s - work.start_s) {
      start_s = work.start_s + (carried_s - jobs_[k].start_s);
      bound = carrying + printf_string(" for floor %d layer %d", jobs_[k].floor, jobs_[k].layer);
    }
    break;
  }
  const double absorbed_s = work.start_s + delay_s_ - start_s;
  if (absorbed_s <= kReplanSlack_s) return;
  record_absorbed(index, start_s, work.duration_s, start_s - work.start_s,
                  printf_string("%s: starts at %.1f s, %.1f s of the run's %.1f s delay "
                                "absorbed, bound by %s",
                                work.detail.c_str(), start_s, absorbed_s, delay_s_, bound.c_str()));
}

void Dispatcher::record_absorbed(std::size_t index, double start_s, double duration_s,
                                 double delay_s, std::string detail) {
  Replan r;
  r.job_id = jobs_[index].job_id;
  r.what = "absorbed";
  r.start_s = start_s;
  r.delay_s = delay_s;
  r.duration_s = duration_s;
  r.detail = std::move(detail);
  journal_.record_replan(r);  // before it is acted on
  apply(r);
}

void Dispatcher::apply(const Replan& r) {
  const std::size_t index = index_of_.at(r.job_id);
  const std::vector<std::size_t> group = starting_with(index);
  for (std::size_t k : group) decided_.insert(jobs_[k].job_id);
  replans_.push_back(r);
  if (origin_[index] == index)
    delay_s_ = r.delay_s;
  else
    start_at_[index] = r.start_s;
  if (r.what == "absorbed") {  // a wait starts as it would have and ends sooner; crew work
                               // starts sooner
    start_at_[index] = r.start_s;
    duration_at_[index] = r.duration_s;  // (its planned end stays what lateness counts from)
  }
  if (r.what != "planned joint") return;
  for (std::size_t k : group) jobs_[k].on_planned_joint = true;
  const DispatchJob& job = jobs_[index];
  DispatchJob treat;
  treat.job_id = r.treatment_job_id;
  treat.machine_id = job.machine_id;
  treat.kind = JobKind::kWait;
  treat.floor = job.floor;
  treat.layer = job.layer;
  treat.start_s = r.treatment_start_s;
  treat.duration_s = r.treatment_s;
  treat.detail = printf_string(
      "planned joint (re-planned): the top of floor %d layer %d treated before floor %d "
      "layer %d",
      job.floor, job.layer - 1, job.floor, job.layer);
  insert_before(index, std::move(treat));
}

}  // namespace ccbuild::dispatch
