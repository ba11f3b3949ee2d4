#include "ccbuild/report/report.hpp"

#include <fstream>
#include <iterator>
#include <map>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/report/day_packages.hpp"
#include "plan_drawing.hpp"
#include "report_assets.hpp"
#include "svg.hpp"

namespace ccbuild::report {
namespace {

std::string read_script(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path.string(), 0, "three.js",
                     "cannot be read; the report inlines three.js from Debian's libjs-three "
                     "(scripts/install-deps.sh installs it)");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text;
}

/// Text safe inside an inline <script>: "</" cannot end it early.
std::string script_safe(std::string text) {
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3)
    text.replace(at, 2, "<\\/");
  return text;
}

}  // namespace

std::string schedule_report_html(const schedule::ScheduleDocument& document,
                                 const ReportOptions& options) {
  const std::string three = read_script(
      options.three_js.empty() ? std::filesystem::path(CCBUILD_THREE_JS) : options.three_js);
  const std::string orbit = read_script(options.orbit_controls_js.empty()
                                            ? std::filesystem::path(CCBUILD_ORBIT_CONTROLS_JS)
                                            : options.orbit_controls_js);
  const schedule::RecordedInputs& inputs = document.inputs;
  const std::string name = inputs.name.empty() ? inputs.building : inputs.name;
  nlohmann::ordered_json schedule = schedule::schedule_json(inputs, document.schedule);
  for (const auto& note : options.notes) schedule["warnings"].push_back(note);
  for (const auto& w : options.anchor_what_ifs)
    schedule["what_if_anchors"].push_back({{"change", w.change},
                                           {"feasible", w.feasible},
                                           {"makespan_s", w.makespan_s},
                                           {"anchor_waits_s", w.anchor_waits_s}});
  // Every plan the layers use, drawn as plan-layer --svg draws one, in the building's unit.
  const floors::LengthUnit unit =
      floors::parse_length_unit(inputs.units).value_or(floors::LengthUnit::kMeter);
  // The nozzles' colours, one list for the drawings made here and the page's script.
  const std::vector<std::string> nozzle_colours = {"#0067A5", "#008856", "#F032E6", "#000080",
                                                   "#9A6324", "#469990", "#BCBD22", "#17BECF"};
  schedule["nozzle_colours"] = nozzle_colours;
  std::map<std::string, std::vector<const schedule::ScheduledLayer*>> users;
  for (const auto& l : document.schedule.layers) users[l.plan].push_back(&l);
  for (const auto& [key, plan] : document.schedule.plans) {
    if (!users.count(key)) continue;
    std::vector<detail::PlanLintel> lintels;
    for (const auto& e : document.schedule.events) {
      if (!e.lintel) continue;
      for (const auto* l : users.at(key))
        if (l->floor == e.floor && l->layer == e.layer + 1) {
          lintels.push_back({e.lintel->start_m, e.lintel->end_m,
                             "lintel over opening " + e.lintel->opening + ", set before floor " +
                                 std::to_string(l->floor) + " layer " + std::to_string(l->layer)});
          break;
        }
    }
    const auto& first = *users.at(key).front();
    schedule["plan_drawings"][key] = detail::schedule_plan_svg(
        plan,
        key + ": " + std::to_string(plan.nozzles) + " nozzle" + (plan.nozzles == 1 ? "" : "s") +
            ", " + plan.method + ", " + std::to_string(users.at(key).size()) +
            " layer(s) from floor " + std::to_string(first.floor) + " layer " +
            std::to_string(first.layer),
        unit, nozzle_colours, lintels);
  }
  // The work packages by day, for the day view: dated on a site calendar, else "day N".
  for (const DayPackage& p : work_packages(document, ExportDates{})) {
    const auto entries = [](const std::vector<DayEntry>& list) {
      nlohmann::ordered_json out = nlohmann::ordered_json::array();
      for (const DayEntry& e : list)
        out.push_back({{"kind", e.kind},
                       {"what", e.what},
                       {"who", e.who},
                       {"floor", e.floor},
                       {"start_s", e.start_s},
                       {"end_s", e.end_s},
                       {"count", e.count},
                       {"concrete_m3", e.concrete_m3},
                       {"person_h", e.person_h},
                       {"printing_h", e.printing_h},
                       {"reasons", e.reasons}});
      return out;
    };
    nlohmann::ordered_json working = nlohmann::ordered_json::array();
    for (const auto& w : p.working) working.push_back({w.from_s, w.to_s});
    schedule["day_packages"].push_back({{"date", p.date},
                                        {"weekday", p.weekday},
                                        {"from_s", p.from_s},
                                        {"to_s", p.to_s},
                                        {"working", working},
                                        {"print", entries(p.print)},
                                        {"deliver", entries(p.deliver)},
                                        {"crew", entries(p.crew)},
                                        {"machine", entries(p.machine)},
                                        {"waits", entries(p.waits)},
                                        {"stop", p.stop}});
  }
  const std::string data =
      script_safe(schedule.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  schedule = nlohmann::ordered_json();  // only its text is needed from here on
  std::string html;
  html.reserve(data.size() + three.size() + 200'000);
  html += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>";
  html += svg::escape("ccbuild schedule: " + name);
  html += "</title>\n<style>\n";
  html += detail::kReportCss;
  html += "</style>\n</head>\n<body>\n<header><h1>" + svg::escape(name) +
          "</h1><div class=\"sub\">schedule of " + svg::escape(inputs.building) + ", seed " +
          std::to_string(inputs.seed) + ", ccbuild " + svg::escape(inputs.ccbuild_version) +
          "</div></header>\n<main>\n";
  html += R"(<div id="verdict"></div>
<section id="summary"><h2>Summary</h2></section>
<section id="gantt"><h2>The build over time</h2></section>
<section id="days"><h2>Work by day</h2></section>
<section id="intervals"><h2>Intervals between layers</h2></section>
<section id="heatmap"><h2>Local intervals of one layer, on its plan</h2></section>
<section id="strength"><h2>Strength</h2></section>
<section id="toolpaths"><h2>Tool paths</h2></section>
<section id="playback"><h2>3-D playback</h2>
<div class="controls"><button id="playback-play">Play</button>
<label>speed <select id="playback-speed"><option value="60">1 min/s</option><option value="600">10 min/s</option>
<option value="2000" selected>2000x</option><option value="7200">2 h/s</option><option value="86400">1 day/s</option></select></label>
<input type="range" id="playback-slider" min="0" step="1" style="flex:1"><span id="playback-time"></span></div>
<canvas id="playback-canvas"></canvas>
<p class="hint">Drag to turn, wheel to zoom, right-drag to pan. Fresh concrete is orange.</p></section>
<pre id="console-errors" data-count="0"></pre>
</main>
<div id="tooltip" class="tooltip"></div>
<script id="schedule-data" type="application/json">)";
  html += data;
  html += "</script>\n<script>\n";
  html += script_safe(three);
  html += "\n</script>\n<script>\n";
  html += script_safe(orbit);
  html += "\n</script>\n<script>\n";
  html += script_safe(detail::kReportJs);
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace ccbuild::report
