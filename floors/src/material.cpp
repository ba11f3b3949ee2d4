#include "ccbuild/floors/material.hpp"

#include <algorithm>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::floors {

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

MaterialProfile load_material_profile(const std::filesystem::path& path) {
  const Document doc = load_document(path);
  const Field root = Field::root(doc);
  MapReader map(root, {"name", "description", "density_kg_m3", "min_layer_interval_s",
                       "max_layer_interval_s", "strength_curve"});
  map.reject_unknown();
  MaterialProfile m;
  m.source_file = path.string();
  m.name = map.required("name").as_string();
  const Field density = map.required("density_kg_m3");
  m.density_kg_m3 = density.as_number();
  if (m.density_kg_m3 <= 0.0) density.fail("density must be positive");
  const Field min_interval = map.required("min_layer_interval_s");
  const Field max_interval = map.required("max_layer_interval_s");
  m.min_layer_interval_s = min_interval.as_number();
  m.max_layer_interval_s = max_interval.as_number();
  if (m.min_layer_interval_s < 0.0) min_interval.fail("must be zero or more seconds");
  if (m.max_layer_interval_s <= m.min_layer_interval_s)
    max_interval.fail("must be greater than min_layer_interval_s (" +
                      std::to_string(m.min_layer_interval_s) + " s)");
  const Field curve = map.required("strength_curve");
  for (const Field& item : curve.items()) {
    MapReader point(item, {"age_min", "strength_mpa"});
    point.reject_unknown();
    const Field age = point.required("age_min");
    const Field strength = point.required("strength_mpa");
    StrengthPoint p{age.as_number() * 60.0, strength.as_number()};
    if (p.age_s < 0.0) age.fail("age must be zero or more");
    if (p.strength_mpa < 0.0) strength.fail("strength must be zero or more");
    if (!m.strength_curve.empty()) {
      if (p.age_s <= m.strength_curve.back().age_s) age.fail("ages must increase down the list");
      if (p.strength_mpa < m.strength_curve.back().strength_mpa)
        strength.fail("strength must not decrease with age");
    }
    m.strength_curve.push_back(p);
  }
  if (m.strength_curve.size() < 2) curve.fail("needs at least two points");
  return m;
}

}  // namespace ccbuild::floors
