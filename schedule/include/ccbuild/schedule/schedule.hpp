#pragma once
// The whole-building schedule (paper 000 §3.3 and §7): every layer of every floor
// planned and timed, bottom to top, with
//   - the fewest nozzles (1 up to the machine's) whose plan keeps every wall piece's
//     interval to the layer below at or under the material's maximum;
//   - the interval checked per wall piece, at both of its ends: the time between
//     depositing a point of layer k and depositing over it in layer k + 1;
//   - waits before a layer when an interval would fall under the minimum, when the layers
//     below could not yet carry it (their strength at their age against the weight above
//     them, times the material's safety factor), or when a climb's anchors are too young;
//     each wait with its reasons and the numbers, and a purge when it outlasts the nozzle
//     idle limit;
//   - on a climbing machine: pipe placements between the layers climb/ chose, climbs
//     (stages break at floor tops where the reach allows), each planned by climb/;
//   - the slab stage between floors (the next floor starts on its slab: no interval to
//     the floor below, whose walls carry the new ones).
// Each distinct layer geometry is planned once per nozzle count (in parallel, `jobs`);
// the result does not depend on `jobs` or on the order plans finish in.
// SI units: m, s.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/rules/intervals.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::schedule {

/// Layer plans and climbs one schedule planned, for the next schedule of the same building
/// to take instead of planning them again (make_plan_memo).
class PlanMemo;
/// An empty memo, to share between schedules of one building that differ in objective,
/// material, site or climbing machine: the CLI's comparison of objectives, the anchor
/// what-ifs. Shared with another building or another gantry it is simply not used.
std::shared_ptr<PlanMemo> make_plan_memo();

/// What the scheduler optimises layer by layer.
enum class Objective {
  kFewestNozzles,  ///< "fewest-nozzles": the fewest nozzles that keep every interval
  kShortest,       ///< "shortest": the count whose layer ends earliest (fewest on a tie)
};
std::string to_string(Objective objective);

struct ScheduleOptions {
  std::uint64_t seed = 1;
  Objective objective = Objective::kFewestNozzles;
  /// Threads planning distinct layers and climbs; 0: every core.
  int jobs = 0;
  /// Per plan (one geometry at one nozzle count). Plans end on their kick budget well
  /// before it on ordinary layers; a plan stopped by it is named in the warnings, since
  /// its result then depends on the machine's speed.
  double layer_time_limit_s = 60.0;
  /// Kicks of each single-nozzle search (unset: chosen from the layer's size).
  std::optional<long> max_kicks;
  /// Per climb's planning.
  double climb_time_limit_s = 20.0;
  /// Progress lines ("planned 12 of 30 layer plans"), called from the calling thread.
  std::function<void(const std::string&)> progress;
  /// Plans and climbs to reuse and to add to (null: none). A layer plan is reused for the
  /// same layers of the building, the same gantry model (the same object), seed and
  /// limits; a climb also for the same climbing machine (the same object). Plans do not
  /// depend on the objective, the material or the site. One schedule at a time.
  std::shared_ptr<PlanMemo> memo;
};

/// Which constraint made a layer (or a climb) wait.
enum class WaitKind {
  kMinInterval,     ///< "min-interval": a wall piece would be covered too soon
  kStrength,        ///< "strength": a layer below could not yet carry the walls above it
  kAnchorStrength,  ///< "anchor-strength": a climb's anchor is younger than it must be
  kSlab,            ///< "slab": the slab stage between floors
  kOffShift,        ///< "off-shift": work that needs a crew waits for working hours
  kJoint,           ///< "joint": a planned joint's treatment waits for the layer below's age
  kCold,            ///< "cold": the air is outside the material's placing range
  kWind,            ///< "wind": a climb waits for the wind to stay under the machine's limit
};
/// The name the JSON and the messages use ("min-interval", ...).
std::string to_string(WaitKind kind);
/// The kind of that name, if it is one.
std::optional<WaitKind> wait_kind_named(const std::string& name);

/// Why a layer (or a climb) waited: one constraint and its numbers.
struct WaitReason {
  WaitKind kind = WaitKind::kMinInterval;
  double required_s = 0.0;  ///< the wait this reason alone requires, s from the earliest start
  std::string detail;       ///< the numbers, in words
  /// When it began to hold, s from the earliest start (0: from the start of the wait; a
  /// night found once the anchors were strong holds from then).
  double from_s = 0.0;
  /// How long it was the binding reason (bind_wait_reasons): the binding times of a
  /// wait's reasons add up to the wait.
  double binding_s = 0.0;
};

/// Sets each reason's binding_s: at each moment of the wait, of the reasons holding then
/// (from_s up to required_s), the one that holds the longest binds (on a tie, the first);
/// a moment none holds binds none.
void bind_wait_reasons(std::vector<WaitReason>& reasons);

/// The binding time of the reasons of kind `kind`, s.
double binding_s(const std::vector<WaitReason>& reasons, WaitKind kind);

/// Every kind's name, comma-separated, for messages that list what is expected.
std::string wait_kind_names();
/// Every kind, in the order of the enum: the one list of them.
const std::vector<WaitKind>& wait_kinds();

/// The kinds of `reasons`, each once, in their order: "min-interval, strength" (a wait may
/// have two strength reasons, the piece below and the layer's bottom).
std::string reason_kinds_text(const std::vector<WaitReason>& reasons);

/// One wall piece's end, where the local interval is extreme.
/// A point of a wall piece (rules/intervals.hpp): wall, 1-based piece, where (m).
using PieceEnd = rules::PieceEnd;

struct ScheduledLayer {
  int floor = 0;
  int layer = 0;
  double z_bottom_m = 0.0, z_top_m = 0.0;
  int geometry = 0;  ///< the distinct geometry's label (1-based)
  std::string plan;  ///< key into Schedule::plans
  int nozzles = 1;
  std::string method;  ///< "cc-tsp" for one nozzle, else the multi-nozzle method
  double start_s = 0.0, end_s = 0.0;
  double deposition_s = 0.0;    ///< per nozzle, summed
  double airtime_s = 0.0;       ///< per nozzle, summed
  double max_idle_s = 0.0;      ///< the longest air move
  double move_before_s = 0.0;   ///< lift and travel from the previous layer's end
  double pipes_before_s = 0.0;  ///< pipes cast between the previous layer and this one
  double wait_before_s = 0.0;
  std::vector<WaitReason> wait_reasons;
  bool purge_before = false;
  /// The layer starts on a planned construction joint: printing stopped at the end of the
  /// layer below for off-shift hours, and the joint was treated (a `joint` event) before
  /// this layer; its interval to the layer below is then not bound by the maximum.
  bool planned_joint = false;
  /// Start to start from the layer below on the same floor; unset on a floor's first.
  std::optional<double> interval_s;
  /// Over every wall piece end of this layer above a wall of the layer below.
  std::optional<double> local_interval_min_s, local_interval_max_s;
  /// The same in equivalent age at 20 °C, when the site has weather (what the material's
  /// window bounds then).
  std::optional<double> equivalent_interval_min_s, equivalent_interval_max_s;
  PieceEnd local_min_at, local_max_at;
  int piece_ends_checked = 0;
  /// The layer just below against the walls it carries once this one is laid (none on a
  /// floor's first layer): its strength at the age its soonest covered piece end then has
  /// (equivalent_interval_min_s with site weather, else local_interval_min_s), and the
  /// strength the walls from its bottom to this layer's top need with the safety factor,
  /// MPa. What the report's buildability chart draws.
  std::optional<double> below_strength_mpa, below_required_mpa;
  double concrete_m3 = 0.0;     ///< its pieces' volume
  double peak_flow_m3_s = 0.0;  ///< the most its nozzles deposit at once
};

/// A nozzle's timed path known by its digest only: how many waypoints, and the SHA-256 of
/// their JSON (compact, as schedule_json writes them). Regression goldens keep these.
struct PathDigest {
  std::size_t waypoints = 0;
  std::string sha256;
  bool operator==(const PathDigest&) const = default;
};

/// A plan's key (SchedulePlan::key, the `plans` keys of the JSON), written in one place:
/// "g3n2" is geometry 3 planned for 2 nozzles; "g4~g3n2" geometry 4 following the order of
/// plan g3n2 (the layer below's), with "h" after it when a gantry is held back; "m1",
/// "m2", ... after either when relabelled for another layer's walls.
struct PlanKey {
  int geometry = 1;        ///< 1-based
  int nozzles = 1;         ///< the count it was planned for (unless it follows a plan)
  std::string follows;     ///< the key of the plan whose order it follows, if any
  bool held_back = false;  ///< following, with a gantry held back
  int relabelled = 0;      ///< 0, or the variant's number
  std::string to_string() const;
};

/// A planned layer geometry at one nozzle count, as it is deposited.
struct SchedulePlan {
  std::string key;  ///< "g3n2": geometry 3, 2 nozzles; "g3n2m1": relabelled for other walls
  int geometry = 0;
  int nozzles = 1;
  std::string method;
  double z_top_m = 0.0;       ///< the layer the waypoints are drawn at
  double layer_time_s = 0.0;  ///< from the common start to the last nozzle's finish
  double min_gap_m = 0.0;     ///< nearest approach of two gantries (several nozzles)
  /// One per nozzle, in rail order; time from the layer's start; `piece` numbers the
  /// pieces of `layer` (a wall cut at a section border keeps its layer piece number).
  std::vector<std::vector<planner::Waypoint>> waypoints;
  floors::Layer layer;  ///< the wall pieces the waypoints deposit
  /// One per nozzle when the paths are known by their digests only (read from a schedule
  /// written with path digests); then `waypoints` is empty.
  std::vector<PathDigest> digests;
};

/// How many points of a climb's youngest anchor's strength the schedule keeps (equal
/// steps in time from its casting to the climb): what the report's anchor chart draws.
inline constexpr int kAnchorCurvePoints = 25;

struct ClimbEvent {
  int from_stage = 0, to_stage = 0;
  double start_s = 0.0, end_s = 0.0;
  double wait_before_s = 0.0;
  std::vector<WaitReason> wait_reasons;
  struct AnchorLoad {
    std::string id;
    std::string unit;
    double age_s = 0.0;
    double strength_mpa = 0.0;
    double required_mpa = 0.0;
    double equivalent_age_s = 0.0;  ///< at 20 °C (age_s without site weather)
  };
  std::vector<AnchorLoad> anchors;  ///< the pins of the stage climbed to
  /// One anchor's strength from its casting to the climb's start as the scheduler reckoned
  /// it (in equivalent age with site weather): the youngest one's (the first, if equal).
  struct StrengthPoint {
    double t_s = 0.0;  ///< schedule time
    double strength_mpa = 0.0;
  };
  std::vector<StrengthPoint> youngest_anchor_strength;  ///< kAnchorCurvePoints, in time order
  climb::ClimbPlan plan;
};

/// A lintel set over an opening before the first layer above its head.
struct LintelTask {
  std::string opening;  ///< its id, or "wall W at X m" when the file names none
  std::int64_t wall = 0;
  /// Along the wall from its start, m: the opening, and what the lintel covers (with
  /// its bearings, clipped to the wall).
  double offset_m = 0.0, width_m = 0.0, from_m = 0.0, to_m = 0.0;
  /// The ends of what it covers, in the machine's frame (z: head_z_m), m.
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::Zero();
  double sill_m = 0.0, head_m = 0.0;  ///< above the floor's base
  double head_z_m = 0.0;              ///< the head's elevation
  floors::LintelSpec::Type type = floors::LintelSpec::Type::kFormwork;
  double height_m = 0.0;  ///< precast: the element's depth
  bool by_arm = false;
};

/// An anchor's pipe as a key: the anchor's id and the floor it is cast on (a stage's
/// anchors repeat their ids floor by floor).
struct PipeKey {
  std::string anchor;
  int floor = 0;
  auto operator<=>(const PipeKey&) const = default;
};
inline PipeKey pipe_key(const climb::Anchor& a) {
  return {a.id, a.floor};
}

struct Event {
  /// kJoint: a planned joint's treatment, by the crew, before the layer above it.
  /// kSlab: the fixed slab stage, or (with `slabs:`) a slab's formwork and reinforcement;
  /// kPour: a slab's pour; kLintel: a lintel set before the layer over its opening.
  enum class Kind { kPipe, kClimb, kSlab, kPurge, kJoint, kLintel, kPour };
  Kind kind = Kind::kPipe;
  double start_s = 0.0, end_s = 0.0;
  int floor = 0, layer = 0;  ///< pipes: cast after this layer; slab: over this floor
  int crew = 0;              ///< people on it (0: the machine alone)
  /// Crew tasks (pipes, lintels, slabs, pours): waited for working hours before it, s
  /// (a climb's wait is its ClimbEvent's).
  double wait_before_s = 0.0;
  std::string detail;
  std::optional<climb::Anchor> anchor;  ///< pipes
  std::optional<ClimbEvent> climb;      ///< climbs
  std::optional<LintelTask> lintel;     ///< lintels
  double concrete_m3 = 0.0;             ///< pours: the slab's concrete
  bool roof = false;                    ///< slab and pour: the roof over the top floor
};
std::string to_string(Event::Kind kind);

/// Why a building cannot be built within its constraints.
enum class InfeasibilityKind {
  kMaxInterval,  ///< "max-interval": no plan keeps a piece within the maximum interval
  kNoPlan,       ///< "no-plan": no nozzle count has a usable plan
  kStrength,     ///< "strength": the material never gets strong enough to carry the walls
  kClimb,        ///< "climb": a climb cannot be planned, or its anchors never get strong
  kCalendar,     ///< "calendar": a task longer than any working window, or none left
  kJoint,        ///< "joint": a planned joint older than its material allows when treated
};
std::string to_string(InfeasibilityKind kind);
std::optional<InfeasibilityKind> infeasibility_kind_named(const std::string& name);

struct Infeasibility {
  InfeasibilityKind kind = InfeasibilityKind::kMaxInterval;
  int floor = 0, layer = 0;
  std::string message;  ///< where, by how much
  double required_s = 0.0, achieved_s = 0.0;
  /// Computed fixes, each on its own: nozzles needed, deposition speed needed, maximum
  /// interval needed; unset when none of that kind would do.
  std::optional<int> nozzles_needed;
  std::optional<double> deposition_speed_needed_m_s;
  std::optional<double> max_interval_needed_s;
  std::string fix;  ///< the fixes in words
};

struct ScheduleTotals {
  double makespan_s = 0.0;
  double deposition_s = 0.0, airtime_s = 0.0;  ///< nozzle time
  double waits_s = 0.0, climbs_s = 0.0, slabs_s = 0.0, pipes_s = 0.0, purges_s = 0.0, moves_s = 0.0;
  double joints_s = 0.0;     ///< planned joints' treatments (crew time, not the machine's)
  double lintels_s = 0.0;    ///< lintels set (the machine waits for them)
  double crew_h = 0.0;       ///< person-hours: every event's crew times its duration
  double concrete_m3 = 0.0;  ///< the layers' concrete
  double machine_s = 0.0;    ///< the machine busy: layers, moves, pipes, purges, climbs
};

/// A delivery of concrete (a truck of the material's batch size, the last one the rest).
struct Delivery {
  double due_s = 0.0;  ///< when the concrete used reaches the batches before it
  double m3 = 0.0;
  int floor = 0, layer = 0;  ///< the layer being printed then
};

/// What was printed on one local day of a site calendar, and where printing stopped.
/// How a working day's printing ended: "planned-joint" (the next layer starts on one),
/// "floor-top" (the floor's walls are done; its slab follows), "finished" (the building's
/// walls are), "continues" (the next layer follows within its interval).
enum class DayEnd { kPlannedJoint, kFloorTop, kFinished, kContinues };
std::string to_string(DayEnd end);
std::optional<DayEnd> day_end_named(const std::string& name);
/// The names of the day ends, for messages: "planned-joint, floor-top, ...".
std::string day_end_names();
/// A day's end in words, from its last layer (`floor`, `layer`) and the next one (unused
/// when the building is finished): "at the top of floor 0 (floor 0 layer 20); floor 1
/// starts on its slab". With `stopped`, the days that stop printing say so first
/// ("stopped at the top of ..."), as WorkDay::detail does.
std::string day_end_text(DayEnd end, int floor, int layer, int next_floor, int next_layer,
                         bool stopped);

struct WorkDay {
  std::string date;  ///< local, "2027-03-01"
  int layers = 0;    ///< layers started that day
  int first_floor = 0, first_layer = 0, last_floor = 0, last_layer = 0;
  double printing_s = 0.0;           ///< those layers' time
  double concrete_m3 = 0.0;          ///< those layers' concrete
  int deliveries = 0;                ///< due that day
  double crew_h = 0.0;               ///< person-hours of the crew tasks that start that day
  DayEnd stop = DayEnd::kContinues;  ///< how the day's printing ended
  std::string detail;                ///< the same, in words (day_end_text)
};

struct Schedule {
  bool feasible = true;
  std::optional<Infeasibility> infeasibility;
  std::vector<ScheduledLayer> layers;  ///< bottom to top, as built
  std::map<std::string, SchedulePlan> plans;
  std::vector<Event> events;              ///< by start time
  std::vector<climb::ClimbStage> stages;  ///< climbing machine only
  ScheduleTotals totals;
  /// Per local day with printing, when the site has a calendar (else empty).
  std::vector<WorkDay> days;
  std::vector<Delivery> deliveries;  ///< by due time
  std::vector<std::string> warnings;
  /// Each floor's concrete against its model's, in the building's floor order, from the
  /// layers as this schedule sliced them (not in the JSON's schedule: its inputs carry it).
  std::vector<floors::FloorQuantities> quantities;
  /// Wall-clock seconds spent planning layers, planning climbs, and on the rest (not in
  /// the JSON, which stays byte-identical).
  double layer_planning_s = 0.0, climb_planning_s = 0.0, bookkeeping_s = 0.0;
  int plans_computed = 0;
};

/// The totals as `layers` and `events` add them up (the machine busy: layers, moves,
/// pipes, purges, climbs; waits include the climbs' waits).
ScheduleTotals totals_of(const std::vector<ScheduledLayer>& layers,
                         const std::vector<Event>& events);

/// The days of `layers` and `events` on `calendar`: what was printed each day and how it
/// stopped.
std::vector<WorkDay> work_days(const std::vector<ScheduledLayer>& layers,
                               const std::vector<Event>& events,
                               const std::vector<Delivery>& deliveries,
                               const site::SiteCalendar& calendar);

/// Schedules the whole building. Throws InputError for a project that cannot be
/// scheduled at all (a fixed gantry's building taller than its reach is caught by
/// schedule::open_project already); an infeasible building is an answer (feasible false).
Schedule build_schedule(const Setup& setup, const ScheduleOptions& options = {});

}  // namespace ccbuild::schedule
