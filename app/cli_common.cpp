#include "cli_common.hpp"

#include <charconv>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"

namespace ccbuild::cli {

CLI::Validator integer_in(std::int64_t min, std::int64_t max) {
  const std::string range = "from " + std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size())
          return "expected a whole number " + range + ", got '" + echoed(text) + "'";
        if (ec == std::errc::result_out_of_range || value < min || value > max)
          return "must be " + range + ", got " + text;
        return "";
      },
      "INTEGER " + range);
}

CLI::Validator unsigned_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || ec != std::errc() || end != text.data() + text.size())
          return "expected a whole number from 0 to 18446744073709551615, got '" + echoed(text) +
                 "'";
        return "";
      },
      "INTEGER from 0 to 2^64 - 1");
}

namespace {

// The number `text` says, when it is one whole finite decimal number.
std::optional<double> parse_finite(const std::string& text) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value))
    return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator number_in(const Range& range, const std::string& unit) {
  const std::string said = range.describe(unit);
  return CLI::Validator(
      [range, said, unit](std::string& text) -> std::string {
        const auto value = parse_finite(text);
        if (!value) return "expected a number " + said + ", got '" + echoed(text) + "'";
        return range.violation(*value, text, unit);
      },
      "NUMBER " + said);
}

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return parse_finite(text) ? "" : "expected a number, got '" + echoed(text) + "'";
      },
      "NUMBER");
}

CLI::Validator output_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "expected a file name, got an empty one" : "";
      },
      "PATH");
}

void add_input_options(CLI::App& command, InputOptions& options) {
  command
      .add_option("--units", options.units,
                  "Show lengths in m or ft (volumes in m³ or yd³), whatever unit the file is "
                  "written in (default: the file's own); also the unit of a plan file that does "
                  "not say its own `units` (default m)")
      ->check(CLI::IsMember({"m", "ft"}));
  command
      .add_option("--floor-height", options.floor_height,
                  "For a plan file: the floor height in --units (default 3 m; " +
                      floors::limits::kFloorHeight_m.describe("m") +
                      "); openings must fit under it")
      ->check(finite_number());
  command
      .add_option("--layer-height", options.layer_height,
                  "For a plan file: the layer height in --units (" +
                      floors::limits::kLayerHeight_m.describe("m") + ")")
      ->check(finite_number())
      ->capture_default_str();
  command.add_option(
      "--machine", options.machine,
      "Machine profile (default: the building's, or the bundled config/machines/cc-gantry.yaml)");
  command.add_option("--material", options.material,
                     "Material profile (default: the building's, or the bundled "
                     "config/materials/standard-mix.yaml)");
  command
      .add_option("--place", options.place,
                  "Where the building stands on the machine: `centre` puts its footprint in the "
                  "middle of the x and y travel (default: the building's `site:`, else its plan "
                  "coordinates are the machine's)")
      ->check(CLI::IsMember({"centre", "center"}));
  command
      .add_option("--rotate", options.rotate,
                  "Turn the building by this many degrees (counter-clockwise) on the machine, "
                  "instead of the building's `site: rotation_deg` (from -360 to 360); a building "
                  "too large for the travel as it stands is told the turn that fits, if any")
      ->check(CLI::Range(-360.0, 360.0))
      ->check(finite_number());
  command.add_option("--site", options.site,
                     "The site's programme (YAML): `start` (local date and time), `time_zone`, "
                     "`working_hours`, `holidays`, `printing: attended|unattended`, `pipes` "
                     "(default: the building's `site:`, else around the clock from day 1 00:00; "
                     "docs/formats.md, Site programme)");
}

schedule::Project open_input(const std::string& file, const InputOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file, 0, "", "file not found");
  return schedule::open_project(file, project_options(options));
}

void add_shown_units_option(CLI::App& command, std::optional<std::string>& units) {
  command
      .add_option("--units", units,
                  "Show lengths in m or ft (volumes in m³ or yd³) (default: the unit the "
                  "building's file is written in, as the schedule records it)")
      ->check(CLI::IsMember({"m", "ft"}));
}

floors::LengthUnit shown_unit(const InputOptions& options, const std::string& recorded) {
  return floors::parse_length_unit(options.units.value_or(recorded))
      .value_or(floors::LengthUnit::kMeter);
}

schedule::ProjectOptions project_options(const InputOptions& options) {
  schedule::ProjectOptions project;
  // CLI11 checked the unit's name.
  project.plan_unit = *floors::parse_length_unit(options.units.value_or("m"));
  if (options.units) project.shown_unit = project.plan_unit;
  const double scale = floors::meters_per(project.plan_unit);
  project.plan_floor_height_m = options.floor_height ? *options.floor_height * scale : 3.0;
  project.plan_layer_height_m = options.layer_height * scale;
  project.machine_profile = options.machine;
  project.material_profile = options.material;
  project.place_centre = !options.place.empty();
  project.rotation_deg = options.rotate;
  project.site_file = options.site;
  return project;
}

double length_flag(const std::string& text, const char* flag, floors::LengthUnit unit,
                   double max_m) {
  const auto value = floors::parse_length_m(text, unit);
  if (!value)
    throw InputError("", 0, flag,
                     "expected a length such as 1.5, 1.5m or 5ft, got '" + echoed(text) + "'");
  const std::string wrong =
      Range::above(0.0, max_m)
          .violation(*value, "'" + text + "'", floors::to_string(unit), floors::meters_per(unit));
  if (!wrong.empty()) throw InputError("", 0, flag, wrong);
  return *value;
}

std::string flag_for_field(const std::string& field) {
  static const std::map<std::string, std::string> flags = {
      {"PlanOptions::time_limit_s", "--time-limit"},
      {"PlanOptions::max_kicks", "--max-kicks"},
      {"PlanOptions::polish_kicks", "--polish-kicks"},
      {"PlanOptions::algorithm", "--algorithm"},
      {"PathSpec::first", "--first-wall"},
      {"MultiNozzleOptions::nozzles", "--nozzles"},
      {"MultiNozzleOptions::gantry_width_m", "--gantry-width"},
      {"MultiNozzleOptions::rail_axis", "--rail-axis"},
      {"MultiNozzleOptions::platform_width_m", "--platform-width"},
      {"floor_height", "--floor-height"},
      {"layer_height", "--layer-height"},
      {"floor", "--floor"},
      {"layer", "--layer"},
  };
  const auto it = flags.find(field);
  return it == flags.end() ? field : it->second;
}

schedule::ReadSchedule read_schedule_for(const std::string& file, bool allow_changed_inputs,
                                         bool allow_path_digests, const std::string& who) {
  schedule::ReadScheduleOptions read;
  read.inputs = allow_changed_inputs ? schedule::RecordedInputCheck::kNote
                                     : schedule::RecordedInputCheck::kRefuseChanged;
  read.allow_path_digests = allow_path_digests;
  schedule::ReadSchedule out = schedule::read_schedule(file, read);
  for (const auto& note : out.notes) std::cerr << who << ": note: " << note << "\n";
  return out;
}

}  // namespace ccbuild::cli
