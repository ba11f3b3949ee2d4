#pragma once
// A design study (docs/studies.md): a study file names the building(s) and the axes to
// vary (machine or material profiles, any numeric key of a profile by its path, sites,
// objectives, seeds); its variants are every combination of the axes' values, or a
// seeded random sample of them. Each variant is one whole-building schedule.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ccbuild::study {

/// Limits on a study file (hostile input is normal input).
inline constexpr int kMaxAxes = 16;
inline constexpr int kMaxValuesPerAxis = 1000;
inline constexpr long long kMaxVariants = 100'000;

/// What an axis varies.
enum class AxisKind {
  kBuilding,     ///< `building`: building files
  kMachine,      ///< `machine`: machine profiles (a family is fitted to each building)
  kMaterial,     ///< `material`: material profiles
  kSite,         ///< `site`: site programmes (calendar, weather); `none` for none
  kObjective,    ///< `objective`: fewest-nozzles or shortest
  kSeed,         ///< `seed`: the planner's seed
  kMachineKey,   ///< `machine.<path>`: a number in the machine profile
  kMaterialKey,  ///< `material.<path>`: a number in the material profile
};

struct Axis {
  AxisKind kind = AxisKind::kBuilding;
  std::string name;  ///< as the study names it: "machine", "material.max_layer_interval_s"
  std::vector<std::string> values;  ///< as written (files relative to the study file)
};

/// One variant's settings: the base's, with each axis's value for this variant.
struct Variant {
  int index = 0;   ///< 0-based, in the study's order (the grid's, or the sample's sorted)
  std::string id;  ///< "v0001": index + 1, zero-padded to the study's size
  /// Per axis, in the study's order: (axis name, value as written).
  std::vector<std::pair<std::string, std::string>> settings;
  std::filesystem::path building, machine, material, site;  ///< absolute; site may be empty
  std::string objective = "fewest-nozzles";
  std::uint64_t seed = 1;
  double layer_time_limit_s = 60.0;  ///< the study's, as `schedule --layer-time-limit`
  /// Numbers set in the profiles, by path below the profile's root
  /// ("climbing.anchor_strength_mpa").
  std::vector<std::pair<std::string, double>> machine_keys, material_keys;
};

struct Study {
  std::string file;  ///< as given
  std::string name;
  int name_line = 0;  ///< the line of `name:` in the study file (for messages)
  std::vector<Axis> axes;
  std::vector<Variant> variants;
  /// Every combination of the axes' values (the product of their sizes; read_study refuses
  /// axes whose product passes 2^63 - 1).
  long long grid_size = 0;
  std::vector<std::string> measures;  ///< the result columns chosen (default: all)
  double variant_timeout_s = 1800.0;  ///< a variant running longer fails
  double layer_time_limit_s = 60.0;   ///< per layer plan, as `schedule --layer-time-limit`
};

/// Reads and checks a study file: every file it names exists, every profile key is a
/// number in its profile, the variants are within kMaxVariants. Throws InputError naming
/// the file, line and field.
Study read_study(const std::filesystem::path& file);

/// The measures a study can collect, in their column order.
const std::vector<std::string>& all_measures();

}  // namespace ccbuild::study
