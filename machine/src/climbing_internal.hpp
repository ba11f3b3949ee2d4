#pragma once
// Pieces of machine profiles shared by their readers (not public): the climbing section,
// and the keys of a gantry's process.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "ccbuild/common/document.hpp"
#include "ccbuild/machine/climbing_machine.hpp"

namespace ccbuild::machine::detail {

/// The keys of a gantry's process (speeds, lift, nozzle and bead widths, gantries, pump),
/// the same in a machine profile and a climbing family, followed by `more`.
std::vector<std::string> with_gantry_process_keys(std::vector<std::string> more);

/// Reads `climbing:` against the URDF; `gantry_joints` are the profile's x, y, z, nozzle.
std::shared_ptr<const ClimbingMachine> read_climbing(
    const Field& climbing, const UrdfInfo& urdf, const MachineModel& gantry,
    const std::array<std::string, 4>& gantry_joints);

}  // namespace ccbuild::machine::detail
