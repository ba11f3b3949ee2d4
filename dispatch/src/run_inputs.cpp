#include "ccbuild/dispatch/run_inputs.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <tuple>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/sha256.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/sim/sim_limits.hpp"
#include "ccbuild/sim/sim_machine.hpp"

namespace ccbuild::dispatch {
namespace fs = std::filesystem;
namespace {

const char* const kInjectGrammar =
    "expected comma-separated drop=P, duplicate=P, reorder=P, delay=P (P from 0 to 0.9), "
    "clog=[MACHINE@]FLOOR:LAYER, pin=[MACHINE@]N, crash=[MACHINE@]N or stall=[MACHINE@]SECONDS";

InputError bad_inject(const std::string& item, const std::string& why) {
  return InputError("", 0, "--inject", why + " in '" + item + "'; " + kInjectGrammar);
}

template <class Number>
bool parse_whole(const std::string& text, Number& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

InjectedFaults parse_injected(const std::string& text) {
  namespace lim = sim::limits;
  InjectedFaults out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, end - at);
    at = end + 1;
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) throw bad_inject(item, "no '='");
    const std::string name = item.substr(0, eq);
    std::string value = item.substr(eq + 1);
    if (name == "drop" || name == "duplicate" || name == "reorder" || name == "delay") {
      double p = 0.0;
      if (!parse_whole(value, p) || !(p >= 0.0 && p <= 0.9))
        throw bad_inject(item, "a probability from 0 to 0.9 expected");
      for (const auto& [seen, v] : out.network)
        if (seen == name) throw bad_inject(item, name + " given twice");
      out.network.emplace_back(name, p);
      continue;
    }
    MachineFault f;
    f.item = item;
    f.name = name;
    f.machine = gantry_id(0);
    if (const std::size_t amp = value.find('@'); amp != std::string::npos) {
      f.machine = value.substr(0, amp);
      value = value.substr(amp + 1);
    }
    if (name == "clog") {
      if (!lim::parse_floor_layer(value, f.floor, f.layer))
        throw bad_inject(item, "FLOOR:LAYER expected (whole numbers from 0)");
    } else if (name == "pin" || name == "crash") {
      const long most = name == "pin" ? lim::kMaxPinFailures : lim::kMaxCrashAfterJobs;
      if (!parse_whole(value, f.count) || f.count < 1 || f.count > most)
        throw bad_inject(item, printf_string("a count from 1 to %ld expected", most));
    } else if (name == "stall") {
      if (!parse_whole(value, f.at_s) || !lim::kStallAt_s.contains(f.at_s))
        throw bad_inject(item, "a schedule time in seconds from 0 to 1e9 expected");
    } else {
      throw bad_inject(item, "unknown fault '" + name + "'");
    }
    for (const auto& seen : out.machine)
      if (seen.name == f.name && seen.machine == f.machine)
        throw bad_inject(item, name + " on " + f.machine + " given twice");
    out.machine.push_back(std::move(f));
  }
  return out;
}

void check_injected(const InjectedFaults& inject, const schedule::ScheduleDocument& document,
                    const std::vector<DispatchJob>& jobs, const std::vector<std::string>& ids) {
  std::string machines;
  for (const auto& id : ids) machines += (machines.empty() ? "" : ", ") + id;
  int inserts = 0;
  for (const auto& e : document.schedule.events)
    if (e.climb)
      for (const auto& p : e.climb->plan.phases)
        inserts += p.kind == climb::ClimbPhase::Kind::kInsert;
  for (const auto& f : inject.machine) {
    if (std::find(ids.begin(), ids.end(), f.machine) == ids.end())
      throw bad_inject(f.item,
                       "the schedule has no machine " + f.machine + " (it has " + machines + ")");
    long runs = 0;
    bool deposits = false;
    for (const auto& j : jobs) {
      if (j.machine_id != f.machine) continue;
      ++runs;
      deposits =
          deposits || (j.kind == JobKind::kDeposit && j.floor == f.floor && j.layer == f.layer);
    }
    if (f.name == "clog" && !deposits)
      throw bad_inject(f.item, printf_string("%s deposits nothing on floor %d layer %d of this "
                                             "schedule, so it cannot clog there",
                                             f.machine.c_str(), f.floor, f.layer));
    if (f.name == "pin" && inserts == 0)
      throw bad_inject(f.item, "the schedule has no climbs, so no pin is ever inserted");
    if (f.name == "pin" && f.machine != gantry_id(0))
      throw bad_inject(f.item,
                       "climbs run as jobs of " + gantry_id(0) + "; a pin can only miss there");
    if (f.name == "crash" && f.count > runs)
      throw bad_inject(f.item, printf_string("%s runs %ld jobs in this schedule, so it never "
                                             "reaches its %ld-th",
                                             f.machine.c_str(), runs, f.count));
    if (f.name == "stall" && f.at_s > document.schedule.totals.makespan_s)
      throw bad_inject(f.item, printf_string("the schedule ends at %.1f s, before the stall",
                                             document.schedule.totals.makespan_s));
  }
}

void check_state_dir(const fs::path& dir, const std::vector<std::string>& ids,
                     const std::string& schedule_sha256) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;  // made when the run starts
  const fs::path marker = dir / "schedule.sha256";
  bool records = false;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    records = records || entry.path().extension() == ".state";
  if (fs::exists(marker, ec)) {
    const std::string recorded = read_text_file(marker);
    if (recorded.substr(0, 64) != schedule_sha256)
      throw InputError(dir.string(), 0, "--state-dir",
                       "holds the machines' records of another schedule (SHA-256 " +
                           recorded.substr(0, 12) + "..., this one is " +
                           schedule_sha256.substr(0, 12) +
                           "...); give a new folder (or empty this one to start over)");
  } else if (records) {
    throw InputError(dir.string(), 0, "--state-dir",
                     "holds machine records (*.state) but names no schedule (schedule.sha256); "
                     "they cannot be matched to this schedule: give a new folder");
  }
  for (const auto& id : ids)
    if (const fs::path record = dir / (id + ".state"); fs::exists(record, ec))
      sim::read_machine_record(record);
}

void check_writable_folder(const fs::path& dir, const std::vector<fs::path>& files,
                           const std::string& field) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw InputError(dir.string(), 0, field,
                     "cannot be made a folder" + (ec ? ": " + ec.message() : std::string()) +
                         "; nothing was started");
  // A file of its own, written, synced and removed: what the journal and the machines'
  // records will do there.
  const fs::path probe = dir / (".ccbuild-write-test-" + std::to_string(::getpid()));
  {
    std::ofstream out(probe, std::ios::binary | std::ios::trunc);
    out << "ccbuild\n";
    out.flush();
    if (!out) {
      out.close();
      fs::remove(probe, ec);
      throw InputError(dir.string(), 0, field,
                       "cannot be written (" + std::string(std::strerror(errno)) +
                           "); the journal and the machines' records go there: nothing was "
                           "started");
    }
  }
  fs::remove(probe, ec);
  for (const auto& f : files) {
    if (!fs::exists(f, ec)) continue;
    std::ofstream out(f, std::ios::binary | std::ios::app);
    if (!out)
      throw InputError(
          f.string(), 0, field,
          "cannot be appended to (" + std::string(std::strerror(errno)) + "); nothing was started");
  }
}

FittedMachineFolder::FittedMachineFolder(FittedMachineFolder&& other) noexcept
    : folder_(std::move(other.folder_)), profile_(std::move(other.profile_)) {
  other.folder_.clear();
  other.profile_.clear();
}

FittedMachineFolder::~FittedMachineFolder() {
  std::error_code ec;
  if (!folder_.empty()) fs::remove_all(folder_, ec);
}

FittedMachineFolder FittedMachineFolder::write(const climb::FitResult& fit,
                                               const schedule::RecordedMachine& recorded,
                                               const std::string& family, const std::string& file) {
  const machine::MachineModel& member = fit.profile.gantry;
  for (const auto& [what, now, was] :
       {std::tuple<const char*, double, double>{"x_max_m", member.x.max_m, recorded.x_max_m},
        {"y_max_m", member.y.max_m, recorded.y_max_m},
        {"z_max_m", member.z.max_m, recorded.z_max_m}})
    if (std::abs(now - was) > 1e-6)
      throw InputError(file, 0, std::string("/inputs/machine/") + what,
                       printf_string("the machine was fitted from the family %s; fitted again "
                                     "it reaches %.6f m, where the schedule records %.6f m: "
                                     "schedule the building again",
                                     family.c_str(), now, was));
  // The profile names its URDF, which goes beside it; a name with a folder in it would
  // leave the run's own folder.
  const std::string urdf_file = fit.urdf_file;
  if (urdf_file.empty() || fs::path(urdf_file).filename() != urdf_file || urdf_file == "." ||
      urdf_file == "..")
    throw InputError(file, 0, "urdf",
                     "the fitted profile names its URDF '" + urdf_file +
                         "'; expected a file name beside the profile");
  FittedMachineFolder out;
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  if (ec) throw InputError("", 0, "TMPDIR", "no temporary folder: " + ec.message());
  out.folder_ = tmp / ("ccbuild-fitted-" + std::to_string(::getpid()));
  fs::remove_all(out.folder_, ec);
  fs::create_directories(out.folder_);
  out.profile_ = out.folder_ / "fitted.yaml";
  write_file_atomically(out.folder_ / urdf_file, fit.urdf_xml, true);
  write_file_atomically(out.profile_, fit.profile_yaml, true);
  return out;
}

std::string machine_profile_of(const schedule::ScheduleDocument& schedule, const std::string& file,
                               const std::string& machine_flag, const schedule::Project* project) {
  if (project) return project->machine->source_file;
  if (!machine_flag.empty()) {
    const std::string sum = sha256_file_hex(machine_flag);
    for (const auto& f : schedule.inputs.files)
      if (f.sha256 == sum) return machine_flag;
    throw InputError(machine_flag, 0, "--machine",
                     "is not among the files the schedule " + file +
                         " was made from; a schedule runs on its own machine");
  }
  // The profile the schedule recorded; a schedule from before it did: by its name.
  if (!schedule.inputs.machine.profile.empty()) return schedule.inputs.machine.profile;
  const std::string& name = schedule.inputs.machine.name;
  for (const auto& f : schedule.inputs.files) {
    const fs::path path = f.path;
    if (path.extension() != ".yaml" && path.extension() != ".json") continue;
    try {
      if (machine::load_machine(path).name == name) return path.string();
    } catch (const InputError&) {
    }
  }
  throw InputError(file, 0, "/inputs/machine/name",
                   "the machine profile '" + name +
                       "' is not among the schedule's files here; name it with --machine");
}

FittedMachineFolder FittedMachineFolder::of(const schedule::ScheduleDocument& schedule,
                                            const std::string& file,
                                            const schedule::Project* project,
                                            const std::string& profile,
                                            schedule::ProjectOptions reopen) {
  std::shared_ptr<const climb::FitResult> fit = project ? project->fit : nullptr;
  std::error_code ec;
  if (!fit && fs::is_regular_file(profile, ec) && machine::load_machine_profile(profile).family) {
    schedule::ProjectOptions& again = reopen;
    again.machine_profile = profile;
    again.rotation_deg = schedule.inputs.placement.rotation_rad * 180.0 / M_PI;
    fit = schedule::open_project(schedule.inputs.building, again).fit;
  }
  if (!fit) return {};
  return FittedMachineFolder::write(*fit, schedule.inputs.machine, profile, file);
}

}  // namespace ccbuild::dispatch
