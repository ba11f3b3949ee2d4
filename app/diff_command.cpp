// ccbuild diff OLD.json NEW.json: what changed between two schedules, exit 1 beyond the
// tolerance (for regression tests of schedules).

#include <iostream>
#include <memory>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/schedule/schedule_diff.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct DiffOptions {
  std::string old_file, new_file;
  std::vector<std::string> tolerances;
  int shown = 5;
};

schedule::DiffTolerance parse_tolerance(const std::vector<std::string>& texts) {
  schedule::DiffTolerance tol;
  for (const auto& text : texts) {
    const bool percent = !text.empty() && text.back() == '%';
    const bool secs = !text.empty() && text.back() == 's';
    const std::string number = percent || secs ? text.substr(0, text.size() - 1) : text;
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value) ||
        value < 0 || (!percent && !secs))
      throw InputError(
          "", 0, "--tolerance",
          "expected a time such as 5s or a share such as 0.5%, got '" + echoed(text) + "'");
    if (percent) {
      if (value > 100) throw InputError("", 0, "--tolerance", "a share is at most 100%");
      tol.relative = value / 100.0;
    } else {
      if (value > 365 * 86400.0) throw InputError("", 0, "--tolerance", "at most a year");
      tol.absolute_s = value;
    }
  }
  return tol;
}

void run_diff(const DiffOptions& o, int& exit_code) {
  const schedule::DiffTolerance tol = parse_tolerance(o.tolerances);
  // Comparing schedules made from different inputs is what diff is for: inputs changed on
  // disk since are named, not refused.
  schedule::ReadScheduleOptions read;
  read.inputs = schedule::RecordedInputCheck::kNote;
  read.allow_path_digests = true;  // regression goldens keep their paths' digests only
  const auto a = schedule::read_schedule(o.old_file, read);
  const auto b = schedule::read_schedule(o.new_file, read);
  const schedule::ScheduleDiff d = schedule::diff_schedules(a.document, b.document, tol, o.shown);
  for (const auto& n : a.notes) std::cout << "note: " << o.old_file << ": " << n << "\n";
  for (const auto& n : b.notes) std::cout << "note: " << o.new_file << ": " << n << "\n";
  for (const auto& n : d.notes) std::cout << "note: " << n << "\n";
  for (const auto& c : d.changes) std::cout << c << "\n";
  if (d.differs()) {
    std::cout << printf_string(
        "%s and %s differ: %zu changes beyond the tolerance (%d layers, %d events, %d plans)\n",
        o.old_file.c_str(), o.new_file.c_str(), d.changes.size(), d.differing_layers,
        d.differing_events, d.differing_plans);
    exit_code = kExitNo;
  } else {
    std::cout << o.old_file << " and " << o.new_file << " agree within the tolerance\n";
    exit_code = kExitOk;
  }
}

}  // namespace

void add_diff_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* command = app.add_subcommand(
      "diff",
      "Compare two schedules (from `ccbuild schedule -o`): feasibility, totals, each floor, "
      "the first differing layers and events, and the plans by key (in one schedule only, or "
      "with other timed paths). Times may move within --tolerance (absolute, or a share of "
      "the OLD value); anything else (nozzle counts, plans, layers or events in one schedule "
      "only) must be equal. Both files are read back and checked first (docs/schedule.md); "
      "input files changed since a schedule was made are noted.\n"
      "Exit code 0 when they agree, 1 when they differ beyond the tolerance, 2 when a file is "
      "not a schedule or breaks a rule (named with its place).\n"
      "Examples:\n"
      "  ccbuild diff tests/regression/house.schedule.json new.json\n"
      "  ccbuild diff old.json new.json --tolerance 0.5% --tolerance 2s");
  command->add_option("OLD", o->old_file, "The reference schedule")->required();
  command->add_option("NEW", o->new_file, "The schedule compared with it")->required();
  command->add_option("--tolerance", o->tolerances,
                      "How far a time may move: 5s (absolute), 0.5% (of its old value); both may "
                      "be given, the larger applies. Default: exact");
  command->add_option("--show", o->shown, "How many differing layers and events to list")
      ->check(integer_in(0, 1000000))
      ->capture_default_str();
  command->callback([o, &exit_code] { run_diff(*o, exit_code); });
}

}  // namespace ccbuild::cli
