// The files a study writes and reads back, read typed (study_files.hpp).

#include "study_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/json_reader.hpp"
#include "ccbuild/common/limits.hpp"
#include "ccbuild/study/study.hpp"

namespace ccbuild::study::detail {
namespace fs = std::filesystem;

namespace {

/// Longest text in a study's files: a path (PATH_MAX), a value as written, a reason.
constexpr std::size_t kMaxText = 100'000;

/// The parsed text of a JSON file the study wrote, with its located root.
struct LocatedFile {
  std::string text;
  JsonText located;
  nlohmann::json dom;
  LocatedFile(const LocatedFile&) = delete;  // `located` points into `text`
  LocatedFile(const fs::path& file, const char* what)
      : text(read_text_file(file)), located(file.string(), text) {
    check_nesting(text, file.string(), limits::kMaxNestingDepth, what);
    dom = parse_located(text, file.string());
  }
  JsonAt root() const { return JsonAt(located, dom, ""); }
};

/// A variant's id: "v" and digits.
std::string variant_id(const JsonAt& at) {
  const std::string id = at.string(32);
  if (id.size() < 2 || id[0] != 'v' || id.find_first_not_of("0123456789", 1) != std::string::npos)
    at.refuse("expected a variant's id (\"v0001\"), got \"" + id + "\"");
  return id;
}

/// An object of strings (a variant's settings: axis name, value as written).
std::vector<std::pair<std::string, std::string>> settings_of(const JsonAt& at) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, value] : at.members(kMaxAxes))
    out.emplace_back(name, value.string(kMaxText));
  return out;
}

bool is_measure(const std::string& name) {
  const auto& all = all_measures();
  return std::find(all.begin(), all.end(), name) != all.end();
}

}  // namespace

bool PlanFile::Entry::operator==(const Entry& other) const {
  auto mine = settings, theirs = other.settings;
  std::sort(mine.begin(), mine.end());
  std::sort(theirs.begin(), theirs.end());
  return id == other.id && mine == theirs;
}

std::string plan_file_text(const PlanFile& plan) {
  nlohmann::ordered_json json;
  json["format"] = kPlanFormat;
  json["study_file"] = plan.study_file;
  json["name"] = plan.name;
  json["chunk"] = plan.chunk;
  json["variants"] = nlohmann::ordered_json::array();
  for (const auto& v : plan.variants) {
    nlohmann::ordered_json settings = nlohmann::ordered_json::object();
    for (const auto& [name, value] : v.settings) settings[name] = value;
    json["variants"].push_back({{"id", v.id}, {"settings", settings}});
  }
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

PlanFile read_plan_file(const fs::path& file) {
  const LocatedFile f(file, "a study's plan");
  const JsonAt root = f.root();
  if (!root.value().is_object() || !root.value().contains("format") ||
      root.value()["format"] != kPlanFormat)
    root.refuse(std::string("not a study's plan (\"format\": \"") + kPlanFormat +
                "\", made by `ccbuild study`)");
  root.only_keys({"format", "study_file", "name", "chunk", "variants"});
  PlanFile plan;
  plan.study_file = root.at("study_file").string(kMaxText);
  plan.study_file_line = f.located.line_of("/study_file");
  if (!fs::path(plan.study_file).is_absolute())
    root.at("study_file").refuse("expected the study file's absolute path");
  plan.name = root.at("name").string(kMaxText);
  plan.chunk = static_cast<int>(root.at("chunk").integer(1, kMaxVariants));
  for (const JsonAt& v : root.at("variants").elements(static_cast<std::size_t>(kMaxVariants))) {
    v.only_keys({"id", "settings"});
    plan.variants.push_back({variant_id(v.at("id")), settings_of(v.at("settings"))});
  }
  return plan;
}

ResultFile read_result_file(const fs::path& file) {
  const LocatedFile f(file, "a variant's result");
  const JsonAt root = f.root();
  root.only_keys({"id", "index", "inputs_sha256", "settings", "status", "reason", "measures"});
  ResultFile r;
  r.id = variant_id(root.at("id"));
  r.index = static_cast<int>(root.at("index").integer(0, kMaxVariants - 1));
  r.inputs_sha256 = root.at("inputs_sha256").string(64);
  if (r.inputs_sha256.size() != 64 ||
      r.inputs_sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
    root.at("inputs_sha256").refuse("expected a SHA-256 as 64 lower-case hex digits");
  settings_of(root.at("settings"));
  const JsonAt status = root.at("status");
  const std::string word = status.string(32);
  const auto named = variant_status_named(word);
  if (!named) status.refuse("expected feasible, infeasible or failed, got \"" + word + "\"");
  r.status = *named;
  if (const auto reason = root.maybe("reason")) r.reason = reason->string(kMaxText);
  if (r.status == VariantStatus::kFailed) {
    if (const auto m = root.maybe("measures")) m->refuse("a failed variant has no measures");
    return r;
  }
  std::map<std::string, nlohmann::ordered_json> by_name;
  for (const auto& [name, value] : root.at("measures").members(all_measures().size())) {
    if (!is_measure(name)) value.refuse("unknown measure \"" + name + "\"");
    const nlohmann::json& v = value.value();
    if (!v.is_null() && !v.is_boolean() && !v.is_number())
      value.refuse("expected a number, true, false or null");
    if (v.is_number_float() && !std::isfinite(v.get<double>()))
      value.refuse("expected a finite number");
    by_name[name] = nlohmann::ordered_json(v);
  }
  nlohmann::ordered_json measures = nlohmann::ordered_json::object();
  for (const auto& name : all_measures())  // in their column order, as written
    if (by_name.count(name)) measures[name] = by_name.at(name);
  r.measures = std::move(measures);
  return r;
}

std::string job_line_text(const JobLine& job) {
  std::string line = job.id + (job.by_variant ? "\tvariant\t" : "\ttask\t");
  for (std::size_t k = 0; k < job.tasks.size(); ++k) {
    if (k > 0) line += ',';
    line += std::to_string(job.tasks[k]);
  }
  return line + "\n";
}

std::vector<JobLine> read_jobs_file(const fs::path& file, int tasks_max, int variants_max) {
  std::vector<JobLine> jobs;
  std::error_code ec;
  if (!fs::exists(file, ec)) return jobs;
  const std::string text = read_text_file(file);
  int line_number = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ++line_number;
    const auto refuse = [&](const char* column, const std::string& message) {
      throw InputError(file.string(), line_number, column, message);
    };
    std::vector<std::string> columns;
    for (std::size_t at = 0;;) {
      const std::size_t tab = std::min(line.find('\t', at), line.size());
      columns.push_back(line.substr(at, tab - at));
      if (tab == line.size()) break;
      at = tab + 1;
    }
    if (columns.size() != 3)
      refuse("", "expected 3 columns (job id, task or variant, the tasks) separated by tabs, got " +
                     std::to_string(columns.size()));
    JobLine job;
    job.id = columns[0];
    if (job.id.empty() || job.id.size() > 20 ||
        job.id.find_first_not_of("0123456789") != std::string::npos)
      refuse("job", "expected Slurm's job id (digits), got '" + job.id + "'");
    if (columns[1] != "task" && columns[1] != "variant")
      refuse("runs", "expected task or variant, got '" + columns[1] + "'");
    job.by_variant = columns[1] == "variant";
    const int max = job.by_variant ? variants_max : tasks_max;
    for (std::size_t at = 0; at <= columns[2].size();) {
      const std::size_t comma = std::min(columns[2].find(',', at), columns[2].size());
      const std::string item = columns[2].substr(at, comma - at);
      int task = -1;
      const auto [ptr, error] = std::from_chars(item.data(), item.data() + item.size(), task);
      if (item.empty() || error != std::errc() || ptr != item.data() + item.size() || task < 0 ||
          task >= max)
        refuse("tasks",
               printf_string("expected %s indices from 0 to %d separated by commas, got '%s'",
                             job.by_variant ? "variant" : "array task", max - 1, item.c_str()));
      job.tasks.push_back(task);
      at = comma + 1;
    }
    jobs.push_back(std::move(job));
  }
  return jobs;
}

nlohmann::ordered_json measures_of_file(const fs::path& file) {
  const LocatedFile f(file, "a schedule");
  return measures_of_located(f.root());
}

}  // namespace ccbuild::study::detail
