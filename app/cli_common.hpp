#pragma once
// Shared pieces of the ccbuild subcommands: exit codes, flag validators that refuse what
// does not fit (overflowing integers, NaN, out-of-range numbers), the options every
// command that reads FILE shares, and opening it through the building-level API.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "ccbuild/common/format.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNo = 1;  ///< the run worked; the answer is "no" (infeasible, collision)
inline constexpr int kExitBadInput = 2;  ///< bad input or usage
inline constexpr int kExitInternal = 3;  ///< a bug in ccbuild

using ::ccbuild::printf_string;

/// A whole number from `min` to `max`, written in decimal (no overflow, no wrap-around).
CLI::Validator integer_in(std::int64_t min, std::int64_t max);
/// The same for unsigned 64-bit values (seeds).
CLI::Validator unsigned_integer();
/// A finite decimal number inside `range` (in `unit`).
CLI::Validator number_in(const Range& range, const std::string& unit);
/// A finite decimal number, its range checked where its unit is known.
CLI::Validator finite_number();
/// The name of a file (or folder) to write: not empty, so that `-o "$UNSET"` is refused
/// instead of silently writing nothing.
CLI::Validator output_path();

/// Options every command that reads FILE shares.
struct InputOptions {
  /// --units: the unit lengths are shown in, and of a plan file without its own `units`
  /// (unset: the file's; m for a plan file that does not say)
  std::optional<std::string> units;
  std::optional<double> floor_height;  ///< in `units`
  double layer_height = 0.1;           ///< in `units`
  std::string machine;                 ///< --machine: overrides the building's
  std::string material;                ///< --material: overrides the building's
  std::string place;                   ///< --place: "centre", or empty (the site's)
  std::optional<double> rotate;        ///< --rotate: degrees, instead of the site's
  std::string site;                    ///< --site: the site's programme file
};

/// Adds --units, --floor-height, --layer-height (for plan files) and --machine,
/// --material, --place to a command.
void add_input_options(CLI::App& command, InputOptions& options);

/// --units for a command that reads a schedule: lengths shown in m or ft instead of the
/// schedule's building unit.
void add_shown_units_option(CLI::App& command, std::optional<std::string>& units);

/// The unit lengths are shown in: --units if given, else `recorded` (a schedule's
/// `inputs.units`; m when it names none).
floors::LengthUnit shown_unit(const InputOptions& options, const std::string& recorded);

/// The building-level API's options from the flags.
schedule::ProjectOptions project_options(const InputOptions& options);
/// Opens FILE through the building-level API with these options. Throws InputError, and
/// schedule::NoFit when a machine family fits no member to the building.
schedule::Project open_input(const std::string& file, const InputOptions& options);

/// A length flag: "5ft", "1.5m", or a bare number in `unit`; positive and finite, at
/// most `max_m`. Throws InputError naming `flag`.
double length_flag(const std::string& text, const char* flag, floors::LengthUnit unit,
                   double max_m = 1000.0);

/// Reads back a schedule a command draws or exports (`ccbuild report`, `export`): refused
/// when its recorded inputs changed, unless `allow_changed_inputs` (then each change is
/// printed to stderr as "WHO: note: ..."). Throws InputError.
schedule::ReadSchedule read_schedule_for(const std::string& file, bool allow_changed_inputs,
                                         bool allow_path_digests, const std::string& who);

/// The flag a library error's field stands for ("PlanOptions::time_limit_s" ->
/// "--time-limit"); the field itself when no flag does.
std::string flag_for_field(const std::string& field);

}  // namespace ccbuild::cli
