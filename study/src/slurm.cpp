// A study as a Slurm job array: the script, its submission, its tasks' fate.

#include "ccbuild/study/slurm.hpp"

#include <cctype>
#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "process.hpp"
#include "study_files.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

/// Single-quoted for bash: a ' becomes '\''.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// A value of an #SBATCH line, quoted for sbatch's own parser (not a shell): in single
/// quotes, where a backslash escapes the next character, so \ and ' get one.
std::string sbatch_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\\' || c == '\'') out += '\\';
    out += c;
  }
  return out + "'";
}

/// Where `text` holds a control character (a newline, a tab, DEL): "U+000A at character 5";
/// empty when it holds none.
std::string control_character(const std::string& text) {
  for (std::size_t k = 0; k < text.size(); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c < 0x20 || c == 0x7f) return printf_string("U+%04X at character %zu", c, k + 1);
  }
  return "";
}

/// Slurm's time syntax: minutes, minutes:seconds, hours:minutes:seconds,
/// days-hours[:minutes[:seconds]], or infinite/unlimited.
bool slurm_time(const std::string& text) {
  static const std::regex syntax("[0-9]+(:[0-9]+){0,2}|[0-9]+-[0-9]+(:[0-9]+){0,2}",
                                 std::regex::extended);
  std::string lower;
  for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "infinite" || lower == "unlimited" || std::regex_match(text, syntax);
}

int chunks_of(const Plan& plan) {
  const int n = static_cast<int>(plan.study.variants.size());
  return (n + plan.chunk - 1) / plan.chunk;
}

fs::path jobs_file(const Plan& plan) {
  return plan.folder / "slurm" / "jobs.tsv";
}

std::vector<detail::JobLine> jobs_of(const Plan& plan) {
  return detail::read_jobs_file(jobs_file(plan), chunks_of(plan),
                                static_cast<int>(plan.study.variants.size()));
}

}  // namespace

bool slurm_available() {
  return detail::on_path("sbatch") && detail::on_path("squeue");
}

void check_sbatch_values(const SlurmOptions& o, const Study& study, const fs::path& folder,
                         const std::string& folder_flag, const fs::path& ccbuild) {
  const auto refuse_control = [](const std::string& file, int line, const std::string& field,
                                 const std::string& what, const std::string& value) {
    if (const std::string at = control_character(value); !at.empty())
      throw InputError(file, line, field,
                       what + " holds a control character (" + at +
                           "); it goes into a line of the sbatch script, which it would break");
  };
  refuse_control("", 0, "--partition", "the partition", o.partition);
  refuse_control("", 0, "--time", "the time limit", o.time);
  if (!o.time.empty() && !slurm_time(o.time))
    throw InputError("", 0, "--time",
                     "expected a time limit in Slurm's syntax (minutes, minutes:seconds, "
                     "hours:minutes:seconds, days-hours[:minutes[:seconds]] or infinite), got '" +
                         o.time + "'");
  refuse_control(study.file, study.name_line, "name", "the study's name", study.name);
  refuse_control("", 0, folder_flag, "the results folder's path",
                 fs::absolute(folder).lexically_normal().string());
  refuse_control("", 0, "ccbuild", "the ccbuild binary's path", ccbuild.string());
}

std::string sbatch_script(const Plan& plan, const SlurmOptions& o, const fs::path& ccbuild,
                          const std::vector<int>& variants) {
  check_sbatch_values(o, plan.study, plan.folder, "RESULTS", ccbuild);
  std::string array;
  if (variants.empty()) {
    array = "0-" + std::to_string(chunks_of(plan) - 1);
  } else {
    for (int v : variants) array += (array.empty() ? "" : ",") + std::to_string(v);
  }
  if (o.array_max > 0) array += "%" + std::to_string(o.array_max);
  const fs::path logs = plan.folder / "slurm";
  std::string s = "#!/bin/bash\n";
  s += "# " + plan.study.name + ": written by `ccbuild study" +
       (variants.empty() ? "" : " collect --resubmit") + "`. Each array task runs " +
       (variants.empty() ? printf_string("a chunk of up to %d variant(s)", plan.chunk)
                         : std::string("one variant, by its index")) +
       "; their results land in " + (plan.folder / "variants").string() + ".\n";
  s += "#SBATCH --job-name=" + sbatch_quoted("ccbuild-study") + "\n";
  s += "#SBATCH --array=" + array + "\n";
  s += "#SBATCH --output=" + sbatch_quoted((logs / "%A_%a.out").string()) + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + sbatch_quoted(o.partition) + "\n";
  if (!o.time.empty()) s += "#SBATCH --time=" + sbatch_quoted(o.time) + "\n";
  s += "set -eu\n";
  s += "exec " + shell_quoted(ccbuild.string()) + " study run " +
       shell_quoted(plan.folder.string()) + " " + (variants.empty() ? "--task" : "--variant") +
       " \"$SLURM_ARRAY_TASK_ID\"\n";
  return s;
}

std::vector<int> array_tasks(const Plan& plan, const std::vector<int>& variants) {
  if (!variants.empty()) return variants;
  std::vector<int> chunks(chunks_of(plan));
  for (std::size_t k = 0; k < chunks.size(); ++k) chunks[k] = static_cast<int>(k);
  return chunks;
}

std::string submit(const Plan& plan, const fs::path& script, const std::vector<int>& variants) {
  // The jobs so far read (and checked) first: a damaged jobs.tsv refuses before a job exists.
  jobs_of(plan);
  std::error_code ec;
  const std::string before =
      fs::exists(jobs_file(plan), ec) ? read_text_file(jobs_file(plan)) : std::string();
  const auto refused = [&](const std::string& why) {
    return InputError(script.string(), 0, "--submit", why + "; nothing was submitted");
  };
  detail::ProcessResult r;
  try {
    r = detail::run_process({"sbatch", "--parsable", script.string()}, {}, 120.0);
  } catch (const std::exception& e) {
    throw refused(std::string("sbatch cannot be run: ") + e.what());
  }
  std::string out = r.output;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (r.timed_out) throw refused("sbatch did not answer within 120 s");
  if (r.signal) throw refused(printf_string("sbatch was killed by signal %d", r.signal));
  std::smatch m;
  if (r.exit_code != 0 || !std::regex_search(out, m, std::regex("^([0-9]+)")))
    throw refused(printf_string("sbatch refused it (exit %d): ", r.exit_code) +
                  (out.empty() ? std::string("it said nothing") : out));
  detail::JobLine job;
  job.id = m[1];
  job.by_variant = !variants.empty();
  job.tasks = array_tasks(plan, variants);
  write_file_atomically(jobs_file(plan), before + detail::job_line_text(job), true);
  return job.id;
}

void wait_for_jobs(const Plan& plan, const std::function<void(const std::string&)>& progress,
                   const std::atomic<int>* stop) {
  std::string ids;
  for (const auto& job : jobs_of(plan)) ids += (ids.empty() ? "" : ",") + job.id;
  if (ids.empty()) return;
  const auto stop_asked = [&] { return stop && stop->load() != 0; };
  auto last = std::chrono::steady_clock::now() - std::chrono::hours(1);
  while (!stop_asked()) {
    const detail::ProcessResult r =
        detail::run_process({"squeue", "-h", "-j", ids, "-o", "%i %T"}, {}, 60.0, stop);
    std::istringstream lines(r.output);
    int running = 0, pending = 0;
    for (std::string line; std::getline(lines, line);) {
      if (line.find("RUNNING") != std::string::npos)
        ++running;
      else if (!line.empty())
        ++pending;
    }
    if (r.exit_code == 0 && running == 0 && pending == 0) return;
    if (progress && std::chrono::steady_clock::now() - last > std::chrono::seconds(10)) {
      progress(printf_string("slurm: %d array task(s) running, %d waiting (jobs %s)", running,
                             pending, ids.c_str()));
      last = std::chrono::steady_clock::now();
    }
    for (int k = 0; k < 20 && !stop_asked(); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

std::optional<TaskState> task_state(const Plan& plan, int index) {
  std::optional<TaskState> found;
  for (const auto& job : jobs_of(plan)) {  // the last job that ran the variant
    const int task = job.by_variant ? index : index / plan.chunk;
    if (std::find(job.tasks.begin(), job.tasks.end(), task) == job.tasks.end()) continue;
    TaskState s;
    s.job = job.id + "_" + std::to_string(task);
    s.log = plan.folder / "slurm" / (s.job + ".out");
    // sacct where the cluster keeps accounts; else scontrol while Slurm remembers the job.
    detail::ProcessResult r =
        detail::run_process({"sacct", "-n", "-P", "-X", "-j", s.job, "-o", "State"}, {}, 60.0);
    std::string state = r.exit_code == 0 ? r.output.substr(0, r.output.find('\n')) : "";
    if (state.empty()) {
      r = detail::run_process({"scontrol", "show", "job", "-o", s.job}, {}, 60.0);
      std::smatch m;
      if (r.exit_code == 0 && std::regex_search(r.output, m, std::regex("JobState=([A-Z_]+)")))
        state = m[1];
    }
    s.state = state.empty()
                  ? "not in Slurm's records (cancelled before it started, or forgotten since)"
                  : state.substr(0, state.find(' '));
    found = s;
  }
  return found;
}

}  // namespace ccbuild::study
