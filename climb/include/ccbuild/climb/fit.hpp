#pragma once
// Fitting a climbing machine to a building: the member of a family (machine/
// climbing_family.hpp) that climbs it. The platform is as small as the building allows
// (its beams the family's clearance outside the outermost walls of every storey), then
// the units are as few as let every unit reach solid wall at every stage and keep the
// platform statically stable, by the stability margin, in every transfer; among as few,
// the mounts whose least stable moment is the most stable and whose every climb plans.
// SI units: m, kg.

#include <functional>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/machine/climbing_family.hpp"

namespace ccbuild::climb {

struct FitOptions {
  /// The URDF's file name, as the fitted profile names it (beside the profile).
  std::string urdf_file = "fitted.urdf";
  /// Where the fitted profile is (or would be) written: its URDF is looked for beside it.
  std::string profile_path = "fitted.yaml";
  /// Plan every climb of the chosen member (OMPL, as `climb` does) and take the next most
  /// stable member when one cannot be planned.
  bool plan_climbs = true;
  ClimbOptions climb;  ///< for those plans
  /// Called now and then with what the fit is doing.
  std::function<void(const std::string&)> progress;
};

struct FitResult {
  /// Feasible when a member climbs the building; else kTooLarge (the platform), kNoAnchor
  /// (no mount reaches a stage's wall) or kUnstable, with the reasons below.
  ClimbStatus status;
  std::vector<std::string> reasons;  ///< per stage, when there is no fit
  std::string nearest_change;        ///< what would make a fit possible
  machine::FittedPlatform platform;
  double mass_kg = 0.0;
  double least_margin_m = 0.0;  ///< the least stable transfer of every climb
  int stages = 0;
  int mounts_considered = 0;  ///< mount positions on the beams
  int mounts_reaching = 0;    ///< of those, reaching solid wall at every stage
  int members_tried = 0;      ///< unit sets whose stages and statics were checked
  std::string optimised;      ///< what was minimised, in words
  std::string summary;        ///< the member: platform, units and where, mass
  std::string profile_yaml;   ///< the fitted profile, as `ccbuild fit` writes it
  std::string urdf_xml;
  std::string urdf_file;  ///< the URDF's file name, as the profile names it (beside it)
  /// The fitted machine, loaded from the two texts above as `--machine` would load them.
  machine::MachineProfile profile;
};

/// Chooses the family member for `building` (placed in the machine's frame). Throws
/// InputError only for a family whose keys do not make a machine (reported at their line
/// in the family file); a building that no member climbs is an answer (status).
FitResult fit_climbing_machine(const floors::Building& building,
                               const machine::ClimbingFamily& family,
                               const FitOptions& options = {});

}  // namespace ccbuild::climb
