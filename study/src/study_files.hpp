#pragma once
// The files a study writes and reads back, each read typed: <results>/study.json (the
// plan), variants/<id>/result.json (a variant's outcome), slurm/jobs.tsv (the jobs
// submitted) and the measures of a variant's schedule.json. A damaged or hand-edited file
// is an InputError naming the file, the line and the JSON pointer (or the column), and
// what was expected; never an exception of the JSON library (an internal error).
// Internal to the study library.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccbuild/common/json_reader.hpp"
#include "ccbuild/study/runner.hpp"

namespace ccbuild::study::detail {

/// study.json's "format".
inline constexpr const char* kPlanFormat = "ccbuild-study-plan";

/// study.json: what `ccbuild study` prepared.
struct PlanFile {
  std::string study_file;   ///< absolute
  int study_file_line = 0;  ///< where study.json names it (read_plan_file), for messages
  std::string name;
  int chunk = 1;  ///< variants per Slurm array task
  struct Entry {
    std::string id;
    std::vector<std::pair<std::string, std::string>> settings;  ///< axis name, value
    /// The same id and settings. Settings are compared by name: read back, an object's
    /// members come in the reader's order, not the file's.
    bool operator==(const Entry& other) const;
    bool operator!=(const Entry& other) const { return !(*this == other); }
  };
  std::vector<Entry> variants;
};

/// The JSON written as study.json (2-space indent, a final newline).
std::string plan_file_text(const PlanFile& plan);
/// Reads study.json. Throws InputError naming `file`, the line and the JSON pointer.
PlanFile read_plan_file(const std::filesystem::path& file);

/// A variant's result.json.
struct ResultFile {
  std::string id;
  int index = 0;
  std::string inputs_sha256;  ///< 64 hex digits
  VariantStatus status = VariantStatus::kFailed;
  std::string reason;  ///< why it failed (empty otherwise)
  /// The measures (numbers, true/false or null, by name); given for feasible and
  /// infeasible results.
  std::optional<nlohmann::ordered_json> measures;
};

/// Reads a result.json. Throws InputError naming `file`, the line and the JSON pointer.
ResultFile read_result_file(const std::filesystem::path& file);

/// One line of slurm/jobs.tsv: a job id, what its array tasks run ("task": chunks of
/// variants, "variant": one variant each) and their indices.
struct JobLine {
  std::string id;  ///< Slurm's job id, digits
  bool by_variant = false;
  std::vector<int> tasks;
};

/// The line for `job` (tab-separated, newline-terminated).
std::string job_line_text(const JobLine& job);
/// Reads slurm/jobs.tsv (none when it is missing). Tasks must lie below `tasks_max` (a
/// "task" line) or `variants_max` (a "variant" line). Throws InputError naming the file,
/// the line and the column.
std::vector<JobLine> read_jobs_file(const std::filesystem::path& file, int tasks_max,
                                    int variants_max);

/// The measures (results.hpp's measures_of) of a schedule JSON file, read typed: a value
/// of the wrong type is an InputError naming `file`, its line and its JSON pointer.
nlohmann::ordered_json measures_of_file(const std::filesystem::path& file);
/// The same of a schedule's located root (results.cpp).
nlohmann::ordered_json measures_of_located(const JsonAt& schedule);

}  // namespace ccbuild::study::detail
