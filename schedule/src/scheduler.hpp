#pragma once
// The scheduler behind build_schedule (schedule.hpp), internal to the schedule library: its
// plans (schedule_plans.cpp: each geometry at each nozzle count, the plans that follow
// the layer below, their registration under plan keys) and its walk up the building
// (schedule.cpp: nozzles, intervals, waits, pipes, slabs, climbs, totals) and its crew tasks
// (schedule_crew.cpp: lintels, slab formwork and pours).

#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "ccbuild/common/format.hpp"
#include "ccbuild/machine/gantry_yard.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "schedule_deposits.hpp"

namespace ccbuild::schedule::detail {

using Clock = std::chrono::steady_clock;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
/// A geometry whose one-nozzle layer takes more than this share of the maximum interval
/// is planned at every nozzle count too: the move and the waits still have to fit.
inline constexpr double kTryMoreNozzlesShare = 0.9;
/// The people on a crew task (a lintel's and a slab's come from the building): a pipe is
/// set by one, a joint treated by one, a climb supervised by two (one at the controls, one
/// at the pins).
inline constexpr int kPipeCrew = 1, kJointCrew = 1, kClimbCrew = 2;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Runs `tasks` on `jobs` threads; the calling thread reports progress as they finish.
/// Rethrows the first exception a task threw, once every task has ended.
void run_parallel(std::vector<std::function<void()>>& tasks, int jobs,
                  const std::function<void(int done, int total)>& on_done);

/// One geometry planned at one nozzle count.
struct Planned {
  bool usable = false;
  std::string why_not;  ///< when not usable
  std::string method;
  double layer_time_s = 0.0, deposition_s = 0.0, airtime_s = 0.0, max_idle_s = 0.0;
  double min_gap_m = 0.0;
  bool stopped_by_time = false;
  std::vector<std::vector<planner::Waypoint>> waypoints;  ///< per nozzle, layer time
  double planning_s = 0.0;
};

/// A layer in building order, as the pipe rule needs it: its floor, its index on the floor
/// and its geometry.
struct LayerOrder {
  int floor = 0, layer = 0, geometry = 0;
};

/// Per layer of `order` (the building's layers in order): the most pipe-casting time, s,
/// between two layers of its run (consecutive layers of one floor and geometry), so that
/// the run gets nozzles enough for it. Pipes cast after layer L delay the interval that
/// ends at L's successor on the floor, which belongs to that layer's run; pipes after a
/// floor's top layer delay no interval (the next floor starts on its slab).
/// `pipes_after` counts the pipes cast after each (floor, layer); each takes `pipe_s`.
std::vector<double> pipe_time_in_runs_s(const std::vector<LayerOrder>& order,
                                        const std::map<std::pair<int, int>, int>& pipes_after,
                                        double pipe_s);

/// A nozzle count's plan as the choice of count weighs it.
struct CountPlan {
  bool usable = false;
  double layer_time_s = 0.0;
  /// Its layer time with the time between two layers of the run and the move up, s.
  double interval_s = 0.0;
};

/// No plan of a layer on `nozzles` nozzles is faster than its deposition shared among
/// them: `deposition_s` is one nozzle's, s.
double deposition_share_s(double deposition_s, int nozzles);

/// Whether a plan on `nozzles` nozzles could fit `max_interval_s` at all: the share of
/// `deposition_s` (one nozzle's) with `between_s` is no more than the maximum.
bool share_could_fit(double deposition_s, int nozzles, double between_s, double max_interval_s);

/// The fewest of 1..`max_count` nozzles whose plan's interval fits `max_interval_s`; when
/// none does, the fastest usable count (the fewest of equally fast ones), else 1. `plan(n)`
/// plans count n. A count that `have(n)` says is not planned yet, and whose share of
/// `deposition_s` with `between_s` already exceeds the maximum, cannot fit: it is planned
/// only when it could still be the fastest (one nozzle included: a layer whose deposition
/// alone is over the maximum is planned on one nozzle only when no more is faster).
int fewest_fitting_count(int max_count, double deposition_s, double between_s,
                         double max_interval_s, const std::function<bool(int)>& have,
                         const std::function<CountPlan(int)>& plan);

/// The first count that fewest_fitting_count, given the same figures, would plan that
/// `known` (count -> its plan, none when not planned) does not hold; none when it needs
/// no more. Planning that count and asking again, until none, plans what
/// fewest_fitting_count would have, so that it then plans nothing and answers as before.
std::optional<int> next_count_to_plan(int max_count, double deposition_s, double between_s,
                                      double max_interval_s,
                                      const std::function<std::optional<CountPlan>(int)>& known);

}  // namespace ccbuild::schedule::detail

namespace ccbuild::schedule {

class PlanMemo {
 public:
  /// What a layer plan depends on besides its geometry and nozzle count.
  struct LayerScope {
    const void* machine = nullptr;  ///< the gantry model
    std::string building;           ///< SHA-256 of the building's layers, in order
    std::uint64_t seed = 0;
    double time_limit_s = 0.0;
    long max_kicks = -1;  ///< -1: chosen from the layer's size
    auto operator<=>(const LayerScope&) const = default;
  };
  /// What a climb depends on besides its stages.
  struct ClimbScope {
    const void* climber = nullptr;
    std::string building;
    std::uint64_t seed = 0;
    double time_limit_s = 0.0;
    auto operator<=>(const ClimbScope&) const = default;
  };
  std::map<std::tuple<LayerScope, int, int>, detail::Planned> layers;  ///< geometry, nozzles
  std::map<std::pair<ClimbScope, int>, climb::ClimbPlan> climbs;       ///< climb index
  /// The machines the scopes point at, kept alive so that no other takes their address.
  std::vector<std::shared_ptr<const void>> kept;
};

}  // namespace ccbuild::schedule

namespace ccbuild::schedule::detail {

inline std::string where_text(int floor, int layer) {
  return "floor " + std::to_string(floor) + " layer " + std::to_string(layer);
}

/// "wall 82 piece 1 at (16.000, 36.000) ft": where a piece ends, in `unit`.
inline std::string piece_text(const PieceEnd& e, floors::LengthUnit unit) {
  return printf_string("wall %lld piece %d at (%.3f, %.3f) %s", static_cast<long long>(e.wall),
                       e.piece, floors::length_in(e.x_m, unit), floors::length_in(e.y_m, unit),
                       floors::to_string(unit).c_str());
}

class Scheduler {
 public:
  Scheduler(const Setup& project, const ScheduleOptions& options)
      : project_(project),
        options_(options),
        machine_(*project.machine),
        material_(project.material),
        calendar_(project.calendar.get()),
        jobs_(options.jobs > 0
                  ? options.jobs
                  : std::max(1, static_cast<int>(std::thread::hardware_concurrency()))) {
    if (project.conditions) {
      maturity_.emplace(*project.conditions, project.material.maturity);
      anchor_maturity_.emplace(*project.conditions, project.anchor_mix().maturity);
    }
  }

  Schedule run();
  /// Takes `other`'s layers, as it sliced them, instead of slicing the building again:
  /// for a scheduler of the same building (the proof of a proposed interval changes only
  /// the material). Before run().
  void take_slices_of(const Scheduler& other) {
    slices_ = other.slices_;
    reps_ = other.reps_;
  }

 private:
  struct Slice {
    int floor = 0;
    floors::Layer layer;
    int geometry = 0;  ///< 0-based index into reps_
  };

  void progress(const std::string& line) const {
    if (options_.progress) options_.progress(line);
  }
  Planned plan(int geometry, int nozzles) const;
  /// Why a plan on `nozzles` of the machine's gantries leaves the others no room to park
  /// at the far end of the rails (its path reaches too far), or nothing.
  std::optional<std::string> no_room_to_park(
      const std::vector<std::vector<planner::Waypoint>>& waypoints, int nozzles) const;
  const Planned& planned(int geometry, int nozzles);
  /// The fewest nozzles whose plan of `geometry` is usable and, with the move up to its
  /// own start, no longer than the maximum interval: below that, the next layer of the
  /// same geometry cannot keep its intervals, and a layer deposited slowly makes the one
  /// above it late at the pieces it did first. `between_s`: the most time spent between
  /// two layers of the run (pipes). When no count is fast enough, the fastest.
  int fewest_nozzles(int geometry, double between_s);
  /// What fewest_nozzles weighs of plan `p`: usable, its layer time, and the interval to
  /// the next layer like it (`between_s` and the move up to its own start).
  CountPlan count_plan(const Planned& p, double between_s) const;
  /// Plans, in parallel batches, the counts fewest_nozzles will ask for on the layers'
  /// geometries and pipe times, so that it does not plan them one at a time: it is run on
  /// each (geometry, pipe time) of the layers, stopping at the first count it asks for
  /// that is not planned; those are planned together, and again until it asks for none.
  /// Its answers are those it would give without this: it asks for the same counts, in
  /// the same order.
  void plan_counts_ahead();
  /// The one-nozzle plan of `geometry`; null before it is made.
  const Planned* single_plan(int geometry) const;
  /// The deposition of `geometry` on one nozzle, s (planner::deposition_time_s).
  double deposition_of(int geometry) const;
  /// The counts planned ahead for `geometry` when one nozzle is too slow for it: the
  /// machine's (the fastest, as a rule) and every count whose share of the deposition
  /// could fit the maximum interval (others are planned by the count choice only where
  /// they could be the fastest), as (geometry, count).
  std::vector<std::pair<int, int>> counts_past_one(int geometry) const;
  void plan_batch(const std::vector<std::pair<int, int>>& wanted, const std::string& what);
  /// Orders (geometry, nozzles) keys by the geometry's pieces, most first (stable).
  void largest_first(std::vector<std::pair<int, int>>& keys) const;
  /// Registers plan `p` of `slice` under `base`, labelled with the slice's walls (a
  /// variant "<base>m1", ... when another layer of its geometry names them differently);
  /// returns its key.
  std::string register_plan(const PlanKey& base, const Slice& slice, int nozzles, const Planned& p);
  /// The key of `slice`'s optimised plan at `nozzles`.
  std::string plan_key(const Slice& slice, int nozzles);
  /// The nozzles depositing `slice` in the order the plan `below_key` deposited the layer
  /// below: where the geometry changes (openings begin or end), an optimised plan may
  /// cover first what the layer below did last, and break the maximum interval there.
  /// With `hold_back`, a gantry that would come too close to its neighbour starts later.
  const Planned& follow_plan(const Slice& slice, const std::string& below_key, bool hold_back);
  static PlanKey follow_key(const Slice& slice, const std::string& below_key, bool hold_back) {
    PlanKey key;
    key.geometry = slice.geometry + 1;
    key.follows = below_key;
    key.held_back = hold_back;
    return key;
  }
  /// From the end of the nozzles' paths on plan `from_key` to the start of `to_key`'s, one
  /// layer up (planner::layer_change_s), s.
  double move_between(const std::string& from_key, const std::string& to_key) const;
  /// Each gantry's first (or last) pose on plan `key` at the layer whose top is at
  /// `z_top_m`, by nozzle; none where the plan leaves that gantry idle.
  std::vector<std::optional<machine::GantryPose>> gantry_poses(const std::string& key,
                                                               double z_top_m, bool last) const;
  const IntervalOffsets& offsets(const Slice& upper, const std::string& upper_key,
                                 const std::string& lower_key);
  /// The earliest start of global layer `i` that the layers below `first_checked` can
  /// carry (each at its age from its end), and why; `impossible` when one never can.
  double strength_ready_s(int i, int first_checked, double earliest_s, WaitReason& reason,
                          bool& impossible) const;
  /// Slices the building, places the climbing stages, plans every geometry with one
  /// nozzle and every climb (in parallel), then the slow geometries with more nozzles.
  void prepare();
  /// Plans and times global layer i (false: no plan at all, the schedule stops there).
  bool schedule_layer(int i);
  /// What follows layer i: its pipes, the slab at a floor's top, a climb (false: the
  /// climb can never start, the schedule stops there).
  bool after_layer(int i);
  /// Sets the lintels over the openings whose first layer above the head is global layer
  /// `next`, from `t_s`; returns when they are set (+infinity: no working window holds one,
  /// the schedule stops there).
  double place_lintels(int next, double t_s);
  /// The slab (or, with `roof`, the roof) over the floor whose top layer is `top`, with
  /// `slabs:`: formwork and reinforcement, then the pour, each in working hours; sets when
  /// the slab carries the next floor. Returns the pour's end (+infinity: no window holds it).
  double pour_slab(const ScheduledLayer& top, bool roof, double t_s);
  /// A crew task of `kind` for `duration_s` from `t_s` (see crew_start_s), with its wait,
  /// start, end and crew; `t_s` moves to its end. Unset (after failing): no window holds it.
  std::optional<Event> crew_task(Event::Kind kind, double& t_s, double duration_s, int crew,
                                 bool needs_crew, const std::string& what, int floor, int layer);
  /// The start of `duration_s` of crew work from `t_s` (working hours when there is a
  /// calendar; a wait there lets the next layer start on a planned joint); +infinity, after
  /// failing with `what`, when no window holds it.
  double crew_start_s(double t_s, double duration_s, bool needs_crew, const std::string& what,
                      int floor, int layer);
  void fail(Infeasibility infeasibility);
  /// The fixes of an interval over the maximum, for the chosen plan `p` on `nozzles`.
  void compute_fix(Infeasibility& inf, const Slice& slice, const Planned& p, int nozzles);

  const Setup& project_;
  const ScheduleOptions& options_;
  const machine::MachineModel& machine_;
  const floors::MaterialProfile& material_;
  /// The site's calendar; null: around the clock.
  const site::SiteCalendar* calendar_;
  bool printing_attended() const { return calendar_ && calendar_->programme().printing_attended; }
  /// Equivalent age on site (the material's, the anchor mix's), with site weather; unset:
  /// ages are real ages (20 °C).
  std::optional<site::EquivalentAge> maturity_, anchor_maturity_;
  /// When concrete placed at `from_s` is `age_s` old (equivalent age with weather).
  double aged_s(double from_s, double age_s) const {
    return site::age_reached_s(maturity_ ? &*maturity_ : nullptr, from_s, age_s);
  }
  /// The largest and smallest local interval (equivalent age with weather) of a layer
  /// starting at `start_s` on one that started at `below_start_s`.
  double largest_interval_s(const IntervalOffsets& o, double below_start_s, double start_s) const;
  double smallest_interval_s(const IntervalOffsets& o, double below_start_s, double start_s) const;
  /// The peak flow of registered plan `key`, m³/s (computed once).
  double peak_flow_of(const std::string& key);
  std::map<std::string, double> peak_flow_;
  /// A time for messages: a date and time of day on a calendar, else seconds.
  std::string when_text(double t_s) const {
    return calendar_ ? calendar_->local_text(t_s) : printf_string("%.1f s", t_s);
  }
  /// The strength a layer needs to carry `height_m` of wall above its bottom, with the
  /// material's safety factor, MPa (floors::MaterialProfile::strength_to_carry_mpa).
  double required_strength_mpa(double height_m) const {
    return material_.strength_to_carry_mpa(height_m);
  }
  /// Why a plan whose longest air move is `max_idle_s` is not used (a plan with an air
  /// move over the nozzle idle limit clogs).
  std::string idle_limit_broken(double max_idle_s) const {
    return printf_string("an air move of %.1f s breaks the nozzle idle limit of %.1f s", max_idle_s,
                         machine_.nozzle_idle_limit_s);
  }
  int jobs_;

  /// The memo's keys for this schedule (set by prepare, once the layers are known).
  void set_memo_scopes();
  PlanMemo::LayerScope layer_scope_;
  PlanMemo::ClimbScope climb_scope_;
  /// The memo's plan of `geometry` at `nozzles`, copied into planned_; false when none.
  bool recall(int geometry, int nozzles);
  void remember(int geometry, int nozzles);

  std::vector<Slice> slices_;
  std::vector<floors::Layer> reps_;  ///< each geometry's first layer
  std::map<std::pair<int, int>, Planned> planned_;
  std::map<std::string, DepositIndex> indexes_;
  std::map<std::pair<std::string, std::string>, IntervalOffsets> offsets_;
  std::map<std::string, std::vector<std::string>> variants_;
  std::map<std::string, Planned> follow_;
  /// Every registered plan key's plan (in planned_ or follow_, whose nodes stay put).
  std::map<std::string, const Planned*> registered_;
  Schedule schedule_;
  std::vector<double> layer_end_s_;  ///< per global layer, once scheduled
  int further_failures_ = 0;

  // Prepared once.
  std::vector<climb::ClimbPlan> climbs_;  ///< climb c goes from stage c to c + 1
  std::map<std::pair<int, int>, std::vector<climb::Anchor>> pipes_after_;  ///< (floor, layer)
  std::map<std::pair<int, int>, int> climb_after_;  ///< (floor, layer) -> climb index
  std::vector<double> run_between_s_;  ///< per global layer: the most pipe time in its run
  // The state between layers.
  std::map<PipeKey, double> pipe_done_s_;  ///< when each pipe was cast
  double previous_end_s_ = 0.0;            ///< the machine is free from here
  double ready_extra_s_ = 0.0;             ///< pipes, slab and climb after the previous layer
  double pipes_before_s_ = 0.0;            ///< cast after the previous layer
  /// Work stopped after the previous layer (pipes or a climb waited for working hours,
  /// lintels were set): the next layer may start on a planned joint.
  bool stopped_since_below_ = false;
  /// Lintels set before global layer i (the first layer over their openings' heads).
  std::map<int, std::vector<LintelTask>> lintels_before_;
  /// With `slabs:`, when the last slab poured carries the walls of the floor above it
  /// (-infinity: none poured yet), and why.
  double slab_ready_s_ = -kInf;
  std::string slab_ready_detail_;
  std::string previous_key_;
  /// Where the gantries stand after the layers so far: the moves before the next layer
  /// (parks and returns from them) as the dispatcher sends them.
  std::optional<machine::GantryYard> yard_;
};

}  // namespace ccbuild::schedule::detail
