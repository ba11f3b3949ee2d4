// Running a study's variants, each in a process of its own, resumably.

#include "ccbuild/study/runner.hpp"

#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <thread>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/sha256.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/study/results.hpp"
#include "process.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "ccbuild-study-plan";

nlohmann::ordered_json settings_json(const Variant& v) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& [name, value] : v.settings) out[name] = value;
  return out;
}

fs::path variant_folder(const Plan& plan, int index) {
  return plan.folder / "variants" / plan.study.variants.at(index).id;
}

/// Sets `key` ("climbing.anchor_strength_mpa") to `value` in a profile's tree.
void set_number(DocNode& root, const std::string& key, double value) {
  DocNode* node = &root;
  std::size_t begin = 0;
  while (begin <= key.size()) {
    const std::size_t dot = std::min(key.find('.', begin), key.size());
    const std::string part = key.substr(begin, dot - begin);
    DocNode* next = nullptr;
    for (auto& [k, child] : node->entries)
      if (k == part) next = &child;
    if (!next) throw InputError("", 0, key, "the profile has no key " + key);
    node = next;
    begin = dot + 1;
  }
  node->text = printf_string("%.17g", value);
  node->quoted = false;
}

/// Scalars naming a file beside the profile (its URDF) made absolute, so that the copy
/// in the variant's folder still finds them.
void absolute_files(DocNode& node, const fs::path& folder) {
  if (node.kind == DocNode::Kind::kScalar && node.quoted == false && !node.text.empty() &&
      node.text.find('/') == std::string::npos && node.text.find('.') != std::string::npos) {
    std::error_code ec;
    if (fs::is_regular_file(folder / node.text, ec))
      node.text = fs::absolute(folder / node.text).lexically_normal().string();
  }
  for (auto& [k, child] : node.entries) absolute_files(child, folder);
  for (auto& child : node.items) absolute_files(child, folder);
}

/// The profile with the variant's numbers set, written into its folder.
fs::path patched_profile(const fs::path& profile,
                         const std::vector<std::pair<std::string, double>>& keys,
                         const fs::path& out) {
  Document doc = load_document(profile);
  absolute_files(doc.root, profile.parent_path());
  for (const auto& [key, value] : keys) set_number(doc.root, key, value);
  write_file_atomically(out,
                        to_yaml(doc.root, "Written by ccbuild study from " + profile.string() +
                                              ", with this variant's numbers"),
                        true);
  return out;
}

}  // namespace

std::string inputs_sha256(const Variant& v) {
  std::string text = "ccbuild-study-variant 1\n";
  const auto file = [&](const char* what, const fs::path& path) {
    text += std::string(what) + " " + (path.empty() ? "-" : sha256_file_hex(path)) + "\n";
  };
  file("building", v.building);
  file("machine", v.machine);
  file("material", v.material);
  file("site", v.site);
  text += "objective " + v.objective + "\nseed " + std::to_string(v.seed) + "\n";
  text += printf_string("layer_time_limit_s %.17g\n", v.layer_time_limit_s);
  for (const auto& [k, value] : v.machine_keys)
    text += printf_string("machine.%s %.17g\n", k.c_str(), value);
  for (const auto& [k, value] : v.material_keys)
    text += printf_string("material.%s %.17g\n", k.c_str(), value);
  return sha256_hex(text);
}

Plan prepare(const Study& study, const fs::path& folder, int chunk, bool force) {
  Plan plan;
  plan.folder = fs::absolute(folder).lexically_normal();
  plan.study = study;
  plan.chunk = std::max(1, chunk);
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["study_file"] = fs::absolute(study.file).lexically_normal().string();
  json["name"] = study.name;
  json["chunk"] = plan.chunk;
  json["variants"] = nlohmann::ordered_json::array();
  for (const Variant& v : study.variants)
    json["variants"].push_back({{"id", v.id}, {"settings", settings_json(v)}});
  const fs::path file = plan.folder / "study.json";
  std::error_code ec;
  if (fs::exists(file, ec) && !force) {
    nlohmann::json old;
    try {
      old = nlohmann::json::parse(read_text_file(file));
    } catch (const nlohmann::json::exception&) {
    }
    if (old.value("study_file", "") != json["study_file"] ||
        old["variants"] != nlohmann::json(json["variants"]))
      throw InputError(file.string(), 0, "",
                       "the folder holds the results of another study (or of this one before its "
                       "axes changed); give another folder, or --force to start over there");
  }
  fs::create_directories(plan.folder / "variants");
  write_file_atomically(file, json.dump(2) + "\n", true);
  plan.json = std::move(json);
  return plan;
}

Plan open_plan(const fs::path& folder) {
  const fs::path file = folder / "study.json";
  const std::string text = read_text_file(file);
  nlohmann::ordered_json json;
  try {
    json = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), 0, "", std::string("not a study's plan: ") + e.what());
  }
  if (!json.is_object() || json.value("format", "") != kFormat || !json.contains("study_file"))
    throw InputError(file.string(), 0, "format", "not a study's plan (made by `ccbuild study`)");
  Plan plan;
  plan.folder = fs::absolute(folder).lexically_normal();
  plan.study = read_study(json["study_file"].get<std::string>());
  plan.chunk = json.value("chunk", 1);
  nlohmann::ordered_json now = nlohmann::ordered_json::array();
  for (const Variant& v : plan.study.variants)
    now.push_back({{"id", v.id}, {"settings", settings_json(v)}});
  if (now != json["variants"])
    throw InputError(json["study_file"].get<std::string>(), 0, "axes",
                     "the study file changed since " + file.string() +
                         " was written; run `ccbuild study` on it again");
  plan.json = std::move(json);
  return plan;
}

bool finished(const Plan& plan, int index) {
  const fs::path result = variant_folder(plan, index) / "result.json";
  std::error_code ec;
  if (!fs::is_regular_file(result, ec)) return false;
  try {
    const auto json = nlohmann::json::parse(read_text_file(result));
    const std::string status = json.value("status", "");
    if (status != "feasible" && status != "infeasible") return false;
    if (json.value("inputs_sha256", "") != inputs_sha256(plan.study.variants.at(index)))
      return false;
    // The files the schedule read besides those (plans, URDFs) unchanged too.
    schedule::ReadScheduleOptions read;
    read.inputs = schedule::RecordedInputCheck::kRefuseChangedOrMissing;
    schedule::read_schedule(variant_folder(plan, index) / "schedule.json", read);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

Outcome run_variant(const Plan& plan, int index, const RunOptions& options) {
  const Variant& v = plan.study.variants.at(index);
  Outcome outcome;
  if (finished(plan, index)) {
    outcome.skipped = true;
    outcome.status =
        nlohmann::json::parse(read_text_file(variant_folder(plan, index) / "result.json"))
            .value("status", "");
    return outcome;
  }
  const fs::path dir = variant_folder(plan, index);
  fs::create_directories(dir);
  const fs::path log = dir / "log.txt";
  std::error_code ec;
  fs::remove(log, ec);
  fs::remove(dir / "result.json", ec);
  fs::remove(dir / "schedule.json", ec);
  std::vector<std::string> argv = {options.ccbuild.string(), "schedule", v.building.string()};
  fs::path machine = v.machine, material = v.material;
  nlohmann::ordered_json result;
  result["id"] = v.id;
  result["index"] = index;
  result["inputs_sha256"] = inputs_sha256(v);
  result["settings"] = settings_json(v);
  const auto start = std::chrono::steady_clock::now();
  try {
    if (!v.machine_keys.empty())
      machine = patched_profile(v.machine, v.machine_keys, dir / "machine.yaml");
    if (!v.material_keys.empty())
      material = patched_profile(v.material, v.material_keys, dir / "material.yaml");
  } catch (const std::exception& e) {
    result["status"] = "failed";
    result["reason"] = std::string("the variant's profile cannot be written: ") + e.what();
  }
  if (!result.contains("status")) {
    if (!machine.empty()) argv.insert(argv.end(), {"--machine", machine.string()});
    if (!material.empty()) argv.insert(argv.end(), {"--material", material.string()});
    if (!v.site.empty()) argv.insert(argv.end(), {"--site", v.site.string()});
    argv.insert(argv.end(), {"--objective", v.objective, "--seed", std::to_string(v.seed), "--jobs",
                             "1", "--quiet", "--no-compare", "--layer-time-limit",
                             printf_string("%.17g", v.layer_time_limit_s), "-o",
                             (dir / "schedule.json").string(), "--force"});
    {
      std::ofstream header(log, std::ios::app);
      header << "$";
      for (const auto& a : argv) header << " " << a;
      header << "\n";
    }
    detail::ProcessResult r;
    try {
      r = detail::run_process(argv, log, plan.study.variant_timeout_s);
    } catch (const std::exception& e) {
      r.exit_code = -1;
      std::ofstream(log, std::ios::app) << "cannot start it: " << e.what() << "\n";
    }
    if (r.timed_out) {
      result["status"] = "failed";
      result["reason"] =
          printf_string("timed out after %.0f s (variant_timeout_s)", plan.study.variant_timeout_s);
    } else if (r.signal) {
      result["status"] = "failed";
      result["reason"] = printf_string("killed by signal %d (%s)", r.signal, strsignal(r.signal));
    } else if ((r.exit_code == 0 || r.exit_code == 1) &&
               fs::is_regular_file(dir / "schedule.json", ec)) {
      const auto schedule = nlohmann::json::parse(read_text_file(dir / "schedule.json"));
      result["status"] = schedule.value("feasible", false) ? "feasible" : "infeasible";
      result["measures"] = measures_of(schedule);
    } else if (r.exit_code < 0) {
      result["status"] = "failed";
      result["reason"] = "ccbuild schedule could not be started (its log says why)";
    } else {
      result["status"] = "failed";
      result["reason"] =
          printf_string("ccbuild schedule exited %d%s (its log says why)", r.exit_code,
                        r.exit_code == 2   ? ", bad input"
                        : r.exit_code == 3 ? ", an internal error"
                                           : "");
    }
  }
  outcome.status = result["status"];
  outcome.reason = result.value("reason", "");
  outcome.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(dir / "result.json", result.dump(2) + "\n", true);
  return outcome;
}

bool write_report(const Plan& plan, int index, const RunOptions& options) {
  const fs::path dir = variant_folder(plan, index);
  const detail::ProcessResult r =
      detail::run_process({options.ccbuild.string(), "report", (dir / "schedule.json").string(),
                           "-o", (dir / "report.html").string(), "--force"},
                          dir / "log.txt", plan.study.variant_timeout_s);
  return r.exit_code == 0;
}

void run_variants(const Plan& plan, const std::vector<int>& indices, int jobs,
                  const RunOptions& options,
                  const std::function<void(int, const Outcome&)>& progress) {
  std::atomic<std::size_t> next{0};
  std::mutex told;
  const auto worker = [&] {
    for (std::size_t k; (k = next++) < indices.size();) {
      Outcome outcome;
      try {
        outcome = run_variant(plan, indices[k], options);
      } catch (const std::exception& e) {  // its folder cannot be written: say so, go on
        outcome.status = "failed";
        outcome.reason = e.what();
      }
      std::lock_guard<std::mutex> lock(told);
      if (progress) progress(indices[k], outcome);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < std::max(1, jobs); ++t) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
}

}  // namespace ccbuild::study
