#include "ccbuild/orchestrator/schedule_diff.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/orchestrator/schedule_json.hpp"

namespace ccbuild::orchestrator {
namespace {

using json = nlohmann::json;
/// Schedules of tall buildings hold many timed paths; far above any real one.
constexpr std::uintmax_t kMaxScheduleBytes = 1024ull * 1024 * 1024;

double number(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : std::nan("");
}

std::string text(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return "null";
  return it->is_string() ? it->get<std::string>() : it->dump();
}

std::string hours(double s) {
  return std::isfinite(s) ? printf_string("%.1f s (%.2f h)", s, s / 3600.0) : "null";
}

std::string layer_name(const json& l) {
  return "floor " + text(l, "floor") + " layer " + text(l, "layer");
}

void require(const std::filesystem::path& path, const char* field, bool ok,
             const std::string& expected) {
  if (!ok) throw InputError(path.string(), 0, field, expected);
}

}  // namespace

bool DiffTolerance::allows(double old_value, double new_value) const {
  if (std::isnan(old_value) || std::isnan(new_value))
    return std::isnan(old_value) == std::isnan(new_value);
  return std::abs(new_value - old_value) <=
         std::max(absolute_s, relative * std::abs(old_value)) + 1e-9;
}

json read_schedule_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), 0, "", "not found or not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxScheduleBytes)
    throw InputError(
        path.string(), 0, "",
        printf_string("is %ju bytes; at most %ju are accepted", size, kMaxScheduleBytes));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json doc;
  try {
    doc = json::parse(bytes);
  } catch (const json::parse_error& e) {
    // Line of the byte the parser stopped at.
    const std::size_t at = std::min<std::size_t>(e.byte, bytes.size());
    const int line = 1 + static_cast<int>(std::count(bytes.begin(), bytes.begin() + at, '\n'));
    throw InputError(path.string(), line, "", std::string("not valid JSON: ") + e.what());
  }
  require(path, "format", doc.is_object() && text(doc, "format") == "ccbuild-schedule",
          "expected a ccbuild schedule (\"format\": \"ccbuild-schedule\"), from `ccbuild schedule "
          "-o`");
  require(path, "schema_version",
          doc.contains("schema_version") && doc["schema_version"] == kScheduleSchemaVersion,
          "expected schema_version " + std::to_string(kScheduleSchemaVersion) + ", got " +
              text(doc, "schema_version"));
  for (const char* key : {"layers", "events"})
    require(path, key, doc.contains(key) && doc[key].is_array(), "expected an array");
  for (const char* key : {"totals", "plans"})
    require(path, key, doc.contains(key) && doc[key].is_object(), "expected an object");
  require(path, "feasible", doc.contains("feasible") && doc["feasible"].is_boolean(),
          "expected true or false");
  for (std::size_t k = 0; k < doc["layers"].size(); ++k) {
    const json& l = doc["layers"][k];
    const std::string field = "layers[" + std::to_string(k) + "]";
    bool ok = l.is_object();
    for (const char* key : {"floor", "layer", "start_s", "end_s", "nozzles"})
      ok = ok && l.contains(key) && l[key].is_number();
    if (!ok)
      throw InputError(path.string(), 0, field,
                       "expected an object with numbers floor, layer, start_s, end_s, nozzles");
  }
  return doc;
}

ScheduleDiff diff_schedules(const json& a, const json& b, const DiffTolerance& tol, int shown) {
  ScheduleDiff out;
  if (a["feasible"] != b["feasible"])
    out.changes.push_back(std::string("feasible: ") + (a["feasible"].get<bool>() ? "yes" : "no") +
                          " -> " + (b["feasible"].get<bool>() ? "yes" : "no") +
                          (b.contains("infeasibility") && b["infeasibility"].is_object()
                               ? " (" + text(b["infeasibility"], "message") + ")"
                               : ""));
  // Inputs: checksums tell whether the same files went in.
  std::map<std::string, std::string> old_files, new_files;
  if (a.contains("inputs") && a["inputs"].contains("files"))
    for (const auto& f : a["inputs"]["files"]) old_files[text(f, "path")] = text(f, "sha256");
  if (b.contains("inputs") && b["inputs"].contains("files"))
    for (const auto& f : b["inputs"]["files"]) new_files[text(f, "path")] = text(f, "sha256");
  for (const auto& [path, sum] : new_files) {
    const auto it = old_files.find(path);
    if (it == old_files.end())
      out.notes.push_back("input " + path + " is new");
    else if (it->second != sum)
      out.notes.push_back("input " + path + " changed (SHA-256 " + it->second.substr(0, 12) +
                          " -> " + sum.substr(0, 12) + ")");
  }
  for (const auto& [path, sum] : old_files)
    if (!new_files.count(path)) out.notes.push_back("input " + path + " is no longer read");

  // Totals.
  for (const auto& [key, value] : a["totals"].items()) {
    if (!value.is_number() || !b["totals"].contains(key)) continue;
    const double x = value.get<double>(), y = number(b["totals"], key.c_str());
    if (x == y) continue;
    const std::string line =
        "totals." + key + ": " +
        (key == "layers" ? text(a["totals"], key.c_str()) + " -> " + text(b["totals"], key.c_str())
                         : hours(x) + " -> " + hours(y)) +
        (std::isfinite(x) && std::isfinite(y) && x != 0
             ? printf_string(" (%+.2f%%)", 100.0 * (y - x) / x)
             : "");
    (key != "layers" && tol.allows(x, y) ? out.notes : out.changes).push_back(line);
  }

  // Per floor: its span, nozzles and waits.
  struct FloorSummary {
    double start_s = INFINITY, end_s = -INFINITY, waits_s = 0;
    int layers = 0, max_nozzles = 0;
  };
  auto floors_of = [](const json& s) {
    std::map<int, FloorSummary> f;
    for (const auto& l : s["layers"]) {
      FloorSummary& x = f[l["floor"].get<int>()];
      x.start_s = std::min(x.start_s, l["start_s"].get<double>());
      x.end_s = std::max(x.end_s, l["end_s"].get<double>());
      x.waits_s += std::isfinite(number(l, "wait_before_s")) ? number(l, "wait_before_s") : 0.0;
      x.layers += 1;
      x.max_nozzles = std::max(x.max_nozzles, l["nozzles"].get<int>());
    }
    return f;
  };
  const auto fa = floors_of(a), fb = floors_of(b);
  for (const auto& [floor, x] : fa) {
    const auto it = fb.find(floor);
    if (it == fb.end()) {
      out.changes.push_back("floor " + std::to_string(floor) + ": no longer scheduled");
      continue;
    }
    const FloorSummary& y = it->second;
    const double dx = x.end_s - x.start_s, dy = y.end_s - y.start_s;
    if (x.layers != y.layers || x.max_nozzles != y.max_nozzles || !tol.allows(dx, dy) ||
        !tol.allows(x.waits_s, y.waits_s))
      out.changes.push_back(printf_string(
          "floor %d: %d -> %d layers, up to %d -> %d nozzles, %s -> %s from first start to last "
          "end, waits %s -> %s",
          floor, x.layers, y.layers, x.max_nozzles, y.max_nozzles, hours(dx).c_str(),
          hours(dy).c_str(), hours(x.waits_s).c_str(), hours(y.waits_s).c_str()));
  }
  for (const auto& [floor, y] : fb)
    if (!fa.count(floor)) out.changes.push_back("floor " + std::to_string(floor) + ": new");

  // Layers, matched by floor and layer.
  std::map<std::pair<int, int>, const json*> new_layers;
  for (const auto& l : b["layers"]) new_layers[{l["floor"].get<int>(), l["layer"].get<int>()}] = &l;
  std::map<std::string, std::string> plan_pairs;  // old plan key -> new, for the plan check
  for (const auto& l : a["layers"]) {
    const auto it = new_layers.find({l["floor"].get<int>(), l["layer"].get<int>()});
    std::string what;
    if (it == new_layers.end()) {
      what = "only in the old schedule";
    } else {
      const json& m = *it->second;
      new_layers.erase(it);
      for (const char* key : {"nozzles", "plan", "method", "geometry"})
        if (text(l, key) != text(m, key))
          what += std::string(what.empty() ? "" : ", ") + key + " " + text(l, key) + " -> " +
                  text(m, key);
      for (const char* key :
           {"start_s", "end_s", "wait_before_s", "local_interval_min_s", "local_interval_max_s"})
        if (!tol.allows(number(l, key), number(m, key)))
          what += std::string(what.empty() ? "" : ", ") + key + " " + text(l, key) + " -> " +
                  text(m, key);
      if (text(l, "plan") == text(m, "plan")) plan_pairs[text(l, "plan")] = text(m, "plan");
    }
    if (what.empty()) continue;
    if (++out.differing_layers <= shown) out.changes.push_back(layer_name(l) + ": " + what);
  }
  for (const auto& [key, l] : new_layers)
    if (++out.differing_layers <= shown)
      out.changes.push_back(layer_name(*l) + ": only in the new schedule");
  if (out.differing_layers > shown)
    out.changes.push_back(printf_string("... %d differing layers in all", out.differing_layers));

  // Plans kept under the same key: their timed paths.
  for (const auto& [key, same] : plan_pairs) {
    if (!a["plans"].contains(key) || !b["plans"].contains(same)) continue;
    if (a["plans"][key] != b["plans"][same]) {
      ++out.differing_plans;
      out.changes.push_back("plan " + key + ": its timed paths differ");
    }
  }

  // Events, in order.
  const json& ea = a["events"];
  const json& eb = b["events"];
  const std::size_t n = std::max(ea.size(), eb.size());
  for (std::size_t k = 0; k < n; ++k) {
    std::string what;
    if (k >= ea.size()) {
      what = "new: " + text(eb[k], "kind") + " " + text(eb[k], "detail");
    } else if (k >= eb.size()) {
      what = "gone: " + text(ea[k], "kind") + " " + text(ea[k], "detail");
    } else {
      if (text(ea[k], "kind") != text(eb[k], "kind") ||
          text(ea[k], "detail") != text(eb[k], "detail"))
        what = text(ea[k], "kind") + " " + text(ea[k], "detail") + " -> " + text(eb[k], "kind") +
               " " + text(eb[k], "detail");
      for (const char* key : {"start_s", "end_s"})
        if (!tol.allows(number(ea[k], key), number(eb[k], key)))
          what +=
              std::string(what.empty() ? text(ea[k], "kind") + " " + text(ea[k], "detail") + ": "
                                       : ", ") +
              key + " " + text(ea[k], key) + " -> " + text(eb[k], key);
    }
    if (what.empty()) continue;
    if (++out.differing_events <= shown)
      out.changes.push_back("event " + std::to_string(k) + ": " + what);
  }
  if (out.differing_events > shown)
    out.changes.push_back(printf_string("... %d differing events in all", out.differing_events));
  return out;
}

}  // namespace ccbuild::orchestrator
