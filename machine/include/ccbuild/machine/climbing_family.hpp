#pragma once
// A family of climbing machines: one design of platform and climbing unit, built to the
// size of each building (as climbing formwork is configured per building). The family
// profile says what may vary (the platform's length and width, how many units, where on
// the beams they may be mounted) and everything else a machine profile says; a member of
// the family (a FittedPlatform) becomes a full machine profile and its URDF, which load
// like any other. climb/fit.hpp chooses the member for a building. SI units: m, rad, kg.

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ccbuild/common/document.hpp"

namespace ccbuild::machine {

struct ClimbingFamily {
  std::string name;
  std::string source_file;
  /// The profile as read: its gantry and `climbing:` keys are copied into each fitted one.
  std::shared_ptr<const Document> document;

  // --- The platform: four beams around the building, their centre lines this far outside
  // its outermost walls; length along x and width along y between the beams' outer faces.
  double length_min_m = 6.0, length_max_m = 48.0;
  double width_min_m = 5.0, width_max_m = 24.0;
  double beam_clearance_m = 1.2;
  double beam_section_m = 0.6;
  double beam_mass_kg_per_m = 54.0;     ///< the platform's beams
  double bridge_mass_kg_per_m = 190.0;  ///< the gantry's bridge, which spans the width

  // --- The climbing units, all alike.
  int units_min = 3, units_max = 16;
  double mount_step_m = 0.5;           ///< mount positions along a beam, this apart
  double mount_end_clearance_m = 0.6;  ///< from a beam's ends (the corner joints)
  double mount_spacing_m = 1.0;        ///< two units' mounts at least this apart
  double swing_limit_rad = 1.2;        ///< either side of pointing square to the beam
  double reach_min_m = 0.4, reach_max_m = 2.8;
  double stroke_min_m = 1.2, stroke_max_m = 5.6;
  double unit_mass_kg = 1420.0;  ///< base, turret, boom, wrist, leg and pin together

  // --- The printing gantry's nozzle, relative to the platform's underside.
  double nozzle_low_m = -3.4, nozzle_high_m = 0.0;
};

/// Where a unit hangs: under one of the four beams, its boom pointing square to the beam
/// towards the building at swing 0.
struct UnitMount {
  enum class Beam { kSouth, kNorth, kWest, kEast };  ///< y min, y max, x min, x max
  std::string name;                                  ///< "U1"
  Beam beam = Beam::kSouth;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< platform frame
  double boom_yaw_rad = 0.0;                             ///< the boom's direction at swing 0
};
/// "south" (y min), "north", "west" (x min), "east".
std::string to_string(UnitMount::Beam beam);

/// One member of a family: the beams' centre lines and the units' mounts.
struct FittedPlatform {
  double x_min_m = 0.0, x_max_m = 0.0;  ///< west and east beams
  double y_min_m = 0.0, y_max_m = 0.0;  ///< south and north beams
  /// The gantry's travel (the nozzle's x and y), within the beams.
  double gantry_x_min_m = 0.0, gantry_x_max_m = 0.0;
  double gantry_y_min_m = 0.0, gantry_y_max_m = 0.0;
  std::vector<UnitMount> units;
  double length_m() const;  ///< between the outer faces, along x
  double width_m() const;
  double mass_kg(const ClimbingFamily& family) const;  ///< the whole machine
};

/// A unit hung at `position_m` under `beam` (its boom's yaw follows from the beam).
UnitMount mount_on(UnitMount::Beam beam, Eigen::Vector2d position_m, std::string name);

/// True when the profile at `path` is a family (it has a `family:` section); reads nothing
/// else. Throws InputError when the file cannot be read or parsed.
bool is_climbing_family(const Document& profile);

/// Reads a family profile. Throws InputError naming the file, line and field: a range the
/// wrong way round, a number out of its plausible range, `urdf:` or `joints:` given (a
/// family has none: fitting writes them), a `climbing:` key that fitting writes.
ClimbingFamily read_climbing_family(std::shared_ptr<const Document> profile);

/// The member's URDF (the same link shapes and masses as config/machines/cc_climber.urdf,
/// sized to the platform), for urdfdom and check_urdf. `header` goes in an XML comment.
std::string climbing_family_urdf(const ClimbingFamily& family, const FittedPlatform& platform,
                                 const std::string& header);

/// The member's machine profile: the family's own keys, `urdf: urdf_file`, `joints:`,
/// `climbing:` with the platform and units, and `description`. Values copied from the
/// family keep their lines in it, so that a bad one is reported where the user wrote it.
Document fitted_profile_document(const ClimbingFamily& family, const FittedPlatform& platform,
                                 const std::string& urdf_file, const std::string& description);

}  // namespace ccbuild::machine
