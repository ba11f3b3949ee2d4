#pragma once
// The climbing section of a machine profile (not public).

#include <array>
#include <memory>
#include <string>

#include "ccbuild/common/document.hpp"
#include "ccbuild/machine/climbing_machine.hpp"

namespace ccbuild::machine::detail {

/// Reads `climbing:` against the URDF; `gantry_joints` are the profile's x, y, z, nozzle.
std::shared_ptr<const ClimbingMachine> read_climbing(
    const Field& climbing, const UrdfInfo& urdf, const MachineModel& gantry,
    const std::array<std::string, 4>& gantry_joints);

}  // namespace ccbuild::machine::detail
