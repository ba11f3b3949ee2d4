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
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/climb/fit.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/climbing_machine.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/planner/plan_nozzles.hpp"
#include "ccbuild/schedule/climbs.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::schedule {

struct ProjectOptions {
  /// For a lone plan: the unit of lengths its file does not state, and its floor and
  /// layer heights in metres.
  floors::LengthUnit plan_unit = floors::LengthUnit::kMeter;
  double plan_floor_height_m = 3.0;
  double plan_layer_height_m = 0.1;
  /// --units given: lengths are shown in this unit (messages, the schedule's `units`, so
  /// its report) whatever unit the file was written in. Unset: the file's own.
  std::optional<floors::LengthUnit> shown_unit;
  /// Overrides of the building's profiles (empty: the building's, else the bundled ones).
  std::filesystem::path machine_profile;
  std::filesystem::path material_profile;
  /// --place centre: the building centred on the machine's x and y travel, whatever its
  /// `site:` says (its rotation is kept).
  bool place_centre = false;
  /// --rotate DEG: the building turned by this many degrees (counter-clockwise) on the
  /// machine, instead of its `site: rotation_deg`.
  std::optional<double> rotation_deg;
  /// Where a family's fitted profile is written (by `ccbuild fit`) or would be: its URDF
  /// is named after it. Empty: beside the family, "<family>-fitted.yaml" (not written).
  std::filesystem::path fitted_profile;
  /// --site FILE: the site's programme (start, calendar, crews), instead of the building's.
  std::filesystem::path site_file;
  /// Told now and then what fitting a family is doing (may be empty).
  std::function<void(const std::string&)> progress;
};

/// No member of a machine family climbs the building: an answer (exit code 1), not bad
/// input. `fit` says why, per stage, and the nearest change that would fit.
struct NoFit : std::runtime_error {
  climb::FitResult fit;
  explicit NoFit(climb::FitResult result);
};

/// A user's FILE opened: what a schedule is made for (schedule::Setup), and whether FILE
/// was a building or a lone plan.
struct Project : schedule::Setup {
  bool is_building = false;
  /// The unit the file was written in; `building.units` is the unit it is shown in.
  floors::LengthUnit file_unit = floors::LengthUnit::kMeter;
};

/// Opens FILE and everything it refers to, each file read and parsed once, and checks
/// that the machine can build it (check_fit). A machine family is fitted to the building
/// (climb::fit_climbing_machine; `fit` says how). Throws InputError naming file, line and
/// field; for the lone-plan heights, field `floor_height` or `layer_height`. Throws NoFit
/// when no member of a family climbs the building.
Project open_project(const std::filesystem::path& file, const ProjectOptions& options = {});

/// The checks that the machine can build the building at all, in the building's unit:
/// its footprint within the x and y reach, every plan vertex (as placed) within the x and
/// y travel, saying by how much and which way it falls outside, its height (plus the nozzle's lift)
/// within the z reach (a climbing machine climbs instead), every wall's thickness made up by
/// one bead or two skins of the machine's bead widths (floors::wall_beads, bead_spec).
/// Throws InputError.
void check_fit(const Project& project);

/// A turn of `building` (degrees, counter-clockwise, as `site: rotation_deg` says it; the
/// building now stands turned by `now_deg`) under which its footprint, walls included,
/// spans at most `reach_x_m` x `reach_y_m` (with 1 µm to spare): an edge of its outline's convex
/// hull along x or y, within (-90, 90] (a half turn changes no size), rounded to 0.01 degree and
/// checked at that value; the one leaving the most room, the smaller on a tie. None when no such
/// turn fits (or the outline has over 1,000 hull corners).
struct FittingTurn {
  double deg = 0.0;        ///< the turn, as `site: rotation_deg` says it
  Eigen::Vector2d size_m;  ///< the footprint's x and y extent so turned
};
std::optional<FittingTurn> turn_that_fits(const floors::Building& building, double now_deg,
                                          double reach_x_m, double reach_y_m);

/// How the machine lays a building's walls: its nozzle's width, its bead widths (the widest
/// no wider than its pump feeds at the building's layer height and the deposition speed,
/// nor narrower than the nozzle), the building's pattern between skins.
floors::BeadSpec bead_spec(const machine::MachineModel& machine, const floors::Building& building);

/// Where a layer is in the building.
struct LayerRef {
  int floor = 0;
  int layer = 0;
};

/// Throws InputError (field `floor`) when the project has no floor `floor`.
using schedule::check_floor;

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

using planner::LayerPlanRequest;
using planner::LayerPlanResult;

/// Plans `layer` with the project's machine. Throws InputError (fields of PlanOptions,
/// PathSpec or MultiNozzleOptions) for options that cannot work.
LayerPlanResult plan_layer(const Project& project, const floors::Layer& layer,
                           const LayerPlanRequest& request);

}  // namespace ccbuild::schedule
