// A study's results: rows, CSV, JSON.

#include "ccbuild/study/results.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

/// A number for the CSV: shortest text that reads back to the same double.
std::string number_text(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return printf_string("%.10g", v.get<double>());
  return v.get<std::string>();
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

nlohmann::ordered_json measures_of(const nlohmann::json& s) {
  nlohmann::ordered_json m;
  const auto& totals = s.at("totals");
  m["makespan_s"] = totals.value("makespan_s", 0.0);
  m["feasible"] = s.value("feasible", false);
  int nozzles = 0;
  double idle_margin_s = std::numeric_limits<double>::infinity();
  const double idle_limit_s = s.at("inputs").at("machine").value("nozzle_idle_limit_s", 0.0);
  std::map<std::string, double> by_reason;
  for (const auto& l : s.at("layers")) {
    nozzles = std::max(nozzles, l.value("nozzles", 0));
    idle_margin_s = std::min(idle_margin_s, idle_limit_s - l.value("max_idle_s", 0.0));
    for (const auto& r : l.value("wait_reasons", nlohmann::json::array()))
      by_reason[r.value("kind", "")] += l.value("wait_before_s", 0.0);
  }
  m["nozzles_max"] = nozzles;
  m["waits_s"] = totals.value("waits_s", 0.0);
  for (const char* kind : {"min-interval", "strength", "anchor-strength", "slab", "off-shift",
                           "joint", "cold", "wind"}) {
    std::string key = std::string("wait_") + kind + "_s";
    std::replace(key.begin(), key.end(), '-', '_');
    m[key] = by_reason.count(kind) ? by_reason.at(kind) : 0.0;
  }
  m["concrete_m3"] = totals.value("concrete_m3", 0.0);
  m["crew_h"] = totals.value("crew_h", 0.0);
  int climbs = 0;
  for (const auto& e : s.at("events"))
    if (e.value("kind", "") == "climb") ++climbs;
  m["climbs"] = climbs;
  m["machine_s"] = totals.value("machine_s", 0.0);
  m["idle_margin_s"] =
      std::isfinite(idle_margin_s) ? nlohmann::ordered_json(idle_margin_s) : nullptr;
  m["warnings"] = s.value("warnings", nlohmann::json::array()).size();
  return m;
}

Collected collect(const Plan& plan) {
  Collected c;
  for (const Variant& v : plan.study.variants) {
    nlohmann::ordered_json row;
    row["id"] = v.id;
    row["settings"] = nlohmann::ordered_json::object();
    for (const auto& [name, value] : v.settings) row["settings"][name] = value;
    const fs::path dir = plan.folder / "variants" / v.id;
    std::error_code ec;
    nlohmann::ordered_json result;
    if (fs::is_regular_file(dir / "result.json", ec)) {
      try {
        result = nlohmann::ordered_json::parse(read_text_file(dir / "result.json"));
      } catch (const std::exception&) {
        result = nullptr;
      }
    }
    std::string status = result.is_object() ? result.value("status", "") : "";
    if ((status == "feasible" || status == "infeasible") && !finished(plan, v.index)) status = "";
    row["status"] = status.empty() ? "missing" : status;
    if (status == "failed") row["reason"] = result.value("reason", "");
    row["measures"] =
        result.is_object() && result.contains("measures") && !status.empty() && status != "failed"
            ? result["measures"]
            : nlohmann::ordered_json(nullptr);
    (status == "feasible"     ? c.feasible
     : status == "infeasible" ? c.infeasible
     : status == "failed"     ? c.failed
                              : c.missing)
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
  return out.dump(2) + "\n";
}

}  // namespace ccbuild::study
