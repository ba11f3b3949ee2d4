#pragma once
// What a schedule is made for: the building, the machine that prints it (and climbs it,
// on a climbing machine), the material, and the files they came from. The building-level
// API (schedule/project.hpp) opens a user's FILE into one; the scheduler, the
// schedule's JSON and the reports read it. SI units.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/climb/fit.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/machine/climbing_machine.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/site/conditions.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::schedule {

/// How a building was placed on the machine: as drawn (no site), by its site's origin, or
/// centred (--place centre or `place: centre`).
enum class PlacedBy { kAsDrawn, kSite, kCentred };
/// "as drawn", "site", "centred": the schedule's `placement.how`.
std::string to_string(PlacedBy how);
std::optional<PlacedBy> placed_by_named(const std::string& name);

/// Where the building stands in the machine's frame, as resolved when it was opened (its
/// plans are placed already): plan point p is at R(rotation_rad) p + origin_m.
struct Placement {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double rotation_rad = 0.0;
  PlacedBy how = PlacedBy::kAsDrawn;
};

struct Setup {
  std::filesystem::path file;  ///< as the user named it
  floors::Building building;   ///< a lone plan is a one-floor building named after its file
  std::shared_ptr<const machine::MachineModel> machine;  ///< the printing gantry
  /// The climbing machine, when the profile has a `climbing:` section; null for a fixed
  /// gantry. Its gantry is `machine`.
  std::shared_ptr<const machine::ClimbingMachine> climber;
  std::string machine_origin;  ///< "config/machines/cc-gantry.yaml (the building's)", ...
  /// Set when the machine was a family, fitted to this building as it was opened (its
  /// URDF then is no file).
  std::shared_ptr<const climb::FitResult> fit;
  floors::MaterialProfile material;
  std::string material_origin;
  /// The mix of the layers the anchor pipes are cast in, when not `material` (a what-if
  /// of anchor_what_ifs; not recorded in the schedule JSON, so never set for a schedule
  /// that is written).
  std::optional<floors::MaterialProfile> anchor_material;
  Placement placement;
  /// The site's programme (calendar, crews), from `--site FILE` or the building's `site:`;
  /// null: work runs around the clock from "day 1 00:00".
  std::shared_ptr<const site::SiteCalendar> calendar;
  std::filesystem::path site_file;  ///< the `--site` file, when one was given
  /// The weather (the programme's constants or hourly file); null: 20 °C and calm, ages
  /// are real ages.
  std::shared_ptr<const site::SiteConditions> conditions;

  const machine::MachineModel& machine_model() const { return *machine; }
  /// The mix the anchors' pipes are cast in: `anchor_material`, else `material`.
  const floors::MaterialProfile& anchor_mix() const {
    return anchor_material ? *anchor_material : material;
  }
  /// Every file read: the FILE, its plans, the profiles, the URDF.
  std::vector<std::filesystem::path> files_read() const;
  /// A length in the building's own unit, for messages: "3.000 m", "9.843 ft".
  std::string length(double value_m, int decimals = 3) const;
  /// The climbing units' names, by index (empty on a fixed gantry).
  std::vector<std::string> unit_names() const;
};

}  // namespace ccbuild::schedule
