#pragma once
// What a dispatch run checks before anything starts, besides the schedule itself: the
// faults to inject (their grammar, within what ccbuild-sim accepts, and against the
// schedule's machines, layers and climbs), the folder of machine records belonging to this
// schedule, and the folders of the journal and the records writable (docs/dispatch.md).
// Errors name the flag of `ccbuild dry-run` that gave the value (--inject, --state-dir).

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/climb/fit.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/dispatch/dispatch_jobs.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::dispatch {

/// One machine fault --inject asks for.
struct MachineFault {
  std::string item;          ///< as the user wrote it, for messages
  std::string name;          ///< clog, pin, crash, stall
  std::string machine;       ///< gantry-1 unless MACHINE@ named another
  int floor = 0, layer = 0;  ///< clog
  long count = 0;            ///< pin, crash
  double at_s = 0.0;         ///< stall
};

/// What --inject asks for: network faults with their probabilities, and machine faults
/// with the machine they happen on.
struct InjectedFaults {
  std::vector<std::pair<std::string, double>> network;  ///< drop, duplicate, reorder, delay
  std::vector<MachineFault> machine;
  /// machine -> its ccbuild-sim flags ("--clog-at", "0:3"), ...
  std::map<std::string, std::vector<std::string>> flags() const {
    std::map<std::string, std::vector<std::string>> out;
    for (const auto& f : machine) {
      auto& args = out[f.machine];
      if (f.name == "clog")
        args.insert(args.end(), {"--clog-at", printf_string("%d:%d", f.floor, f.layer)});
      if (f.name == "pin") args.insert(args.end(), {"--pin-failures", std::to_string(f.count)});
      if (f.name == "crash") args.insert(args.end(), {"--crash-after", std::to_string(f.count)});
      if (f.name == "stall")
        args.insert(args.end(), {"--stall-at", printf_string("%.17g", f.at_s)});
    }
    return out;
  }
};

/// --inject "drop=0.1,duplicate=0.1,reorder=0.1,clog=0:3,pin=1,crash=5,stall=gantry-2@60":
/// each fault and its value, within what ccbuild-sim accepts. Throws InputError (field
/// --inject) for anything else; check_injected() then holds it against the schedule.
InjectedFaults parse_injected(const std::string& text);

/// Refuses (InputError, field --inject) a machine fault that could never happen on this
/// schedule: on a machine it does not have, a layer that machine does not deposit, a pin
/// where nothing climbs, a crash after more jobs than the machine runs, a stall after the
/// schedule ends.
void check_injected(const InjectedFaults& inject, const schedule::ScheduleDocument& document,
                    const std::vector<DispatchJob>& jobs, const std::vector<std::string>& ids);

/// The folder of machine records (--state-dir) belongs to one schedule, named in its
/// `schedule.sha256`: records of another schedule would be taken as jobs done. Checks each
/// machine's record, so that one a machine would refuse is refused here, before anything
/// starts. Throws InputError naming the file.
void check_state_dir(const std::filesystem::path& dir, const std::vector<std::string>& ids,
                     const std::string& schedule_sha256);

/// The folder of the journal and the machines' records can be made and written, and each
/// of `files` already there appended to: else InputError (exit 2) naming it, `field` the
/// flag, before anything starts (a machine that cannot record a job would otherwise stop
/// at its first one).
void check_writable_folder(const std::filesystem::path& dir,
                           const std::vector<std::filesystem::path>& files,
                           const std::string& field);

/// The machine profile a schedule (`file`) was made with: the building's (`project`, when
/// the schedule was just made), else `machine_flag` (--machine, which must be one of the
/// files the schedule recorded), else the profile file the schedule recorded, else (an
/// older schedule) the recorded file that loads as the machine it names. Throws InputError.
std::string machine_profile_of(const schedule::ScheduleDocument& schedule, const std::string& file,
                               const std::string& machine_flag, const schedule::Project* project);

/// A fitted machine's profile and URDF in a temporary folder of the run's own, for the
/// machines to read; the folder is removed with this.
class FittedMachineFolder {
 public:
  FittedMachineFolder() = default;
  FittedMachineFolder(const FittedMachineFolder&) = delete;
  FittedMachineFolder& operator=(const FittedMachineFolder&) = delete;
  FittedMachineFolder(FittedMachineFolder&& other) noexcept;
  ~FittedMachineFolder();
  /// The profile (empty when there is no fitted machine).
  const std::filesystem::path& profile() const { return profile_; }

  /// Writes `fit`'s member when its travel is the machine the schedule `file` records
  /// (within 1 um on x, y and z): else InputError naming the field, since the building
  /// would have to be scheduled again. `family` names the family file in that message.
  static FittedMachineFolder write(const climb::FitResult& fit,
                                   const schedule::RecordedMachine& recorded,
                                   const std::string& family, const std::string& file);

  /// Where `profile` is a family, or the building was opened with one (`project`, else
  /// null for a schedule read back): the member fitted to the schedule's building, as the
  /// schedule recorded it (the building where it stood, opened again with `reopen`),
  /// written by `write`. An empty folder otherwise.
  static FittedMachineFolder of(const schedule::ScheduleDocument& schedule, const std::string& file,
                                const schedule::Project* project, const std::string& profile,
                                schedule::ProjectOptions reopen);

 private:
  std::filesystem::path folder_, profile_;
};

}  // namespace ccbuild::dispatch
