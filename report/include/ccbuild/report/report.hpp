#pragma once
// The schedule report: one self-contained HTML page (every script and style inline, no
// network) that draws a schedule JSON (docs/schedule.md): a summary with the warnings
// (an infeasible schedule says so first, and where), a Gantt of the whole build (zoom,
// pan, hover), the intervals against the material's band and one layer's local intervals
// as a heat map on its plan, the anchors' strength at every climb and the buildability
// margin over time, every distinct plan's tool path with its gantries' x/t curves, and a
// 3-D playback of the build (three.js from Debian's libjs-three, inlined).

#include <filesystem>
#include <string>
#include <vector>

#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/schedule/what_if.hpp"

namespace ccbuild::report {

struct ReportOptions {
  /// three.js (non-module build, global THREE) and its OrbitControls; Debian's
  /// libjs-three by default.
  std::filesystem::path three_js;
  std::filesystem::path orbit_controls_js;
  /// Said among the schedule's warnings (e.g. an input changed since it was made).
  std::vector<std::string> notes;
  /// Changes that would shorten the anchor waits, each scheduled (schedule/what_if.hpp):
  /// shown with the anchors' chart when given.
  std::vector<schedule::AnchorWhatIf> anchor_what_ifs;
};

/// The report of `schedule` (as build_schedule with recorded_inputs, or read_schedule,
/// give it). Throws InputError (field `three.js`) when three.js cannot be read, saying
/// what to install.
std::string schedule_report_html(const schedule::ScheduleDocument& schedule,
                                 const ReportOptions& options = {});

}  // namespace ccbuild::report
