#include "cli_common.hpp"

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::cli {

void add_plan_input_options(CLI::App& command, PlanInputOptions& options) {
  command
      .add_option("--units", options.units,
                  "Length unit of a plan file that does not say its own `units` (m or ft)")
      ->check(CLI::IsMember({"m", "ft"}))
      ->capture_default_str();
  command.add_option(
      "--floor-height", options.floor_height,
      "For a plan file: the floor height in --units (default 3 m); openings must fit under it");
  command
      .add_option("--layer-height", options.layer_height,
                  "For a plan file: the layer height in --units")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

LoadedInput load_input(const std::filesystem::path& file, const PlanInputOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string(), 0, "", "file not found");
  LoadedInput input;
  if (floors::looks_like_building(file)) {
    input.is_building = true;
    input.building = floors::load_building(file);
    return input;
  }
  const floors::LengthUnit unit = *floors::parse_length_unit(options.units);
  const double scale = floors::meters_per(unit);
  floors::Floor floor;
  floor.name = file.stem().string();
  floor.plan = floors::load_plan(file, unit);
  floor.height_m = options.floor_height ? *options.floor_height * scale : 3.0;
  if (floor.height_m <= 0.0) throw InputError("", 0, "--floor-height", "must be positive");
  if (options.floor_height) floors::validate_plan(floor.plan, floor.height_m);
  input.building.name = floor.name;
  input.building.source_file = file.string();
  input.building.units = unit;
  input.building.layer_height_m = options.layer_height * scale;
  input.building.floors.push_back(std::move(floor));
  return input;
}

}  // namespace ccbuild::cli
