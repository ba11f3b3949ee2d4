#pragma once
// What the planner and the scheduler know about a Contour Crafting machine. The
// kinematics (axis speeds, work envelope, the nozzle's rotation range, i.e. its stopper)
// come from the machine's URDF; the process parameters (deposition speed, delays, lift,
// idle limit) from the machine profile. All SI: m, s, rad.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ccbuild::machine {

/// The layout axis a machine's gantries ride along (its common rails): the one type every
/// library uses for it.
enum class RailAxis { kX, kY };
/// "x" or "y", as profiles, flags and the JSON say it.
std::string to_string(RailAxis axis);
/// The axis of that name ("x", "y"), if it is one.
std::optional<RailAxis> rail_axis_named(const std::string& name);
/// The coordinate of (x, y) along the rails, m.
inline double rail_coordinate(double x_m, double y_m, RailAxis axis) {
  return axis == RailAxis::kY ? y_m : x_m;
}

struct AxisLimits {
  double min_m = 0.0;
  double max_m = 0.0;
  double speed_m_s = 0.0;  ///< the joint's velocity limit
};

struct MachineModel {
  std::string name = "default";
  std::string source_file;  ///< profile the model was loaded from, empty for defaults
  /// Every file read to build the model (profile, URDF), so no output overwrites them.
  std::vector<std::filesystem::path> files_read;

  // --- Kinematics (URDF) ---
  AxisLimits x;  ///< the layout's x (along the rails by default)
  AxisLimits y;  ///< the layout's y (along the bridge by default)
  AxisLimits z;  ///< nozzle height
  double rotation_speed_rad_s = 1.5707963267948966;  ///< nozzle yaw velocity limit
  /// Cumulative nozzle heading must stay within [min, max]; ±2π is a ±360° stopper.
  double stopper_min_rad = -6.283185307179586;
  double stopper_max_rad = 6.283185307179586;

  // --- Process (profile) ---
  double deposition_speed_m_s = 0.1;   ///< nozzle speed along a wall while extruding
  double travel_speed_m_s = 0.5;       ///< straight-line (euclidean) air moves
  bool rotate_while_moving = true;     ///< then a move costs max(travel, rotation), else the sum
  double accel_delay_s = 0.5;          ///< acceleration + deceleration per air move
  double lift_height_m = 0.1;          ///< how far the nozzle rises over deposited walls
  double lift_time_s = 2.0;            ///< raising the nozzle over deposited walls
  double lower_time_s = 2.0;           ///< lowering it back
  double nozzle_idle_limit_s = 600.0;  ///< longest idle (air) move before concrete clogs
  double nozzle_width_m = 0.15;        ///< default wall thickness; a thick wall's skins
  /// `bead_width_m: [narrowest, widest]`: the widths one pass can lay, m, the nozzle's
  /// width among them. The nozzle moves at deposition_speed_m_s whatever the width, so a
  /// bead's flow is its width x the layer height x that speed (docs/formats.md, "Bead
  /// widths"). Unset: the nozzle's width only; read it with bead_widths().
  std::optional<std::pair<double, double>> bead_width_range_m;
  /// Gantries (one nozzle each) on the common rails; the scheduler uses 1 up to this.
  int nozzles = 1;
  double gantry_width_m = 1.5;        ///< two gantries' rail positions stay at least this apart
  RailAxis rail_axis = RailAxis::kX;  ///< the layout axis the rails run along
  /// Clearing the nozzle after an idle spell longer than nozzle_idle_limit_s.
  double purge_s = 120.0;
  /// `pump_capacity_m3_h`: the most concrete the pump delivers, m³/s; unset: no limit. A
  /// plan whose nozzles together draw more is not used (fewer nozzles print the layer).
  std::optional<double> pump_capacity_m3_s;

  /// The narrowest and widest bead, m: bead_width_range_m, else the nozzle's width twice.
  std::pair<double, double> bead_widths() const {
    return bead_width_range_m.value_or(std::make_pair(nozzle_width_m, nozzle_width_m));
  }

  /// The defaults above, with x/y axes 0..50 m at 0.5 m/s and z 0..10 m at 0.1 m/s.
  static MachineModel defaults();
};

/// Loads a machine profile (YAML or JSON) and the URDF it names (path relative to the
/// profile). Every number, in the profile and in the URDF's joint limits, must lie in
/// its plausible range (docs/formats.md). Throws InputError naming the profile or URDF
/// file, the line or field, and what was expected: missing joints, wrong joint types,
/// numbers out of range, a URDF urdfdom cannot parse or that is nested too deep.
MachineModel load_machine(const std::filesystem::path& profile_path);

}  // namespace ccbuild::machine
