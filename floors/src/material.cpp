#include "ccbuild/floors/material.hpp"

#include <algorithm>
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
}  // namespace

double MaterialProfile::strength_at_mpa(double age_s) const {
  if (strength_curve.empty()) return 0.0;
  if (age_s <= strength_curve.front().age_s) return strength_curve.front().strength_mpa;
  for (std::size_t i = 1; i < strength_curve.size(); ++i) {
    const auto& p = strength_curve[i - 1];
    const auto& q = strength_curve[i];
    if (age_s <= q.age_s) {
      const double t = (age_s - p.age_s) / (q.age_s - p.age_s);
      return p.strength_mpa + t * (q.strength_mpa - p.strength_mpa);
    }
  }
  return strength_curve.back().strength_mpa;
}

double MaterialProfile::age_for_strength_s(double strength_mpa) const {
  if (strength_curve.empty() || strength_curve.back().strength_mpa < strength_mpa)
    return std::numeric_limits<double>::infinity();
  if (strength_curve.front().strength_mpa >= strength_mpa) return 0.0;
  for (std::size_t i = 1; i < strength_curve.size(); ++i) {
    const auto& p = strength_curve[i - 1];
    const auto& q = strength_curve[i];
    if (q.strength_mpa >= strength_mpa) {
      // p is below the strength and q reaches it, so q is strictly above p here.
      const double t = (strength_mpa - p.strength_mpa) / (q.strength_mpa - p.strength_mpa);
      return p.age_s + t * (q.age_s - p.age_s);
    }
  }
  return std::numeric_limits<double>::infinity();
}

MaterialProfile load_material_profile(const std::filesystem::path& path) {
  const Document doc = load_document(path);
  const Field root = Field::root(doc);
  MapReader map(root, {"name", "description", "density_kg_m3", "min_layer_interval_s",
                       "max_layer_interval_s", "strength_curve", "safety_factor", "planned_joint"});
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
  return m;
}

}  // namespace ccbuild::floors
