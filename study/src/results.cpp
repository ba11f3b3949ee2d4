// A study's results: rows, CSV, JSON.

#include "ccbuild/study/results.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/json_reader.hpp"
#include "study_files.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

std::string wait_measure(schedule::WaitKind kind) {
  std::string key = "wait_" + schedule::to_string(kind) + "_s";
  std::replace(key.begin(), key.end(), '-', '_');
  return key;
}

namespace {

/// A number for the CSV: shortest text that reads back to the same double.
std::string number_text(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return printf_string("%.10g", v.get<double>());
  return v.get<std::string>();
}

}  // namespace

namespace detail {

nlohmann::ordered_json measures_of_located(const JsonAt& s) {
  // Every finite double: a measure is what the schedule says; its own reader checks ranges.
  // A value a measure is made of that the schedule lacks is an error naming it, never 0.
  const Range any =
      Range::closed(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  constexpr std::size_t kMaxItems = 100'000'000;
  const auto number = [&](const JsonAt& object, const char* key) {
    return object.at(key).number(any);
  };
  const auto text = [](const JsonAt& object, const char* key) { return object.at(key).string(); };
  nlohmann::ordered_json m;
  const JsonAt totals = s.at("totals");
  m["makespan_s"] = number(totals, "makespan_s");
  m["feasible"] = s.at("feasible").boolean();
  int nozzles = 0;
  double idle_margin_s = std::numeric_limits<double>::infinity();
  const double idle_limit_s = number(s.at("inputs").at("machine"), "nozzle_idle_limit_s");
  std::map<std::string, double> by_reason;
  for (const JsonAt& l : s.at("layers").elements(kMaxItems)) {
    nozzles = std::max(nozzles, static_cast<int>(l.at("nozzles").integer(0, 1'000'000)));
    idle_margin_s = std::min(idle_margin_s, idle_limit_s - number(l, "max_idle_s"));
    if (const auto reasons = l.maybe("wait_reasons"))
      for (const JsonAt& r : reasons->elements(kMaxItems))
        by_reason[text(r, "kind")] += number(r, "binding_s");
  }
  // A climb's wait too, each cause by the time it was the binding one.
  for (const JsonAt& e : s.at("events").elements(kMaxItems))
    if (const auto reasons = e.maybe("wait_reasons"))
      for (const JsonAt& r : reasons->elements(kMaxItems))
        by_reason[text(r, "kind")] += number(r, "binding_s");
  m["nozzles_max"] = nozzles;
  m["waits_s"] = number(totals, "waits_s");
  for (const schedule::WaitKind kind : schedule::wait_kinds()) {
    const std::string name = schedule::to_string(kind);
    m[wait_measure(kind)] = by_reason.count(name) ? by_reason.at(name) : 0.0;
  }
  m["concrete_m3"] = number(totals, "concrete_m3");
  m["crew_h"] = number(totals, "crew_h");
  int climbs = 0;
  for (const JsonAt& e : s.at("events").elements(kMaxItems))
    if (text(e, "kind") == "climb") ++climbs;
  m["climbs"] = climbs;
  m["machine_s"] = number(totals, "machine_s");
  m["idle_margin_s"] =
      std::isfinite(idle_margin_s) ? nlohmann::ordered_json(idle_margin_s) : nullptr;
  m["warnings"] = s.at("warnings").elements(kMaxItems).size();
  return m;
}

}  // namespace detail

nlohmann::ordered_json measures_of(const nlohmann::json& s) {
  const std::string no_text;  // a value in memory: errors name the pointer, no line
  const JsonText located("schedule JSON", no_text);
  return detail::measures_of_located(JsonAt(located, s, ""));
}

Collected collect(const Plan& plan) {
  Collected c;
  for (const Variant& v : plan.study.variants) {
    nlohmann::ordered_json row;
    row["id"] = v.id;
    row["settings"] = nlohmann::ordered_json::object();
    for (const auto& [name, value] : v.settings) row["settings"][name] = value;
    const fs::path file = plan.folder / "variants" / v.id / "result.json";
    std::error_code ec;
    std::optional<detail::ResultFile> result;
    std::string unreadable;  // a result.json that does not read: why, located
    if (fs::is_regular_file(file, ec)) {
      try {
        result = detail::read_result_file(file);
        if (result->id != v.id || result->index != v.index)
          throw InputError(file.string(), 0, "id",
                           "holds the result of " + result->id + ", not of " + v.id);
      } catch (const InputError& e) {
        result.reset();
        unreadable = e.what();
      }
    }
    // A result whose inputs changed since, or whose schedule no longer reads, is missing.
    std::optional<VariantStatus> status;
    if (result) status = result->status;
    if (status && *status != VariantStatus::kFailed && !finished(plan, v.index)) status.reset();
    row["status"] = status ? to_string(*status) : "missing";
    if (status == VariantStatus::kFailed) row["reason"] = result->reason;
    if (!unreadable.empty()) row["reason"] = "its result.json does not read: " + unreadable;
    row["measures"] = status && *status != VariantStatus::kFailed && result->measures
                          ? *result->measures
                          : nlohmann::ordered_json(nullptr);
    (!status                                 ? c.missing
     : *status == VariantStatus::kFeasible   ? c.feasible
     : *status == VariantStatus::kInfeasible ? c.infeasible
                                             : c.failed)
        .push_back(v.index);
    c.rows.push_back(std::move(row));
  }
  return c;
}

std::string results_csv(const Plan& plan, const Collected& c) {
  std::string out = "id";
  for (const Axis& a : plan.study.axes) out += "," + csv_field(a.name);
  out += ",status";
  for (const auto& m : plan.study.measures) out += "," + m;
  out += "\r\n";
  for (const auto& row : c.rows) {
    out += row["id"].get<std::string>();
    for (const Axis& a : plan.study.axes)
      out += "," + csv_field(row["settings"][a.name].get<std::string>());
    out += "," + row["status"].get<std::string>();
    for (const auto& m : plan.study.measures)
      out += "," + (row["measures"].is_object() ? number_text(row["measures"][m]) : std::string());
    out += "\r\n";
  }
  return out;
}

std::string results_json(const Plan& plan, const Collected& c) {
  nlohmann::ordered_json out;
  out["format"] = "ccbuild-study-results";
  out["name"] = plan.study.name;
  out["axes"] = nlohmann::ordered_json::array();
  for (const Axis& a : plan.study.axes)
    out["axes"].push_back({{"name", a.name}, {"values", a.values}});
  out["grid_size"] = plan.study.grid_size;
  out["counts"] = {{"variants", c.rows.size()},
                   {"feasible", c.feasible.size()},
                   {"infeasible", c.infeasible.size()},
                   {"failed", c.failed.size()},
                   {"missing", c.missing.size()}};
  out["variants"] = nlohmann::ordered_json::array();
  for (const auto& row : c.rows) {
    nlohmann::ordered_json r = row;
    if (r["measures"].is_object()) {
      nlohmann::ordered_json chosen;
      for (const auto& m : plan.study.measures) chosen[m] = r["measures"][m];
      r["measures"] = chosen;
    }
    out["variants"].push_back(std::move(r));
  }
  return out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace ccbuild::study
