#pragma once
// The concrete's material profile: what the scheduler needs to know about how fast a
// layer may follow the previous one and how strength grows with age. Files state units
// in their key names (`_s`, `_min`, `_mpa`, `_kg_m3`).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ccbuild {
class Field;
}

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

/// Strength with age as EN 1992-1-1 §3.1.2 (3.1)-(3.2) gives it at 20 °C: fcm(t) =
/// βcc(t) fcm, βcc(t) = exp(s (1 - sqrt(28 / t))), t in days; s by the cement's class:
/// 0.20 (R: CEM 42.5 R, 52.5 N and R), 0.25 (N: CEM 32.5 R, 42.5 N), 0.38 (S: CEM 32.5 N).
struct En1992Strength {
  double fcm_mpa = 0.0;  ///< mean compressive strength at 28 days
  double s = 0.20;
  std::string cement_class = "R";
  /// The age from which it holds (`from_h`): before it, a printable mix's green strength
  /// is the curve's alone (the Eurocode's expression is meant for hardened concrete).
  double from_s = 0.0;
  double strength_at_mpa(double age_s) const;
  /// +infinity when it never reaches `strength_mpa` (ultimate_mpa is its limit).
  double age_for_strength_s(double strength_mpa) const;
  /// The strength it tends to and never reaches, fcm e^s, MPa.
  double ultimate_mpa() const;
};

/// How temperature speeds or slows hydration: the age function of the maturity method
/// (ASTM C1074): the rate at which equivalent age at 20 °C accrues per second at T.
///   Nurse-Saul: (T - T0) / (20 °C - T0), none below the datum temperature T0;
///   Arrhenius (Freiesleben Hansen and Pedersen): exp(-E/R (1/T - 1/293.15 K)).
struct MaturityFunction {
  enum class Kind { kArrhenius, kNurseSaul };
  Kind kind = Kind::kArrhenius;
  double activation_energy_j_mol = 40'000.0;  ///< E (Arrhenius)
  double datum_temperature_c = -10.0;         ///< T0 (Nurse-Saul)
  double rate(double temperature_c) const;
  std::string name() const { return kind == Kind::kArrhenius ? "arrhenius" : "nurse-saul"; }
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
  /// `strength_en1992:`: the Eurocode's estimate, which extends the curve past its last
  /// point (strength_at_mpa).
  std::optional<En1992Strength> en1992;
  /// `maturity:`: the age function used with site temperatures.
  MaturityFunction maturity;
  /// `placing_temperature_c: [min, max]`: the air temperature printing needs.
  double placing_min_c = 5.0, placing_max_c = 35.0;
  /// `delivery_batch_m3`: what one delivery brings (a truck mixer's 8 m³ by default).
  double delivery_batch_m3 = 8.0;

  /// Strength at `age_s` (equivalent age at 20 °C), MPa: the one strength rule.
  /// The curve (tested strengths) governs up to its last point, linear between points,
  /// flat before the first: EN 1992-1-1 §3.1.2 (3.1)-(3.2) is an estimate for where no
  /// test is at hand (§3.1.2(6) asks for tests where early strength matters), and it
  /// overrates a printable mix in its first days. From the last point's age on, where
  /// `en1992` is stated, the smaller of two estimates carries it further, never below the
  /// last test: the Eurocode's for the stated fcm, and the class's development beta_cc
  /// through the last test (f_last beta_cc(t) / beta_cc(t_last)). Without `en1992`, flat.
  double strength_at_mpa(double age_s) const;
  /// The curve's last point's age, s (0 when it has none): where the tests end.
  double last_tested_age_s() const;
  /// The class's development through the last test as an EN 1992 strength (its fcm
  /// f_last / beta_cc(t_last)); none without `en1992` or a test after age 0.
  std::optional<En1992Strength> from_last_test() const;
  /// The youngest age at which the strength reaches `strength_mpa` (0 when it does from
  /// the start); +infinity when it never does.
  double age_for_strength_s(double strength_mpa) const;
  /// The strength it reaches at the most, MPa.
  double final_strength_mpa() const;
  /// The strength (MPa) its concrete needs to carry `height_m` of its wall above it, with
  /// the safety factor: the buildability rule, stated once.
  double strength_to_carry_mpa(double height_m) const;
};

/// Reads an EN 1992-1-1 §3.1.2 strength from a map with `fcm_mpa`, `cement_class` (R, N,
/// S; R by default) and, where `keys` allow it, `from_h`. Throws InputError naming the
/// field.
En1992Strength read_en1992_strength(const Field& field, const std::vector<std::string>& keys);

/// Loads and validates a material profile (YAML or JSON).
/// Throws InputError naming file, line and field.
MaterialProfile load_material_profile(const std::filesystem::path& path);

}  // namespace ccbuild::floors
