#pragma once
// The schedule as JSON (docs/schedule.md, `schema_version` 2), both ways: the inputs
// (every file read with its SHA-256, the seed, the machine's limits, the material), the
// layers, the plans with every nozzle's timed path, the stages, the events, the totals and
// whether it is feasible. The same inputs and seed give the same bytes: no wall-clock
// times, numbers rounded. read_schedule() reads such a document back into the same model
// and re-validates it, so that writing it again gives the same bytes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/material.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::schedule {

/// 2: local intervals taken where beads meet mid-piece too (piece_ends_checked counts them).
inline constexpr int kScheduleSchemaVersion = 2;
/// The version of ccbuild, stated once: CMake's project(VERSION) (CCBUILD_VERSION).
inline constexpr const char* kCcbuildVersion = CCBUILD_VERSION;
/// The largest schedule file read back, bytes. Reading one takes about 6 times its size
/// in memory at the peak (docs/schedule.md); the ten-storey tower's is 2.1 MB.
inline constexpr std::uintmax_t kMaxScheduleBytes = 256ull * 1024 * 1024;

/// An input file as the schedule recorded it.
struct RecordedFile {
  std::string path;    ///< as the run named it (relative to where it ran)
  std::string sha256;  ///< 64 lowercase hex digits
};

/// The machine as the schedule recorded it: its name and the limits an independent check
/// (and the dry-run) needs. SI units.
struct RecordedMachine {
  std::string name;
  double deposition_speed_m_s = 0.0, travel_speed_m_s = 0.0;
  double x_speed_m_s = 0.0, y_speed_m_s = 0.0, z_speed_m_s = 0.0, rotation_speed_rad_s = 0.0;
  bool rotate_while_moving = true;
  double accel_delay_s = 0.0, lift_height_m = 0.0, lift_time_s = 0.0, lower_time_s = 0.0;
  std::optional<double> stopper_min_rad, stopper_max_rad;  ///< unset: no stopper
  double nozzle_idle_limit_s = 0.0, nozzle_width_m = 0.0;
  double x_min_m = 0.0, x_max_m = 0.0, y_min_m = 0.0, y_max_m = 0.0, z_min_m = 0.0, z_max_m = 0.0;
  std::string origin;  ///< where the profile came from, in words
  /// The profile's file as inputs.files records it (empty: none, as for the bundled
  /// default, or a schedule from before it was recorded): the dry-run's machines load it.
  std::string profile;
  int nozzles = 1;
  double gantry_width_m = 0.0;
  machine::RailAxis rail_axis = machine::RailAxis::kX;
  double purge_s = 0.0;
  std::optional<double> pump_capacity_m3_s;  ///< unset: no limit
  /// The profile's bead_width_m [narrowest, widest], m; unset: the nozzle's width only.
  std::optional<std::pair<double, double>> bead_width_range_m;
  bool climbing = false;
  /// Climbing machines only.
  double anchor_strength_mpa = 0.0, pipe_embed_s = 0.0;
  double climb_wind_limit_m_s = 0.0;  ///< written with site weather only
  /// The speed of the rail axis, m/s.
  double rail_speed_m_s() const {
    return machine::rail_coordinate(x_speed_m_s, y_speed_m_s, rail_axis);
  }
};

/// What a schedule records about the run that made it.
/// Where a floor's walls and openings came from in a BIM model: their IFC GlobalIds, by
/// wall id and opening id (only those that have one), so that a user finds them there.
struct FloorProvenance {
  int floor = 0;
  std::vector<std::pair<std::int64_t, std::string>> walls;
  std::vector<std::pair<std::string, std::string>> openings;
  /// The floor's walls' concrete against the volume their model states
  /// (floors::floor_quantities on this machine), m³; unset when no wall states one.
  struct Quantities {
    double model_volume_m3 = 0.0;      ///< what the model states, over the walls that state it
    double printed_modelled_m3 = 0.0;  ///< what those walls print
    double printed_m3 = 0.0;           ///< what every wall of the floor prints
    int walls_modelled = 0, walls_unmodelled = 0;
  };
  std::optional<Quantities> quantities;
};

struct RecordedInputs {
  std::string ccbuild_version = kCcbuildVersion;
  std::string building;  ///< the file, as the run named it
  std::string name;
  std::string units;  ///< "m" or "ft": the building's own unit
  double layer_height_m = 0.0, slab_stage_s = 0.0;
  floors::LintelSpec lintels;  ///< how lintels are made (formwork by default)
  /// Slabs poured and cured to a strength (`slabs:`); unset: the fixed slab stage.
  std::optional<floors::SlabSpec> slabs;
  /// Where the building stood on the machine: every coordinate in the schedule is in the
  /// machine's frame. Absent in schedules older than placement: as drawn.
  Placement placement;
  std::uint64_t seed = 1;
  Objective objective = Objective::kFewestNozzles;  ///< written when not the default
  std::vector<RecordedFile> files;
  RecordedMachine machine;
  floors::MaterialProfile material;
  std::string material_origin;
  /// The climbing units' names: anchors and climb phases name their unit by index here.
  std::vector<std::string> unit_names;
  /// Empty unless the building came from a model whose elements have GlobalIds.
  std::vector<FloorProvenance> provenance;
  /// The walls the print spec left out for the crew (floors::leave_out_thin_walls).
  std::vector<floors::LeftOutWall> left_out;
  /// The building's print spec, where it states one (`inputs.print`).
  std::optional<floors::PrintSpec> print;
  /// The site's calendar, when the schedule has one: times then have ISO 8601 timestamps
  /// beside their seconds, and the days are summed up (`days`).
  std::shared_ptr<const site::SiteCalendar> calendar;
  /// The weather, when the site has it: ages are then equivalent ages at 20 °C.
  std::shared_ptr<const site::SiteConditions> conditions;
};

/// A schedule with what it was made from, as its JSON holds it.
struct ScheduleDocument {
  RecordedInputs inputs;
  Schedule schedule;
};

/// The inputs of a run on `setup`; each floor's quantities from `schedule` when given (as
/// it sliced the floors; else sliced here). Throws InputError when an input file cannot be
/// read back for its checksum.
RecordedInputs recorded_inputs(const Setup& setup, const ScheduleOptions& options,
                               const Schedule* schedule = nullptr);

struct ScheduleJsonOptions {
  /// Each nozzle's timed path as its digest (PathDigest) instead of its waypoints: a
  /// schedule a fraction of the size, which `diff` compares exactly (regression goldens),
  /// but which report and dry-run, needing the paths, refuse.
  bool path_digests = false;
};

/// The schedule's JSON document.
nlohmann::ordered_json schedule_json(const RecordedInputs& inputs, const Schedule& schedule,
                                     const ScheduleJsonOptions& options = {});
/// The same, with the inputs of `setup`. Throws as recorded_inputs does.
nlohmann::ordered_json schedule_json(const Setup& setup, const ScheduleOptions& options,
                                     const Schedule& schedule);

/// What read_schedule does with an input file the schedule recorded that is no longer
/// what it was.
enum class RecordedInputCheck {
  kNote,                   ///< changed or missing: named in ReadSchedule::notes
  kRefuseChanged,          ///< changed: refused; missing: named in the notes
  kRefuseChangedOrMissing  ///< either refused (the dry-run, which runs the machine from them)
};

struct ReadScheduleOptions {
  RecordedInputCheck inputs = RecordedInputCheck::kRefuseChanged;
  /// Whether paths known by their digests only are read (diff); else refused.
  bool allow_path_digests = false;
};

struct ReadSchedule {
  ScheduleDocument document;
  /// Recorded inputs that changed or are missing, when allowed, in words.
  std::vector<std::string> notes;
};

/// Reads a schedule JSON file back into the model and re-validates it: its size (at most
/// kMaxScheduleBytes), nesting (limits::kMaxNestingDepth), every key and type with a
/// plausible range for every number, then the rules every schedule keeps (each layer's
/// plan and nozzle count, every wall piece deposited once, speeds within the machine's
/// limits, gantries a gantry width apart, one layer at a time and in building order, the
/// interval and the local intervals recomputed from the paths, waits as long as their
/// reasons, events between layers, totals), then the recorded input files by path and
/// SHA-256. Throws InputError naming the file, the line and the JSON pointer (e.g.
/// `/layers/12/start_s`) and what was expected or which rule is broken.
ReadSchedule read_schedule(const std::filesystem::path& path,
                           const ReadScheduleOptions& options = {});

/// Parses schedule JSON text (named `file` in messages) as read_schedule does, without
/// the size check and without looking at the recorded input files.
ScheduleDocument parse_schedule(const std::string& text, const std::string& file,
                                bool allow_path_digests = false);

}  // namespace ccbuild::schedule
