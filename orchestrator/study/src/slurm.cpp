// A study as a Slurm job array: the script, its submission, its tasks' fate.

#include "ccbuild/study/slurm.hpp"

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "process.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {

/// Single-quoted for the shell.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Job {
  std::string id;
  std::string runs;  ///< "task" (chunks) or "variant"
  std::vector<int> tasks;
};

std::vector<Job> jobs_of(const Plan& plan) {
  std::vector<Job> jobs;
  std::ifstream in(plan.folder / "slurm" / "jobs.tsv");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    Job job;
    std::string tasks;
    if (!(fields >> job.id >> job.runs >> tasks)) continue;
    std::istringstream list(tasks);
    for (std::string t; std::getline(list, t, ',');) job.tasks.push_back(std::stoi(t));
    jobs.push_back(std::move(job));
  }
  return jobs;
}

int chunks_of(const Plan& plan) {
  const int n = static_cast<int>(plan.study.variants.size());
  return (n + plan.chunk - 1) / plan.chunk;
}

}  // namespace

bool slurm_available() {
  return detail::on_path("sbatch") && detail::on_path("squeue");
}

std::string sbatch_script(const Plan& plan, const SlurmOptions& o, const fs::path& ccbuild,
                          const std::vector<int>& variants) {
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
  s += "#SBATCH --job-name=" + quoted("ccbuild-study") + "\n";
  s += "#SBATCH --array=" + array + "\n";
  s += "#SBATCH --output=" + quoted((logs / "%A_%a.out").string()) + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + quoted(o.partition) + "\n";
  if (!o.time.empty()) s += "#SBATCH --time=" + quoted(o.time) + "\n";
  s += "set -eu\n";
  s += "exec " + quoted(ccbuild.string()) + " study run " + quoted(plan.folder.string()) + " " +
       (variants.empty() ? "--task" : "--variant") + " \"$SLURM_ARRAY_TASK_ID\"\n";
  return s;
}

std::vector<int> array_tasks(const Plan& plan, const std::vector<int>& variants) {
  if (!variants.empty()) return variants;
  std::vector<int> chunks(chunks_of(plan));
  for (std::size_t k = 0; k < chunks.size(); ++k) chunks[k] = static_cast<int>(k);
  return chunks;
}

std::string submit(const Plan& plan, const fs::path& script, const std::vector<int>& variants) {
  const detail::ProcessResult r =
      detail::run_process({"sbatch", "--parsable", script.string()}, {}, 120.0);
  std::string out = r.output;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  std::smatch m;
  if (r.exit_code != 0 || !std::regex_search(out, m, std::regex("^([0-9]+)")))
    throw std::runtime_error("sbatch refused " + script.string() + ": " + out);
  const std::string id = m[1];
  std::string tasks;
  for (int t : array_tasks(plan, variants)) tasks += (tasks.empty() ? "" : ",") + std::to_string(t);
  std::ofstream(plan.folder / "slurm" / "jobs.tsv", std::ios::app)
      << id << "\t" << (variants.empty() ? "task" : "variant") << "\t" << tasks << "\n";
  return id;
}

void wait_for_jobs(const Plan& plan, const std::function<void(const std::string&)>& progress) {
  std::string ids;
  for (const Job& job : jobs_of(plan)) ids += (ids.empty() ? "" : ",") + job.id;
  if (ids.empty()) return;
  auto last = std::chrono::steady_clock::now() - std::chrono::hours(1);
  for (;;) {
    const detail::ProcessResult r =
        detail::run_process({"squeue", "-h", "-j", ids, "-o", "%i %T"}, {}, 60.0);
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
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
}

std::optional<TaskState> task_state(const Plan& plan, int index) {
  std::optional<TaskState> found;
  for (const Job& job : jobs_of(plan)) {  // the last job that ran the variant
    const int task = job.runs == "variant" ? index : index / plan.chunk;
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
