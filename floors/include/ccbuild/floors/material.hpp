#pragma once
// The concrete's material profile: what the scheduler needs to know about how fast a
// layer may follow the previous one and how strength grows with age. Files state units
// in their key names (`_s`, `_min`, `_mpa`, `_kg_m3`).

#include <filesystem>
#include <string>
#include <vector>

namespace ccbuild::floors {

struct StrengthPoint {
  double age_s = 0.0;
  double strength_mpa = 0.0;
};

/// A planned construction joint (EN 13670 §8.4: a joint surface cleaned, roughened and
/// wetted before new concrete goes on it): where printing stops for off-shift hours at a
/// layer's end, the next layer waits for the joint's treatment, which may begin once the
/// layer below is `min_age_s` old and no later than `max_age_s`. `planned_joint:` in the
/// file, `treatment_min`, `min_age_h`, `max_age_h`.
struct PlannedJoint {
  double treatment_s = 1800.0;
  double min_age_s = 0.0;
  double max_age_s = 7 * 86400.0;
  bool operator==(const PlannedJoint&) const = default;
};

struct MaterialProfile {
  std::string name;
  std::string source_file;
  double density_kg_m3 = 2200.0;
  /// Interval between starting layer k and layer k+1: under min the lower layer cannot
  /// carry the next (wait); over max the layers no longer bond (cold joint).
  double min_layer_interval_s = 0.0;
  double max_layer_interval_s = 0.0;
  /// Compressive strength against age, ages strictly increasing, strength non-decreasing.
  std::vector<StrengthPoint> strength_curve;
  /// A layer must be this many times stronger than the stress of the walls above it.
  double safety_factor = 1.5;
  PlannedJoint planned_joint;

  /// Strength at `age_s`, linear between points, flat outside them.
  double strength_at_mpa(double age_s) const;
  /// The youngest age at which the strength reaches `strength_mpa` (0 when it does from
  /// the start); +infinity when the curve never reaches it.
  double age_for_strength_s(double strength_mpa) const;
};

/// Loads and validates a material profile (YAML or JSON).
/// Throws InputError naming file, line and field.
MaterialProfile load_material_profile(const std::filesystem::path& path);

}  // namespace ccbuild::floors
