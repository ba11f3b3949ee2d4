// A study's results as one HTML page: the counts, the Pareto fronts, the makespan's
// sensitivity to each axis, every variant. Plain SVG and HTML, no script needed.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/study/results.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

double measure(const nlohmann::ordered_json& row, const std::string& name) {
  const auto& m = row["measures"];
  return m.is_object() && m.contains(name) && m[name].is_number()
             ? m[name].get<double>()
             : std::numeric_limits<double>::quiet_NaN();
}

std::string settings_text(const nlohmann::ordered_json& row) {
  std::string out;
  for (const auto& [k, v] : row["settings"].items())
    out += (out.empty() ? "" : ", ") + k + " " + v.get<std::string>();
  return out;
}

/// Where a variant's page is: its report when one was written, else its schedule.
std::string link_of(const Plan& plan, const std::string& id) {
  std::error_code ec;
  return fs::is_regular_file(plan.folder / "variants" / id / "report.html", ec)
             ? "variants/" + id + "/report.html"
             : "variants/" + id + "/schedule.json";
}

std::string days(double s) {
  return printf_string("%.2f d", s / 86400.0);
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& front_costs() {
  static const std::vector<std::pair<std::string, std::string>> kCosts = {
      {"nozzles_max", "nozzles (machine size)"},
      {"concrete_m3", "concrete, m³"},
      {"crew_h", "crew, person-hours"}};
  return kCosts;
}

std::vector<int> pareto_front(const Collected& c, const std::string& cost) {
  struct Point {
    double cost, makespan;
    int index;
  };
  std::vector<Point> points;
  for (int i : c.feasible) {
    const auto& row = c.rows[i];
    const double x = measure(row, cost), y = measure(row, "makespan_s");
    if (std::isfinite(x) && std::isfinite(y)) points.push_back({x, y, i});
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
    return a.cost != b.cost           ? a.cost < b.cost
           : a.makespan != b.makespan ? a.makespan < b.makespan
                                      : a.index < b.index;
  });
  std::vector<int> front;
  const Point* kept = nullptr;  // the last point on the front
  for (const Point& p : points) {
    // Faster than every cheaper one; or equal in both to the one kept before (not beaten).
    if (!kept || p.makespan < kept->makespan ||
        (p.makespan == kept->makespan && p.cost == kept->cost)) {
      front.push_back(p.index);
      kept = &p;
    }
  }
  return front;
}

std::vector<Sensitivity> sensitivity(const Plan& plan, const Collected& c) {
  std::vector<Sensitivity> out;
  for (const Axis& axis : plan.study.axes) {
    Sensitivity s;
    s.axis = axis.name;
    for (const std::string& value : axis.values) {
      Sensitivity::Value v;
      v.value = value;
      double sum = 0.0;
      for (int i : c.feasible) {
        const auto& row = c.rows[i];
        if (row["settings"][axis.name].get<std::string>() != value) continue;
        const double y = measure(row, "makespan_s");
        v.min_s = v.count ? std::min(v.min_s, y) : y;
        v.max_s = v.count ? std::max(v.max_s, y) : y;
        sum += y;
        ++v.count;
      }
      v.mean_s = v.count ? sum / v.count : 0.0;
      s.values.push_back(v);
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& v : s.values)
      if (v.count) lo = std::min(lo, v.mean_s), hi = std::max(hi, v.mean_s);
    s.spread_s = std::isfinite(lo) ? hi - lo : 0.0;
    out.push_back(std::move(s));
  }
  std::stable_sort(out.begin(), out.end(), [](const Sensitivity& a, const Sensitivity& b) {
    return a.spread_s > b.spread_s;
  });
  return out;
}

std::string results_html(const Plan& plan, const Collected& c) {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
                  xml_escape(plan.study.name) +
                  " - ccbuild study</title>\n<style>\n"
                  "body{font:14px/1.4 system-ui,sans-serif;margin:24px;color:#222;max-width:1200px}"
                  "h1{font-size:22px}h2{font-size:17px;margin-top:28px}"
                  "table{border-collapse:collapse}td,th{padding:3px 8px;border-bottom:1px solid "
                  "#e3e6ea;text-align:left}"
                  "td.n{text-align:right;font-variant-numeric:tabular-nums}"
                  ".front{fill:#d62728}.dot{fill:#1f77b4;opacity:.55}.axis{stroke:#888}.tick{font-"
                  "size:11px;fill:#555}"
                  ".bar{fill:#9ecae1}.mean{fill:#1f77b4}.failed{color:#b00}.charts{display:flex;"
                  "flex-wrap:wrap;gap:16px}"
                  "</style></head><body>\n";
  h += "<h1>" + xml_escape(plan.study.name) + "</h1>\n";
  h += printf_string(
      "<p id=\"counts\">%zu variants of %lld combinations: %zu feasible, %zu infeasible, %zu "
      "failed, %zu not run.</p>\n",
      c.rows.size(), plan.study.grid_size, c.feasible.size(), c.infeasible.size(), c.failed.size(),
      c.missing.size());

  // Pareto fronts: the makespan against each cost; every feasible variant a dot that links
  // to its page, the front in red.
  h += "<h2>Makespan against cost</h2>\n<p>Each dot a feasible variant (hover for its settings, "
       "click for its schedule); red: the Pareto front, where nothing is both faster and "
       "cheaper.</p>\n<div class=\"charts\">\n";
  const double W = 360, H = 260, L = 56, B = 36;
  for (const auto& [cost, label] : front_costs()) {
    const std::vector<int> front = pareto_front(c, cost);
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (int i : c.feasible) {
      const double x = measure(c.rows[i], cost), y = measure(c.rows[i], "makespan_s");
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    h += "<svg class=\"front-chart\" data-cost=\"" + cost + "\" width=\"" +
         printf_string("%.0f", W) + "\" height=\"" + printf_string("%.0f", H) + "\">";
    if (std::isfinite(x0)) {
      if (x1 == x0) x0 -= 1, x1 += 1;
      if (y1 == y0) y0 -= 3600, y1 += 3600;
      const auto X = [&](double x) { return L + (x - x0) / (x1 - x0) * (W - L - 12); };
      const auto Y = [&](double y) { return 10 + (y1 - y) / (y1 - y0) * (H - B - 10); };
      h += printf_string("<line class=\"axis\" x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\"/>",
                         L, H - B, W - 6, H - B);
      h += printf_string("<line class=\"axis\" x1=\"%.0f\" y1=\"10\" x2=\"%.0f\" y2=\"%.0f\"/>", L,
                         L, H - B);
      h += printf_string("<text class=\"tick\" x=\"%.0f\" y=\"%.0f\">%s</text>", L, H - B + 14,
                         printf_string("%.4g", x0).c_str());
      h += printf_string("<text class=\"tick\" x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\">%s</text>",
                         W - 6, H - B + 14, printf_string("%.4g", x1).c_str());
      h += printf_string(
          "<text class=\"tick\" x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">%s</text>",
          (L + W) / 2, H - 6, xml_escape(label).c_str());
      h += printf_string("<text class=\"tick\" x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\">%s</text>",
                         L - 4, H - B, days(y0).c_str());
      h += printf_string("<text class=\"tick\" x=\"%.0f\" y=\"18\" text-anchor=\"end\">%s</text>",
                         L - 4, days(y1).c_str());
      std::string line;
      for (int i : front)
        line += printf_string("%s%.1f,%.1f", line.empty() ? "" : " ", X(measure(c.rows[i], cost)),
                              Y(measure(c.rows[i], "makespan_s")));
      if (front.size() > 1)
        h += "<polyline points=\"" + line + "\" fill=\"none\" stroke=\"#d62728\"/>";
      for (int i : c.feasible) {
        const auto& row = c.rows[i];
        const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        const std::string id = row["id"];
        h += "<a href=\"" + link_of(plan, id) + "\"><circle class=\"" +
             (on_front ? "front" : "dot") + "\" data-id=\"" + id +
             printf_string("\" cx=\"%.1f\" cy=\"%.1f\" r=\"%d\">", X(measure(row, cost)),
                           Y(measure(row, "makespan_s")), on_front ? 5 : 4) +
             "<title>" +
             xml_escape(id + ": " + settings_text(row) + "; " + days(measure(row, "makespan_s")) +
                        ", " + label + " " + printf_string("%.4g", measure(row, cost))) +
             "</title></circle></a>";
      }
    } else {
      h += "<text x=\"20\" y=\"40\">no feasible variant</text>";
    }
    h += "</svg>\n";
  }
  h += "</div>\n";

  // Sensitivity: per axis, the mean makespan at each value (bar), with its least and largest.
  h +=
      "<h2>What the makespan depends on</h2>\n<p>Per axis, largest effect first: the mean makespan "
      "of the feasible variants at each value (bar), and their least and largest (line).</p>\n";
  double top = 0.0;
  for (int i : c.feasible) top = std::max(top, measure(c.rows[i], "makespan_s"));
  for (const Sensitivity& s : sensitivity(plan, c)) {
    h += "<h3 class=\"sensitivity\" data-axis=\"" + xml_escape(s.axis) + "\">" +
         xml_escape(s.axis) + ": the means differ by " + days(s.spread_s) + "</h3>\n<table>";
    for (const auto& v : s.values) {
      h += "<tr><td>" + xml_escape(v.value) + "</td>";
      if (v.count && top > 0) {
        const double k = 300.0 / top;
        h += printf_string(
            "<td><svg width=\"310\" height=\"14\"><rect class=\"bar\" x=\"0\" y=\"2\" "
            "width=\"%.1f\" height=\"10\"/>"
            "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"7\" y2=\"7\" stroke=\"#08519c\"/></svg></td>",
            v.mean_s * k, v.min_s * k, v.max_s * k);
        h += "<td class=\"n\">" + days(v.mean_s) + "</td><td class=\"n\">" + days(v.min_s) +
             " to " + days(v.max_s) + "</td>" + printf_string("<td class=\"n\">%d</td>", v.count);
      } else {
        h += "<td colspan=\"4\">no feasible variant</td>";
      }
      h += "</tr>\n";
    }
    h += "</table>\n";
  }

  // Every variant.
  h += "<h2>Variants</h2>\n<table id=\"variants\"><tr><th>id</th>";
  for (const Axis& a : plan.study.axes) h += "<th>" + xml_escape(a.name) + "</th>";
  h += "<th>status</th><th>makespan</th><th>nozzles</th><th>concrete m³</th><th>crew "
       "h</th><th>waits</th></tr>\n";
  for (const auto& row : c.rows) {
    const std::string id = row["id"], status = row["status"];
    h += "<tr data-id=\"" + id + "\"><td><a href=\"" + link_of(plan, id) + "\">" + id + "</a></td>";
    for (const Axis& a : plan.study.axes)
      h += "<td>" + xml_escape(row["settings"][a.name].get<std::string>()) + "</td>";
    h += "<td" + std::string(status == "failed" || status == "missing" ? " class=\"failed\"" : "") +
         ">" + xml_escape(status) +
         (row.contains("reason") ? ": <a href=\"variants/" + id + "/log.txt\">" +
                                       xml_escape(row["reason"].get<std::string>()) + "</a>"
                                 : "") +
         "</td>";
    if (row["measures"].is_object())
      h += "<td class=\"n\">" + days(measure(row, "makespan_s")) + "</td>" +
           printf_string(
               "<td class=\"n\">%.0f</td><td class=\"n\">%.1f</td><td class=\"n\">%.1f</td>",
               measure(row, "nozzles_max"), measure(row, "concrete_m3"), measure(row, "crew_h")) +
           "<td class=\"n\">" + days(measure(row, "waits_s")) + "</td>";
    else
      h += "<td colspan=\"5\"></td>";
    h += "</tr>\n";
  }
  h += "</table>\n<p>Made by ccbuild study; the same rows are in results.csv and "
       "results.json.</p>\n</body></html>\n";
  return h;
}

}  // namespace ccbuild::study
