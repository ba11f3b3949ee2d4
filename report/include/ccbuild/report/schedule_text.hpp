#pragma once
// A schedule as the text `ccbuild schedule` prints: the building and site, each floor's
// layers, nozzles, times and waits by cause, the working days, each climb and what held
// it, the anchors' critical path and what-ifs when asked, the totals, the crew's
// person-hours by kind of task and the concrete (against the model's own quantities).

#include <ostream>
#include <string>
#include <vector>

#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/what_if.hpp"

namespace ccbuild::report {

struct ScheduleTextOptions {
  std::string file;      ///< the building, named in the first line
  bool what_if = false;  ///< `--what-if anchors`: each climb's anchor and the changes
  const std::vector<schedule::AnchorWhatIf>* changes = nullptr;  ///< with what_if
};

/// Writes the summary of `s`, made for `project`, to `out`.
void write_schedule_text(std::ostream& out, const schedule::Project& project,
                         const schedule::Schedule& s, const ScheduleTextOptions& options);

/// The "objectives:" line: `s` against the same building scheduled in full with the
/// other objective (reusing the plans `options.memo` holds; no progress lines).
void write_objectives_line(std::ostream& out, const schedule::Project& project,
                           const schedule::Schedule& s, const schedule::ScheduleOptions& options);

}  // namespace ccbuild::report
