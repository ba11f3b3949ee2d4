#pragma once
// The building-level API every command and the scheduler stand on: open the user's FILE
// (a building, or a lone floor plan made into a one-floor building), resolve its machine
// and material the same way every time, check that the machine can build it, list its
// distinct layers, and plan a layer with one nozzle or several.
//
// Resolution: the machine is --machine when given, else the building's, else the bundled
// config/machines/cc-gantry.yaml; the material is --material, else the building's, else
// the bundled config/materials/standard-mix.yaml. Every file read is recorded, so that
// no output is ever written over one.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/climbing_machine.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::orchestrator {

struct ProjectOptions {
  /// For a lone plan: the unit of lengths its file does not state, and its floor and
  /// layer heights in metres.
  floors::LengthUnit plan_unit = floors::LengthUnit::kMeter;
  double plan_floor_height_m = 3.0;
  double plan_layer_height_m = 0.1;
  /// Overrides of the building's profiles (empty: the building's, else the bundled ones).
  std::filesystem::path machine_profile;
  std::filesystem::path material_profile;
};

struct Project {
  std::filesystem::path file;  ///< as the user named it
  bool is_building = false;
  floors::Building building;  ///< a lone plan is a one-floor building named after its file
  std::shared_ptr<const machine::MachineModel> machine;  ///< the printing gantry
  /// The climbing machine, when the profile has a `climbing:` section; null for a fixed
  /// gantry. Its gantry is `machine`.
  std::shared_ptr<const machine::ClimbingMachine> climber;
  std::string machine_origin;  ///< "config/machines/cc-gantry.yaml (the building's)", ...
  floors::MaterialProfile material;
  std::string material_origin;

  const machine::MachineModel& machine_model() const { return *machine; }
  /// Every file read: the FILE, its plans, the profiles, the URDF.
  std::vector<std::filesystem::path> files_read() const;
  /// A length in the building's own unit, for messages: "3.000 m", "9.843 ft".
  std::string length(double value_m, int decimals = 3) const;
};

/// Opens FILE and everything it refers to, each file read and parsed once, and checks
/// that the machine can build it (check_fit). Throws InputError naming file, line and
/// field; for the lone-plan heights, field `floor_height` or `layer_height`.
Project open_project(const std::filesystem::path& file, const ProjectOptions& options = {});

/// The checks that the machine can build the building at all, in the building's unit:
/// its footprint within the x and y reach, its height (plus the nozzle's lift) within the
/// z reach (a climbing machine climbs instead), every wall no thicker than the nozzle
/// lays in one pass. Throws InputError.
void check_fit(const Project& project);

/// Where a layer is in the building.
struct LayerRef {
  int floor = 0;
  int layer = 0;
};

/// Throws InputError (field `floor`) when the project has no floor `floor`.
void check_floor(const Project& project, int floor);

/// One layer of a floor (InputError, field `floor` or `layer`, when there is none). For
/// a lone plan without a layer number, the plan with every wall whole (openings ignored).
floors::Layer layer_of(const Project& project, int floor, std::optional<int> layer);

/// A geometry that one or more layers share, planned once for all of them.
struct DistinctLayer {
  floors::GeometryKey key;
  floors::Layer layer;          ///< the lowest layer with this geometry
  std::vector<LayerRef> where;  ///< every layer with it, bottom to top
  int label = 0;                ///< 1-based, numbered by first appearance in the building
};

/// The distinct layer geometries of the building (optionally of one floor, or one layer
/// number of each floor), in order of first appearance. Layers without walls are left
/// out. Equal geometry is decided by GeometryKey equality, not by a hash.
std::vector<DistinctLayer> distinct_layers(const Project& project,
                                           std::optional<int> floor = std::nullopt,
                                           std::optional<int> layer = std::nullopt);

/// What to plan a layer with: one nozzle (planning), or several (multi, whose own
/// `nozzles` field is ignored in favour of `nozzles`).
struct LayerPlanRequest {
  int nozzles = 1;
  planner::PlanOptions planning;
  planner::MultiNozzleOptions multi;
};

struct LayerPlanResult {
  int nozzles = 1;
  std::optional<planner::LayerPlan> single;       ///< nozzles == 1
  std::optional<planner::MultiNozzlePlan> multi;  ///< nozzles >= 2
  planner::PlanStatus status;                     ///< solved, or why no plan
  double layer_time_s() const;
  /// The longest air move of any nozzle, s, and how many exceed the idle limit.
  double max_idle_s() const;
  int idle_limit_violations() const;
};

/// Plans `layer` with the project's machine. Throws InputError (fields of PlanOptions,
/// PathSpec or MultiNozzleOptions) for options that cannot work.
LayerPlanResult plan_layer(const Project& project, const floors::Layer& layer,
                           const LayerPlanRequest& request);

}  // namespace ccbuild::orchestrator
