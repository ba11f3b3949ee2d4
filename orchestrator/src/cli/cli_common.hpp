#pragma once
// Shared pieces of the ccbuild subcommands: exit codes, number formatting, and loading
// whatever FILE the user named (a building or a single plan).

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/plan.hpp"

namespace ccbuild::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNo = 1;  ///< the run worked; the answer is "no" (infeasible, collision)
inline constexpr int kExitBadInput = 2;  ///< bad input or usage

using ::ccbuild::printf_string;

/// Options every command that reads a single plan shares.
struct PlanInputOptions {
  std::string units = "m";             ///< for plan files without their own `units`
  std::optional<double> floor_height;  ///< in `units`
  double layer_height = 0.1;           ///< in `units`
};

/// Adds --units, --floor-height, --layer-height to a command that accepts plan files.
void add_plan_input_options(CLI::App& command, PlanInputOptions& options);

/// A building file, or a single plan turned into a one-floor building.
struct LoadedInput {
  bool is_building = false;
  floors::Building building;  ///< for a plan: one floor named after the file
};

/// Loads FILE as a building when it has `floors:`, else as a plan. A plan becomes a
/// building of one floor (height --floor-height, default 3 m) with no profiles.
/// Throws InputError.
LoadedInput load_input(const std::filesystem::path& file, const PlanInputOptions& options);

}  // namespace ccbuild::cli
