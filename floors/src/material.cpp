#include "ccbuild/floors/material.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::floors {
namespace {
// Plausible ranges (docs/formats.md): concretes and mortars weigh 1,500-2,600 kg/m3
// (lightweight mixes less), layers follow each other within minutes to hours, and no
// concrete is stronger than ~200 MPa.
const Range kDensity_kg_m3 = Range::closed(500.0, 5000.0);
const Range kInterval_s = Range::closed(0.0, 7 * 86'400.0);
const Range kAge_s = Range::closed(0.0, 365 * 86'400.0);
const Range kStrength_mpa = Range::closed(0.0, 200.0);
constexpr std::size_t kMaxStrengthPoints = 1000;
const Range kSafetyFactor = Range::closed(1.0, 10.0);
const Range kJointTreatment_s = Range::closed(0.0, 86'400.0);
const Range kJointAge_s = Range::closed(0.0, 90 * 86'400.0);
const Range kFcm_mpa = Range::closed(1.0, 200.0);
const Range kActivation_j_mol = Range::closed(10'000.0, 100'000.0);
const Range kDatum_c = Range::closed(-30.0, 10.0);
const Range kAirTemperature_c = Range::closed(-60.0, 60.0);
constexpr double kDays28_s = 28.0 * 86'400.0;  // EN 1992-1-1's reference age

// EN 1992-1-1 (3.2): the development of strength with age, beta_cc(t), t > 0.
double beta_cc(double s, double age_s) {
  return std::exp(s * (1.0 - std::sqrt(kDays28_s / age_s)));
}
}  // namespace

double En1992Strength::strength_at_mpa(double age_s) const {
  if (age_s <= 0.0 || age_s < from_s) return 0.0;
  return beta_cc(s, age_s) * fcm_mpa;
}

double En1992Strength::age_for_strength_s(double strength_mpa) const {
  if (strength_mpa <= 0.0) return 0.0;
  const double ratio = std::log(strength_mpa / fcm_mpa) / s;  // 1 - sqrt(28 / t)
  if (ratio >= 1.0) return std::numeric_limits<double>::infinity();
  return std::max(from_s, kDays28_s / ((1.0 - ratio) * (1.0 - ratio)));
}

double En1992Strength::ultimate_mpa() const {
  return fcm_mpa * std::exp(s);
}

double MaturityFunction::rate(double temperature_c) const {
  if (kind == Kind::kNurseSaul)
    return std::max(0.0, temperature_c - datum_temperature_c) / (20.0 - datum_temperature_c);
  constexpr double kGas_j_mol_k = 8.314462618, kReference_k = 293.15;
  return std::exp(-activation_energy_j_mol / kGas_j_mol_k *
                  (1.0 / (temperature_c + 273.15) - 1.0 / kReference_k));
}

double MaterialProfile::final_strength_mpa() const {
  const double curve = strength_curve.empty() ? 0.0 : strength_curve.back().strength_mpa;
  if (!en1992) return curve;
  double limit_mpa = en1992->ultimate_mpa();
  if (const auto through = from_last_test())
    limit_mpa = std::min(limit_mpa, through->ultimate_mpa());
  return std::max(curve, limit_mpa);
}

namespace {

// The table: linear between points, flat outside them.
double curve_strength_at(const std::vector<StrengthPoint>& curve, double age_s) {
  if (curve.empty()) return 0.0;
  if (age_s <= curve.front().age_s) return curve.front().strength_mpa;
  for (std::size_t i = 1; i < curve.size(); ++i) {
    const auto& p = curve[i - 1];
    const auto& q = curve[i];
    if (age_s <= q.age_s) {
      const double t = (age_s - p.age_s) / (q.age_s - p.age_s);
      return p.strength_mpa + t * (q.strength_mpa - p.strength_mpa);
    }
  }
  return curve.back().strength_mpa;
}

double curve_age_for(const std::vector<StrengthPoint>& curve, double strength_mpa) {
  if (curve.empty() || curve.back().strength_mpa < strength_mpa)
    return std::numeric_limits<double>::infinity();
  if (curve.front().strength_mpa >= strength_mpa) return 0.0;
  for (std::size_t i = 1; i < curve.size(); ++i) {
    const auto& p = curve[i - 1];
    const auto& q = curve[i];
    if (q.strength_mpa >= strength_mpa) {
      // p is below the strength and q reaches it, so q is strictly above p here.
      const double t = (strength_mpa - p.strength_mpa) / (q.strength_mpa - p.strength_mpa);
      return p.age_s + t * (q.age_s - p.age_s);
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double MaterialProfile::last_tested_age_s() const {
  return strength_curve.empty() ? 0.0 : strength_curve.back().age_s;
}

std::optional<En1992Strength> MaterialProfile::from_last_test() const {
  const double last_s = last_tested_age_s();
  if (!en1992 || last_s <= 0.0) return std::nullopt;
  // fcm' beta_cc(t_last) = f_last: the class's development through the last test.
  En1992Strength through = *en1992;
  through.from_s = 0.0;
  through.fcm_mpa = strength_curve.back().strength_mpa / beta_cc(en1992->s, last_s);
  return through;
}

double MaterialProfile::strength_at_mpa(double age_s) const {
  // Tested strengths govern up to the last test; from its age on, the smaller of the two
  // estimates, never below the last test.
  const double table = curve_strength_at(strength_curve, age_s);
  if (!en1992 || age_s < last_tested_age_s()) return table;
  double estimate_mpa = en1992->strength_at_mpa(age_s);
  if (const auto through = from_last_test())
    estimate_mpa = std::min(estimate_mpa, through->strength_at_mpa(age_s));
  return std::max(table, estimate_mpa);
}

double MaterialProfile::strength_to_carry_mpa(double height_m) const {
  constexpr double kGravity_m_s2 = 9.80665;
  const double stress_per_m_mpa = density_kg_m3 * kGravity_m_s2 * 1e-6;
  return safety_factor * stress_per_m_mpa * height_m;
}

double MaterialProfile::age_for_strength_s(double strength_mpa) const {
  // The tests first; the estimates only from the last test's age on, where both reach it
  // (strength_at_mpa).
  const double table_s = curve_age_for(strength_curve, strength_mpa);
  if (!en1992 || std::isfinite(table_s)) return table_s;
  double age_s = en1992->age_for_strength_s(strength_mpa);
  if (const auto through = from_last_test())
    age_s = std::max(age_s, through->age_for_strength_s(strength_mpa));
  return std::max(last_tested_age_s(), age_s);
}

En1992Strength read_en1992_strength(const Field& field, const std::vector<std::string>& keys) {
  MapReader e(field, keys);
  e.reject_unknown();
  En1992Strength en;
  en.fcm_mpa = e.required("fcm_mpa").as_number_in(kFcm_mpa, "MPa");
  if (auto c = e.optional("cement_class")) {
    en.cement_class = c->as_string();
    if (en.cement_class == "R")
      en.s = 0.20;
    else if (en.cement_class == "N")
      en.s = 0.25;
    else if (en.cement_class == "S")
      en.s = 0.38;
    else
      c->fail("expected R, N or S (EN 1992-1-1 §3.1.2: s = 0.20, 0.25, 0.38), got '" +
              echoed(en.cement_class) + "'");
  }
  if (e.has("from_h")) en.from_s = e.required("from_h").as_number_in(kJointAge_s, "h", 3600.0);
  return en;
}

MaterialProfile load_material_profile(const std::filesystem::path& path) {
  const Document doc = load_document(path);
  const Field root = Field::root(doc);
  MapReader map(
      root, {"name", "description", "density_kg_m3", "min_layer_interval_s", "max_layer_interval_s",
             "strength_curve", "safety_factor", "planned_joint", "strength_en1992", "maturity",
             "placing_temperature_c", "delivery_batch_m3"});
  map.reject_unknown();
  MaterialProfile m;
  m.source_file = path.string();
  m.name = map.required("name").as_string();
  m.density_kg_m3 = map.required("density_kg_m3").as_number_in(kDensity_kg_m3, "kg/m3");
  const Field max_interval = map.required("max_layer_interval_s");
  m.min_layer_interval_s = map.required("min_layer_interval_s").as_number_in(kInterval_s, "s");
  m.max_layer_interval_s = max_interval.as_number_in(kInterval_s, "s");
  if (m.max_layer_interval_s <= m.min_layer_interval_s)
    max_interval.fail("must be greater than min_layer_interval_s (" +
                      plain_number(m.min_layer_interval_s) + " s)");
  const Field curve = map.required("strength_curve");
  const auto items = curve.items();
  if (items.size() > kMaxStrengthPoints)
    curve.fail("holds " + std::to_string(items.size()) + " points; at most " +
               std::to_string(kMaxStrengthPoints) + " are accepted");
  for (const Field& item : items) {
    MapReader point(item, {"age_min", "strength_mpa"});
    point.reject_unknown();
    const Field age = point.required("age_min");
    const Field strength = point.required("strength_mpa");
    StrengthPoint p{age.as_number_in(kAge_s, "min", 60.0),
                    strength.as_number_in(kStrength_mpa, "MPa")};
    if (!m.strength_curve.empty()) {
      if (p.age_s <= m.strength_curve.back().age_s) age.fail("ages must increase down the list");
      if (p.strength_mpa < m.strength_curve.back().strength_mpa)
        strength.fail("strength must not decrease with age");
    }
    m.strength_curve.push_back(p);
  }
  if (m.strength_curve.size() < 2) curve.fail("needs at least two points");
  if (auto factor = map.optional("safety_factor"))
    m.safety_factor = factor->as_number_in(kSafetyFactor, "");
  if (auto joint = map.optional("planned_joint")) {
    MapReader j(*joint, {"treatment_min", "min_age_h", "max_age_h"});
    j.reject_unknown();
    PlannedJoint& p = m.planned_joint;
    if (auto t = j.optional("treatment_min"))
      p.treatment_s = t->as_number_in(kJointTreatment_s, "min", 60.0);
    if (auto a = j.optional("min_age_h")) p.min_age_s = a->as_number_in(kJointAge_s, "h", 3600.0);
    if (auto a = j.optional("max_age_h")) {
      p.max_age_s = a->as_number_in(kJointAge_s, "h", 3600.0);
      if (p.max_age_s <= p.min_age_s)
        a->fail("must be greater than min_age_h (" + plain_number(p.min_age_s / 3600.0) + " h)");
    }
  }
  if (auto eurocode = map.optional("strength_en1992"))
    m.en1992 = read_en1992_strength(*eurocode, {"fcm_mpa", "cement_class", "from_h"});
  if (auto maturity = map.optional("maturity")) {
    MapReader r(*maturity, {"function", "activation_energy_kj_mol", "datum_temperature_c"});
    r.reject_unknown();
    const Field function = r.required("function");
    const std::string name = function.as_string();
    if (name == "arrhenius") {
      m.maturity.kind = MaturityFunction::Kind::kArrhenius;
      if (r.has("datum_temperature_c"))
        r.required("datum_temperature_c").fail("the Arrhenius function has no datum temperature");
      if (auto e = r.optional("activation_energy_kj_mol"))
        m.maturity.activation_energy_j_mol = e->as_number_in(kActivation_j_mol, "kJ/mol", 1000.0);
    } else if (name == "nurse-saul") {
      m.maturity.kind = MaturityFunction::Kind::kNurseSaul;
      if (r.has("activation_energy_kj_mol"))
        r.required("activation_energy_kj_mol")
            .fail("the Nurse-Saul function has no activation energy");
      if (auto t = r.optional("datum_temperature_c"))
        m.maturity.datum_temperature_c = t->as_number_in(kDatum_c, "°C");
    } else {
      function.fail(
          "expected arrhenius or nurse-saul (the maturity method's age functions, ASTM "
          "C1074), got '" +
          echoed(name) + "'");
    }
  }
  if (auto batch = map.optional("delivery_batch_m3"))
    m.delivery_batch_m3 = batch->as_number_in(Range::above(0.0, 100.0), "m3");
  if (auto placing = map.optional("placing_temperature_c")) {
    const auto range = placing->items();
    if (range.size() != 2)
      placing->fail("expected [min, max], the air temperatures printing needs");
    m.placing_min_c = range[0].as_number_in(kAirTemperature_c, "°C");
    m.placing_max_c = range[1].as_number_in(kAirTemperature_c, "°C");
    if (m.placing_max_c <= m.placing_min_c) range[1].fail("must be above the minimum");
  }
  return m;
}

}  // namespace ccbuild::floors
