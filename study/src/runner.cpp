// Running a study's variants, each in a process of its own, resumably.

#include "ccbuild/study/runner.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
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
#include "study_files.hpp"

namespace ccbuild::study {

std::string to_string(VariantStatus status) {
  switch (status) {
    case VariantStatus::kFeasible:
      return "feasible";
    case VariantStatus::kInfeasible:
      return "infeasible";
    case VariantStatus::kFailed:
      break;
  }
  return "failed";
}

std::optional<VariantStatus> variant_status_named(const std::string& name) {
  for (VariantStatus s :
       {VariantStatus::kFeasible, VariantStatus::kInfeasible, VariantStatus::kFailed})
    if (to_string(s) == name) return s;
  return std::nullopt;
}
namespace fs = std::filesystem;

namespace {

nlohmann::ordered_json settings_json(const Variant& v) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& [name, value] : v.settings) out[name] = value;
  return out;
}

fs::path variant_folder(const Plan& plan, int index) {
  return plan.folder / "variants" / plan.study.variants.at(index).id;
}

/// study.json's content for `study`.
detail::PlanFile plan_file_of(const Study& study, int chunk) {
  detail::PlanFile file;
  file.study_file = fs::absolute(study.file).lexically_normal().string();
  file.name = study.name;
  file.chunk = chunk;
  for (const Variant& v : study.variants) file.variants.push_back({v.id, v.settings});
  return file;
}

/// Makes `folder` (and its parents). Throws InputError naming it when it cannot.
void make_folder(const fs::path& folder, const std::string& flag) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder.string(), 0, flag, "cannot make the folder: " + ec.message());
}

/// An exclusive flock on a variant's lock file, taken without waiting, released when
/// destroyed. flock (not fcntl) locks belong to the open file, so the schedule the runner
/// starts holds it too (it inherits the descriptor) and the lock outlives a runner killed
/// with SIGKILL for as long as its schedule runs.
class VariantLock {
 public:
  explicit VariantLock(const fs::path& file) {
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw InputError(file.string(), 0, "",
                       std::string("cannot open the variant's lock: ") + std::strerror(errno));
    int r;
    while ((r = ::flock(fd_, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR) {
    }
    if (r == 0) {
      held_ = true;
    } else if (errno != EWOULDBLOCK) {
      const int error = errno;
      ::close(fd_);
      throw InputError(file.string(), 0, "",
                       std::string("cannot lock the variant: ") + std::strerror(error));
    }
  }
  ~VariantLock() { ::close(fd_); }
  VariantLock(const VariantLock&) = delete;
  VariantLock& operator=(const VariantLock&) = delete;

  bool held() const { return held_; }
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
  bool held_ = false;
};

bool stop_asked(const RunOptions& options) {
  return options.stop && options.stop->load() != 0;
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

void check_results_folder(const Study& study, const fs::path& folder, bool force) {
  std::error_code ec;
  const fs::file_status status = fs::status(folder, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw InputError(folder.string(), 0, "-o", "expected a folder for the results, got a file");
  if (!fs::exists(status) || force) return;
  const std::string way_out =
      "; give another folder, or --force to write there (files of the "
      "same names are replaced as the study writes them)";
  const fs::path plan_path = folder / "study.json";
  if (fs::exists(fs::symlink_status(plan_path, ec))) {
    detail::PlanFile old;
    try {
      old = detail::read_plan_file(plan_path);
    } catch (const InputError& e) {
      std::vector<Diagnostic> all = {
          {folder.string(), 0, "-o",
           "holds a study.json that is not a study's plan (below)" + way_out}};
      all.insert(all.end(), e.diagnostics().begin(), e.diagnostics().end());
      throw InputError(std::move(all));
    }
    const detail::PlanFile now = plan_file_of(study, old.chunk);
    if (old.study_file != now.study_file)
      throw InputError(folder.string(), 0, "-o",
                       "holds the results of another study ('" + old.name + "', " + old.study_file +
                           ", " + std::to_string(old.variants.size()) + " variants)" + way_out);
    if (old.variants != now.variants)
      throw InputError(folder.string(), 0, "-o",
                       "holds this study's results from before its axes changed (" +
                           std::to_string(old.variants.size()) + " variants then, " +
                           std::to_string(now.variants.size()) + " now)" + way_out);
    return;  // this study's own folder: a resume
  }
  // No plan: whatever files are there are not this study's (empty folders hold nothing).
  std::vector<std::string> found;
  auto it = fs::recursive_directory_iterator(folder, ec);
  for (; !ec && it != fs::recursive_directory_iterator() && found.size() < 4; it.increment(ec)) {
    std::error_code kind;
    if (!fs::is_directory(it->symlink_status(kind)))
      found.push_back(fs::relative(it->path(), folder, kind).string());
  }
  if (ec)
    throw InputError(
        folder.string(), 0, "-o",
        "cannot be listed (" + ec.message() + "), so what it holds is unknown" + way_out);
  if (found.empty()) return;
  std::string listed;
  for (std::size_t k = 0; k < std::min<std::size_t>(found.size(), 3); ++k)
    listed += (listed.empty() ? "" : ", ") + found[k];
  throw InputError(folder.string(), 0, "-o",
                   "holds files `ccbuild study` did not make (" + listed +
                       (found.size() > 3 ? ", ..." : "") +
                       "; no study.json says whose results they are)" + way_out);
}

Plan prepare(const Study& study, const fs::path& folder, int chunk, bool force) {
  check_results_folder(study, folder, force);
  Plan plan;
  plan.folder = fs::absolute(folder).lexically_normal();
  plan.study = study;
  plan.chunk = std::max(1, chunk);
  make_folder(plan.folder, "-o");
  // The plan first: a folder holding it is this study's, whatever happens next. A resume
  // finds the same bytes there and leaves the file as it is.
  const fs::path file = plan.folder / "study.json";
  const std::string text = detail::plan_file_text(plan_file_of(study, plan.chunk));
  std::error_code ec;
  if (!fs::is_regular_file(file, ec) || read_text_file(file) != text)
    write_file_atomically(file, text, true);
  make_folder(plan.folder / "variants", "-o");
  return plan;
}

Plan open_plan(const fs::path& folder) {
  const fs::path file = folder / "study.json";
  const detail::PlanFile written = detail::read_plan_file(file);
  Plan plan;
  plan.folder = fs::absolute(folder).lexically_normal();
  plan.chunk = written.chunk;
  try {
    plan.study = read_study(written.study_file);
  } catch (const InputError& e) {
    std::vector<Diagnostic> all = {
        {file.string(), written.study_file_line, "/study_file",
         "names the study file " + written.study_file + ", which does not read (below)"}};
    all.insert(all.end(), e.diagnostics().begin(), e.diagnostics().end());
    throw InputError(std::move(all));
  }
  if (plan_file_of(plan.study, written.chunk).variants != written.variants)
    throw InputError(written.study_file, 0, "axes",
                     "the study file changed since " + file.string() +
                         " was written; run `ccbuild study` on it again");
  return plan;
}

fs::path variant_lock_file(const Plan& plan, int index) {
  return variant_folder(plan, index) / "lock";
}

bool finished(const Plan& plan, int index) {
  const fs::path result = variant_folder(plan, index) / "result.json";
  std::error_code ec;
  if (!fs::is_regular_file(result, ec)) return false;
  try {
    const detail::ResultFile r = detail::read_result_file(result);
    const Variant& v = plan.study.variants.at(index);
    if (r.status == VariantStatus::kFailed) return false;
    if (r.id != v.id || r.index != index || r.inputs_sha256 != inputs_sha256(v)) return false;
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
  const fs::path dir = variant_folder(plan, index);
  Outcome outcome;
  const auto skipped = [&] {
    outcome.skipped = true;
    outcome.status = detail::read_result_file(dir / "result.json").status;
    return outcome;
  };
  if (stop_asked(options)) {
    outcome.stopped = true;
    return outcome;
  }
  if (finished(plan, index)) return skipped();
  make_folder(dir, "");
  const VariantLock lock(variant_lock_file(plan, index));
  if (!lock.held()) {
    outcome.locked = true;
    outcome.reason =
        "another process runs it now (it holds " + variant_lock_file(plan, index).string() + ")";
    return outcome;
  }
  if (finished(plan, index)) return skipped();  // by the process that held the lock
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
  // What it came to, written into result.json below (status, reason, measures, in order).
  std::optional<VariantStatus> status;
  std::string reason;
  std::optional<nlohmann::ordered_json> measures;
  try {
    if (!v.machine_keys.empty())
      machine = patched_profile(v.machine, v.machine_keys, dir / "machine.yaml");
    if (!v.material_keys.empty())
      material = patched_profile(v.material, v.material_keys, dir / "material.yaml");
  } catch (const std::exception& e) {
    status = VariantStatus::kFailed;
    reason = std::string("the variant's profile cannot be written: ") + e.what();
  }
  if (!status) {
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
      r = detail::run_process(argv, log, plan.study.variant_timeout_s, options.stop, lock.fd());
    } catch (const std::exception& e) {
      r.exit_code = -1;
      std::ofstream(log, std::ios::app) << "cannot start it: " << e.what() << "\n";
    }
    if (r.stopped) {  // not the variant's fault: nothing recorded, the next run runs it
      std::ofstream(log, std::ios::app) << "stopped: the study was asked to stop\n";
      outcome.stopped = true;
      outcome.reason = "stopped";
      outcome.elapsed_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return outcome;
    }
    if (r.timed_out) {
      status = VariantStatus::kFailed;
      reason =
          printf_string("timed out after %.0f s (variant_timeout_s)", plan.study.variant_timeout_s);
    } else if (r.signal) {
      status = VariantStatus::kFailed;
      reason = printf_string("killed by signal %d (%s)", r.signal, strsignal(r.signal));
    } else if ((r.exit_code == 0 || r.exit_code == 1) &&
               fs::is_regular_file(dir / "schedule.json", ec)) {
      try {
        measures = detail::measures_of_file(dir / "schedule.json");
        status = (*measures)["feasible"].get<bool>() ? VariantStatus::kFeasible
                                                     : VariantStatus::kInfeasible;
      } catch (const InputError& e) {
        status = VariantStatus::kFailed;
        reason = std::string("its schedule does not read: ") + e.what();
      }
    } else if (r.exit_code < 0) {
      status = VariantStatus::kFailed;
      reason = "ccbuild schedule could not be started (its log says why)";
    } else {
      status = VariantStatus::kFailed;
      reason = printf_string("ccbuild schedule exited %d%s (its log says why)", r.exit_code,
                             r.exit_code == 2   ? ", bad input"
                             : r.exit_code == 3 ? ", an internal error"
                                                : "");
    }
  }
  result["status"] = to_string(*status);
  if (!reason.empty()) result["reason"] = reason;
  if (measures) result["measures"] = std::move(*measures);
  outcome.status = status;
  outcome.reason = reason;
  outcome.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(dir / "result.json",
                        result.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                        true);
  return outcome;
}

bool write_report(const Plan& plan, int index, const RunOptions& options) {
  const fs::path dir = variant_folder(plan, index);
  const detail::ProcessResult r =
      detail::run_process({options.ccbuild.string(), "report", (dir / "schedule.json").string(),
                           "-o", (dir / "report.html").string(), "--force"},
                          dir / "log.txt", plan.study.variant_timeout_s, options.stop);
  return r.exit_code == 0;
}

void run_variants(const Plan& plan, const std::vector<int>& indices, int jobs,
                  const RunOptions& options,
                  const std::function<void(int, const Outcome&)>& progress) {
  std::atomic<std::size_t> next{0};
  std::mutex told;
  const auto worker = [&] {
    for (std::size_t k; (k = next++) < indices.size();) {
      if (stop_asked(options)) return;  // none started once asked to stop
      Outcome outcome;
      try {
        outcome = run_variant(plan, indices[k], options);
      } catch (const std::exception& e) {  // its folder cannot be written: say so, go on
        outcome.status = VariantStatus::kFailed;
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
