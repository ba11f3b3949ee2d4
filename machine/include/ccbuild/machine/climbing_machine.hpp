#pragma once
// The climbing machine (paper 000 §7): a platform carrying the printing gantry and N >= 3
// climbing units, all in one URDF. Each unit is a chain swing (revolute about z), reach
// (a boom, prismatic along it), wrist (revolute about z, pointing the pin), stroke (the
// leg, prismatic downwards) and pin (prismatic, into a horizontal pipe cast through a
// wall). The profile says which joints are which and adds what a URDF cannot: pin times,
// the loaded stroke speed, anchor strength, stability margin. SI units: m, s, rad, kg.

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/common/document.hpp"
#include "ccbuild/machine/climbing_family.hpp"
#include "ccbuild/machine/kinematics.hpp"
#include "ccbuild/machine/machine_model.hpp"

namespace ccbuild::machine {

/// A unit's joint values in chain order: swing (rad), reach (m), wrist (rad), stroke (m),
/// pin (m).
using UnitPose = std::array<double, 5>;

struct ClimbingUnit {
  std::string name;
  std::array<int, 5> joints{};  ///< indices into the robot's joints, chain order
  int foot_link = -1;           ///< the stroke's child: the pin slides out of it
  int pin_link = -1;            ///< the pin (its frame at the pin's tip)
  /// Links that move with the unit (the swing's child and below), for collision checks.
  std::vector<int> links;
};

/// What a climbing machine may state as its anchors' strength (`anchor_strength_mpa`),
/// MPa: makers of climbing anchors load them in concrete from about 10 MPa; under 5 MPa
/// an embedded pipe would tear out, over 100 MPa no concrete gets there. A what-if never
/// proposes a strength outside it.
inline const Range kAnchorStrength_mpa = Range::closed(5.0, 100.0);

struct ClimbingMachine {
  std::string name;
  MachineModel gantry;  ///< the printing gantry; its joints are relative to the platform
  std::shared_ptr<const Kinematics> robot;
  std::array<int, 4> gantry_joints{};  ///< x, y, z, nozzle yaw (robot joint indices)
  std::vector<int> gantry_links;       ///< links that move with the gantry
  std::vector<ClimbingUnit> units;
  int units_per_transfer = 1;  ///< units that change anchors at once

  // --- Printing window: where a layer's top may be, below the platform's frame (m).
  double nozzle_reach_below_m = 3.0;
  double nozzle_reach_above_m = 0.0;

  // --- Climbing (profile).
  double stroke_end_margin_m = 0.015;         ///< a cylinder keeps this from its stroke ends
  double stroke_speed_loaded_m_s = 0.2 / 60;  ///< the legs under the machine's weight
  double lift_per_stroke_m = 0.5;             ///< the hydraulic cylinder's own stroke
  double stroke_reset_s = 60.0;               ///< between two strokes of a lift
  double pin_insert_s = 60.0;
  double pin_release_s = 45.0;
  double pin_gap_m = 0.05;          ///< between the foot's face and the wall, pin out
  double pin_past_centre_m = 0.02;  ///< an engaged pin's tip beyond the wall's centre line
  /// The concrete strength from which an anchor may be loaded, MPa, within
  /// kAnchorStrength_mpa.
  double anchor_strength_mpa = 10.0;
  double anchor_clearance_m = 0.3;  ///< default anchors keep this from wall ends, openings
  double pipe_embed_s = 120.0;
  double foundation_anchor_depth_m = 0.3;
  double stability_margin_m = 0.3;
  /// A climb starts only when the wind forecast stays at or under this for its whole
  /// duration (`climb_wind_limit_m_s`): climbing formwork is moved in calm weather only,
  /// and cranes design for 20 m/s in service (EN 13001-2); 15 m/s keeps a margin.
  double climb_wind_limit_m_s = 15.0;

  std::vector<std::filesystem::path> files_read;

  const ClimbingUnit& unit(int u) const { return units[u]; }
  /// The pin's extension from the foot's face to its tip at 0, along the pin (m).
  double foot_to_pin_m() const { return foot_to_pin_m_; }

  /// The unit's joint values that put its foot at `foot_m` (world) with the pin pointing
  /// along `pin_direction` (horizontal) and extended `pin_m`, the platform at `platform`
  /// (the robot's root) and `q` for every other joint. nullopt when the foot is not
  /// reachable by this chain at all; the values are not checked against the limits.
  std::optional<UnitPose> unit_ik(int u, const Eigen::Isometry3d& platform,
                                  const std::vector<double>& q, const Eigen::Vector3d& foot_m,
                                  const Eigen::Vector2d& pin_direction, double pin_m) const;
  /// The range a joint may use: its URDF limits, a unit's stroke within them by
  /// stroke_end_margin_m (m or rad).
  std::pair<double, double> usable_range(int joint) const;
  /// True when every joint of `pose` is within its usable range.
  bool unit_within_limits(int u, const UnitPose& pose) const;
  /// Writes `pose` into the joint vector `q`.
  void set_unit(int u, const UnitPose& pose, std::vector<double>& q) const;
  UnitPose get_unit(int u, const std::vector<double>& q) const;

  double foot_to_pin_m_ = 0.15;
};

/// The same machine with every unit's leg `extra_m` longer: its stroke's upper limit
/// raised (a what-if: pipes cast lower). m.
std::shared_ptr<const ClimbingMachine> with_longer_legs(const ClimbingMachine& machine,
                                                        double extra_m);

/// A machine profile: the gantry always; the climbing machine when the profile has a
/// `climbing:` section. Each file (profile, URDF) is read once. A family profile (with a
/// `family:` section) is not a machine yet: `family` is set, and `gantry` holds only its
/// name and file until climb::fit_climbing_machine chooses the member for a building.
struct MachineProfile {
  MachineModel gantry;
  std::shared_ptr<const ClimbingMachine> climbing;  ///< null for a fixed gantry
  std::shared_ptr<const ClimbingFamily> family;     ///< set for a family profile only
};

/// Loads a machine profile (YAML or JSON) and its URDF. Throws InputError naming the
/// profile or URDF, the line or field or element, and what was expected: a unit missing a
/// joint, a joint of the wrong type or axis, limits the wrong way round, a unit's link
/// without collision geometry, fewer than 3 units, numbers out of range.
MachineProfile load_machine_profile(const std::filesystem::path& profile_path);
/// The same for a profile already parsed (`profile_path` is where it is, or would be: its
/// URDF is looked for beside it), its URDF from `urdf_xml` when not null (then no URDF
/// file is read). A family profile is not accepted here.
MachineProfile load_machine_profile(const Document& profile,
                                    const std::filesystem::path& profile_path,
                                    const std::string* urdf_xml);

}  // namespace ccbuild::machine
