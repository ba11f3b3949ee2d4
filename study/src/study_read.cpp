// Reading a study file and listing its variants (docs/studies.md).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/study.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

/// The number a value checked as one (Field::as_number, or a range made here) was written
/// as; std::stod would throw on a subnormal such as 1e-320.
double number_of(const std::string& text) {
  double value = 0.0;
  const char* begin = text.data() + (!text.empty() && text.front() == '+');
  const auto [ptr, ec] = std::from_chars(begin, text.data() + text.size(), value);
  CCBUILD_CHECK(ec == std::errc() && ptr == text.data() + text.size(),
                "a study value read twice differently: " + text);
  return value;
}

// In the order measures_of() gives them; one wait measure per reason kind.
const std::vector<std::string> kMeasures = [] {
  std::vector<std::string> out = {"makespan_s", "feasible", "nozzles_max", "waits_s"};
  for (const schedule::WaitKind kind : schedule::wait_kinds()) out.push_back(wait_measure(kind));
  for (const char* m :
       {"concrete_m3", "crew_h", "climbs", "machine_s", "idle_margin_s", "warnings"})
    out.push_back(m);
  return out;
}();

/// A file the study names, relative to the study file's folder; it must exist.
fs::path study_path(const Field& field, const fs::path& folder) {
  const std::string text = field.as_string();
  if (text.empty()) field.fail("expected a file name, got an empty one");
  fs::path path = fs::path(text).is_absolute() ? fs::path(text) : folder / text;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    field.fail("no such file: " + path.lexically_normal().string() +
               " (files are relative to the study file's folder)");
  return fs::absolute(path, ec).lexically_normal();
}

/// The node at `path` ("climbing.anchor_strength_mpa") of a profile, if it is there.
const DocNode* node_at(const DocNode& root, const std::string& path) {
  const DocNode* node = &root;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t dot = std::min(path.find('.', begin), path.size());
    const std::string key = path.substr(begin, dot - begin);
    if (node->kind != DocNode::Kind::kMap) return nullptr;
    const auto it = std::find_if(node->entries.begin(), node->entries.end(),
                                 [&](const auto& e) { return e.first == key; });
    if (it == node->entries.end()) return nullptr;
    node = &it->second;
    begin = dot + 1;
  }
  return node;
}

/// An axis's values: a list, or {from, to, step} for numbers.
std::vector<std::string> axis_values(const Field& field, bool numeric) {
  std::vector<std::string> values;
  if (field.is_sequence()) {
    for (const Field& item : field.items()) {
      if (!item.is_scalar()) item.fail("expected a value, got a map or a list");
      if (numeric) item.as_number();  // throws, located, for text
      values.push_back(item.as_string());
    }
  } else if (field.is_map()) {
    if (!numeric) field.fail("a range {from, to, step} is for numeric keys; list the values");
    MapReader r(field, {"from", "to", "step"});
    r.reject_unknown();
    const double from = r.required("from").as_number(), to = r.required("to").as_number();
    const Field step_field = r.required("step");
    const double step = step_field.as_number();
    if (!(step > 0.0)) step_field.fail("expected a step above 0");
    if (to < from) r.required("to").fail("expected `to` at least `from`");
    // Counted in doubles, checked before any cast: bounds far apart for their step (or
    // wider than the largest double) make a count no integer holds.
    const double count = std::floor((to - from) / step + 1e-9) + 1.0;
    if (!std::isfinite(count) || count > kMaxValuesPerAxis)
      field.fail(std::string("the range has ") +
                 (std::isfinite(count) && count < 1e15 ? printf_string("%.0f", count)
                                                       : std::string("too many to count")) +
                 " values; at most " + std::to_string(kMaxValuesPerAxis) + " per axis");
    for (int k = 0; k < static_cast<int>(count); ++k) {
      const double value = from + k * step;
      if (!std::isfinite(value)) field.fail("the range's values pass the largest number");
      values.push_back(printf_string("%.10g", value));
      if (k > 0 && values[k] == values[k - 1])
        field.fail("the range's values " + values[k - 1] + " and " + values[k] +
                   " are the same at 10 significant digits: its step is too small for its "
                   "bounds");
    }
  } else {
    field.fail("expected a list of values (or {from, to, step} for a number)");
  }
  if (values.empty()) field.fail("expected at least one value");
  if (static_cast<int>(values.size()) > kMaxValuesPerAxis)
    field.fail("expected at most " + std::to_string(kMaxValuesPerAxis) + " values, got " +
               std::to_string(values.size()));
  std::set<std::string> seen;
  for (const auto& v : values)
    if (!seen.insert(v).second) field.fail("the value '" + v + "' is listed twice");
  return values;
}

AxisKind kind_of(const Field& field, const std::string& name) {
  if (name == "building") return AxisKind::kBuilding;
  if (name == "machine") return AxisKind::kMachine;
  if (name == "material") return AxisKind::kMaterial;
  if (name == "site") return AxisKind::kSite;
  if (name == "objective") return AxisKind::kObjective;
  if (name == "seed") return AxisKind::kSeed;
  if (name.rfind("machine.", 0) == 0 && name.size() > 8) return AxisKind::kMachineKey;
  if (name.rfind("material.", 0) == 0 && name.size() > 9) return AxisKind::kMaterialKey;
  field.fail("unknown axis '" + name +
             "'; expected building, machine, material, site, objective, seed, or "
             "machine.<key> / material.<key> for a number in a profile");
}

std::string objective_of(const Field& field) {
  const std::string text = field.as_string();
  if (text != "fewest-nozzles" && text != "shortest")
    field.fail("expected fewest-nozzles or shortest, got '" + echoed(text) + "'");
  return text;
}

std::uint64_t seed_of(const Field& field) {
  const double value = field.as_number();
  if (value < 0 || value > 4294967295.0 || value != std::floor(value))
    field.fail("expected a whole number from 0 to 4294967295");
  return static_cast<std::uint64_t>(value);
}

}  // namespace

const std::vector<std::string>& all_measures() {
  return kMeasures;
}

Study read_study(const fs::path& file) {
  const Document doc = load_document(file);
  const Field root = Field::root(doc);
  if (!root.is_map()) root.fail("expected a study: name, base, axes (docs/studies.md)");
  MapReader top(root, {"name", "base", "axes", "sample", "measures", "variant_timeout_s",
                       "layer_time_limit_s"});
  top.reject_unknown();
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  Study study;
  study.file = file.string();
  const Field name_field = top.required("name");
  study.name = name_field.as_string();
  study.name_line = name_field.line();
  if (const auto t = top.optional("variant_timeout_s"))
    study.variant_timeout_s = t->as_number_in(Range::above(0.0, 7.0 * 86400.0), "s");
  if (const auto t = top.optional("layer_time_limit_s"))
    study.layer_time_limit_s = t->as_number_in(Range::above(0.0, 3600.0), "s");

  // The base every variant starts from.
  Variant base;
  base.layer_time_limit_s = study.layer_time_limit_s;
  const Field base_field = top.required("base");
  MapReader b(base_field, {"building", "machine", "material", "site", "objective", "seed"});
  b.reject_unknown();
  if (const auto f = b.optional("building")) base.building = study_path(*f, folder);
  if (const auto f = b.optional("machine")) base.machine = study_path(*f, folder);
  if (const auto f = b.optional("material")) base.material = study_path(*f, folder);
  if (const auto f = b.optional("site")) base.site = study_path(*f, folder);
  if (const auto f = b.optional("objective")) base.objective = objective_of(*f);
  if (const auto f = b.optional("seed")) base.seed = seed_of(*f);

  // The axes, in the file's order; each value checked where it is written.
  const Field axes_field = top.required("axes");
  if (!axes_field.is_map() || axes_field.node().entries.empty())
    axes_field.fail(
        "expected a map of axes: `machine.nozzles: [1, 2, 3]`, `material: [a.yaml, b.yaml]`");
  if (static_cast<int>(axes_field.node().entries.size()) > kMaxAxes)
    axes_field.fail("expected at most " + std::to_string(kMaxAxes) + " axes");
  std::vector<std::vector<Field>> value_fields;
  bool machine_axis = false, material_axis = false, building_axis = false;
  for (const auto& [name, node] : axes_field.node().entries) {
    const Field field = axes_field.child(node, join_path(axes_field.path(), name));
    Axis axis;
    axis.name = name;
    axis.kind = kind_of(field, name);
    const bool numeric = axis.kind == AxisKind::kMachineKey ||
                         axis.kind == AxisKind::kMaterialKey || axis.kind == AxisKind::kSeed;
    axis.values = axis_values(field, numeric);
    machine_axis |= axis.kind == AxisKind::kMachine;
    material_axis |= axis.kind == AxisKind::kMaterial;
    building_axis |= axis.kind == AxisKind::kBuilding;
    value_fields.push_back(field.is_sequence() ? field.items() : std::vector<Field>{});
    study.axes.push_back(std::move(axis));
  }
  if (!building_axis && base.building.empty())
    base_field.fail(
        "expected `building:` (or a `building` axis): the building every variant schedules");

  // Profile keys: a number at that path in every profile the variants use.
  for (std::size_t a = 0; a < study.axes.size(); ++a) {
    const Axis& axis = study.axes[a];
    if (axis.kind != AxisKind::kMachineKey && axis.kind != AxisKind::kMaterialKey) continue;
    const bool machine = axis.kind == AxisKind::kMachineKey;
    const std::string key = axis.name.substr(machine ? 8 : 9);
    std::vector<fs::path> profiles;
    if (machine ? machine_axis : material_axis) {
      for (const Axis& other : study.axes)
        if (other.kind == (machine ? AxisKind::kMachine : AxisKind::kMaterial))
          for (std::size_t v = 0; v < other.values.size(); ++v)
            profiles.push_back(folder / other.values[v]);
    } else if (!(machine ? base.machine : base.material).empty()) {
      profiles.push_back(machine ? base.machine : base.material);
    } else {
      base_field.fail(std::string("expected `") + (machine ? "machine" : "material") +
                      ":` in the base: the profile whose `" + key + "` the axis " + axis.name +
                      " sets");
    }
    for (const fs::path& profile : profiles) {
      const Document p = load_document(profile);
      const DocNode* node = node_at(p.root, key);
      const Field at = axes_field.child(axes_field.node().entries[a].second,
                                        join_path(axes_field.path(), axis.name));
      if (!node || node->kind != DocNode::Kind::kScalar || node->quoted)
        at.fail(profile.string() + " has no number at `" + key + "` to vary");
    }
  }

  // Files named by the file axes, each checked where it is written.
  for (std::size_t a = 0; a < study.axes.size(); ++a) {
    Axis& axis = study.axes[a];
    for (std::size_t v = 0; v < axis.values.size(); ++v) {
      if (value_fields[a].empty()) {  // a range: numbers made here
        const double value = number_of(axis.values[v]);
        if (axis.kind == AxisKind::kSeed &&
            (value < 0 || value > 4294967295.0 || value != std::floor(value)))
          axes_field
              .child(axes_field.node().entries[a].second, join_path(axes_field.path(), axis.name))
              .fail("expected whole seeds from 0 to 4294967295, the range gives " + axis.values[v]);
        continue;
      }
      const Field& at = value_fields[a][v];
      if (axis.kind == AxisKind::kObjective) objective_of(at);
      if (axis.kind == AxisKind::kSeed) seed_of(at);
      // A profile's number, read as every number in a file is (its range is the
      // profile's, checked when the variant loads it).
      if (axis.kind == AxisKind::kMachineKey || axis.kind == AxisKind::kMaterialKey) at.as_number();
      if (axis.kind == AxisKind::kBuilding || axis.kind == AxisKind::kMachine ||
          axis.kind == AxisKind::kMaterial ||
          (axis.kind == AxisKind::kSite && axis.values[v] != "none"))
        study_path(at, folder);
    }
  }

  // The grid's size, and which of its points the study takes. Counted in checked integers:
  // a product past 2^63 - 1 is refused, never wrapped.
  long long grid = 1;
  for (const Axis& axis : study.axes)
    if (__builtin_mul_overflow(grid, static_cast<long long>(axis.values.size()), &grid))
      axes_field.fail(printf_string(
          "the axes make more than %lld combinations (the product of their sizes), the most a "
          "study counts, even to sample from; vary fewer axes or fewer values",
          std::numeric_limits<long long>::max()));
  std::vector<long long> chosen;
  const auto sample = top.optional("sample");
  if (!sample || (sample->is_scalar() && sample->as_string() == "grid")) {
    if (grid > kMaxVariants)
      axes_field.fail(
          printf_string("the axes make %lld variants; at most %lld (take a random "
                        "sample: `sample: {random: 500, seed: 1}`)",
                        grid, kMaxVariants));
    for (long long k = 0; k < grid; ++k) chosen.push_back(k);
  } else {
    if (!sample->is_map()) sample->fail("expected `grid` or {random: N, seed: S}");
    MapReader s(*sample, {"random", "seed"});
    s.reject_unknown();
    const Field count_field = s.required("random");
    const long long count = count_field.as_count();
    if (count < 1 || count > kMaxVariants)
      count_field.fail("expected from 1 to " + std::to_string(kMaxVariants) + " variants");
    if (count > grid) count_field.fail(printf_string("the axes make only %lld variants", grid));
    const std::uint64_t seed = s.optional("seed") ? seed_of(*s.optional("seed")) : 1;
    // Floyd's sampling: `count` distinct grid points, the same for the same seed on any
    // machine (mt19937_64 is fully specified; the reduction below is ours).
    std::mt19937_64 random(seed);
    const auto below = [&](long long n) {  // uniform in [0, n], by rejection; n < 2^63 - 1
      const std::uint64_t range = static_cast<std::uint64_t>(n) + 1;
      const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
      std::uint64_t r;
      do r = random();
      while (r >= limit);
      return static_cast<long long>(r % range);
    };
    std::set<long long> picked;
    const long long n = grid;
    for (long long j = n - count; j < n; ++j) {
      const long long t = below(j);
      picked.insert(picked.count(t) ? j : t);
    }
    chosen.assign(picked.begin(), picked.end());
  }
  study.grid_size = grid;

  if (const auto m = top.optional("measures")) {
    for (const Field& item : m->items()) {
      const std::string name = item.as_string();
      if (std::find(kMeasures.begin(), kMeasures.end(), name) == kMeasures.end())
        item.fail("unknown measure '" + name + "'; the measures are: " + [] {
          std::string all;
          for (const auto& k : kMeasures) all += (all.empty() ? "" : ", ") + k;
          return all;
        }());
      study.measures.push_back(name);
    }
  } else {
    study.measures = kMeasures;
  }

  // The variants: the first axis varies slowest.
  const int width = std::max(4, static_cast<int>(std::to_string(chosen.size()).size()));
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    Variant v = base;
    v.index = static_cast<int>(i);
    v.id = printf_string("v%0*zu", width, i + 1);
    long long rest = chosen[i];
    std::vector<std::size_t> pick(study.axes.size());
    for (std::size_t a = study.axes.size(); a-- > 0;) {
      pick[a] = static_cast<std::size_t>(rest % study.axes[a].values.size());
      rest /= static_cast<long long>(study.axes[a].values.size());
    }
    for (std::size_t a = 0; a < study.axes.size(); ++a) {
      const Axis& axis = study.axes[a];
      const std::string& value = axis.values[pick[a]];
      v.settings.emplace_back(axis.name, value);
      const fs::path path = (folder / value).lexically_normal();
      switch (axis.kind) {
        case AxisKind::kBuilding:
          v.building = fs::absolute(path);
          break;
        case AxisKind::kMachine:
          v.machine = fs::absolute(path);
          break;
        case AxisKind::kMaterial:
          v.material = fs::absolute(path);
          break;
        case AxisKind::kSite:
          v.site = value == "none" ? fs::path() : fs::absolute(path);
          break;
        case AxisKind::kObjective:
          v.objective = value;
          break;
        case AxisKind::kSeed:  // a whole number (checked above) as written: 7, 7.0 or 7e0
          v.seed = static_cast<std::uint64_t>(number_of(value));
          break;
        case AxisKind::kMachineKey:
          v.machine_keys.emplace_back(axis.name.substr(8), number_of(value));
          break;
        case AxisKind::kMaterialKey:
          v.material_keys.emplace_back(axis.name.substr(9), number_of(value));
          break;
      }
    }
    study.variants.push_back(std::move(v));
  }
  return study;
}

}  // namespace ccbuild::study
