// What a study run does around its variants (session.hpp).

#include "ccbuild/study/session.hpp"

#include <algorithm>
#include <chrono>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/slurm.hpp"

namespace ccbuild::study {
namespace fs = std::filesystem;

namespace {
/// Set from a signal handler: lock-free.
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

extern "C" void on_stop_signal(int signal_number) {
  g_stop_signal.store(signal_number);
}
}  // namespace

std::atomic<int>& stop_signal() {
  return g_stop_signal;
}

StopOnSignals::StopOnSignals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (std::size_t k = 0; k < kSignals.size(); ++k) ::sigaction(kSignals[k], &action, &before_[k]);
}

StopOnSignals::~StopOnSignals() {
  for (std::size_t k = 0; k < kSignals.size(); ++k) ::sigaction(kSignals[k], &before_[k], nullptr);
}

void Rollback::file(const fs::path& path) {
  std::error_code ec;
  Saved saved{path, std::nullopt, {}};
  if (fs::is_regular_file(path, ec)) {
    saved.bytes = read_text_file(path);
    saved.modified = fs::last_write_time(path, ec);
  }
  files_.push_back(std::move(saved));
}
void Rollback::folder(const fs::path& path) {
  std::error_code ec;
  for (fs::path p = fs::absolute(path).lexically_normal();
       !fs::exists(fs::symlink_status(p, ec)) && p != p.parent_path(); p = p.parent_path())
    folders_.push_back(p);
}
void Rollback::undo(std::ostream& err) noexcept {
  std::error_code ec;
  for (auto it = files_.rbegin(); it != files_.rend(); ++it) {
    try {
      if (!it->bytes) {
        fs::remove(it->path, ec);
      } else if (!fs::is_regular_file(it->path, ec) || read_text_file(it->path) != *it->bytes) {
        write_file_atomically(it->path, *it->bytes, true);
        fs::last_write_time(it->path, it->modified, ec);
      }
    } catch (const std::exception& e) {
      err << "study: cannot put back " << it->path.string() << ": " << e.what() << "\n";
    }
  }
  std::sort(folders_.begin(), folders_.end(), [](const fs::path& a, const fs::path& b) {
    return a.string().size() > b.string().size();  // the deepest first
  });
  for (const fs::path& folder : folders_) fs::remove(folder, ec);  // only when empty
}

void run_locally(const Plan& plan, const std::vector<int>& indices, int jobs, bool quiet,
                 const fs::path& ccbuild, std::ostream& progress) {
  const auto start = std::chrono::steady_clock::now();
  std::size_t done = 0, run = 0, skipped = 0;
  RunOptions options;
  options.ccbuild = ccbuild;
  options.stop = &stop_signal();
  run_variants(plan, indices, jobs, options, [&](int index, const Outcome& o) {
    ++done;
    if (o.skipped) ++skipped;
    if (!o.skipped && !o.stopped && !o.locked) ++run;
    const std::string& id = plan.study.variants[index].id;
    if (o.locked) {  // told even when quiet: the user may think it ran here
      progress << "study: " << id << " not run here: " << o.reason << "\n";
      return;
    }
    if (quiet || o.skipped) return;  // the skipped are counted once, below
    if (o.stopped) {
      progress << "study: " << id << " stopped, not recorded\n";
      return;
    }
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t left = indices.size() - done;
    std::string eta =
        run > 0 && left > 0 ? ", about " + duration_text(elapsed_s / run * left) + " left" : "";
    progress << printf_string(
        "study: %zu of %zu variants (%s %s%s%s), %s%s\n", done, indices.size(), id.c_str(),
        o.status ? to_string(*o.status).c_str() : "", o.reason.empty() ? "" : ": ",
        o.reason.c_str(), duration_text(elapsed_s).c_str(), eta.c_str());
  });
  if (!quiet && skipped > 0)
    progress << printf_string(
        "study: %zu variant(s) finished before with the same inputs were not run again\n", skipped);
}

std::vector<int> write_results(const Plan& plan, bool slurm, const fs::path& ccbuild,
                               std::ostream& out, std::ostream& err) {
  Collected c = collect(plan);
  std::vector<int> fronts;
  for (const auto& [cost, label] : front_costs())
    for (int i : pareto_front(c, cost)) fronts.push_back(i);
  std::sort(fronts.begin(), fronts.end());
  fronts.erase(std::unique(fronts.begin(), fronts.end()), fronts.end());
  RunOptions run;
  run.ccbuild = ccbuild;
  run.stop = &stop_signal();
  for (int i : fronts) {
    std::error_code ec;
    if (fs::is_regular_file(plan.folder / "variants" / plan.study.variants[i].id / "report.html",
                            ec))
      continue;
    if (!write_report(plan, i, run))
      err << "study: no report for " << plan.study.variants[i].id
          << " (ccbuild report failed; its log says why)\n";
  }
  write_file_atomically(plan.folder / "results.csv", results_csv(plan, c), true);
  write_file_atomically(plan.folder / "results.json", results_json(plan, c), true);
  write_file_atomically(plan.folder / "results.html", results_html(plan, c), true);
  out << printf_string("%s: %zu variants: %zu feasible, %zu infeasible, %zu failed, %zu not run\n",
                       plan.study.name.c_str(), c.rows.size(), c.feasible.size(),
                       c.infeasible.size(), c.failed.size(), c.missing.size());
  for (const auto& [cost, label] : front_costs()) {
    const auto front = pareto_front(c, cost);
    if (front.empty()) continue;
    std::string ids;
    for (int i : front) ids += (ids.empty() ? "" : " ") + plan.study.variants[i].id;
    out << "  front of makespan against " << label << ": " << ids << "\n";
  }
  std::vector<int> lacking = c.failed;
  lacking.insert(lacking.end(), c.missing.begin(), c.missing.end());
  std::sort(lacking.begin(), lacking.end());
  for (int i : lacking) {
    const auto& row = c.rows[i];
    const fs::path dir = plan.folder / "variants" / plan.study.variants[i].id;
    std::string line = "  " + row["id"].get<std::string>() + " " + row["status"].get<std::string>();
    if (row.contains("reason")) line += ": " + row["reason"].get<std::string>();
    std::error_code ec;
    if (fs::exists(dir / "log.txt", ec)) line += "; log " + (dir / "log.txt").string();
    if (slurm)
      if (const auto state = task_state(plan, i))
        line += "; Slurm task " + state->job + " " + state->state + ", log " + state->log.string();
    out << line << "\n";
  }
  out << "results: " << (plan.folder / "results.csv").string() << ", results.json, results.html\n";
  return lacking;
}

SlurmSubmission prepare_slurm_study(const Study& s, const fs::path& output, int chunk, bool force,
                                    const SlurmOptions& options, bool submit,
                                    const fs::path& ccbuild, std::ostream& err) {
  const fs::path folder = fs::absolute(output).lexically_normal();
  const fs::path script = folder / "slurm" / "study.sbatch";
  // A submission sbatch refuses leaves the folder as it was.
  Rollback rollback;
  for (const fs::path& f : {folder, folder / "variants", folder / "slurm"}) rollback.folder(f);
  for (const fs::path& f : {folder / "study.json", script}) rollback.file(f);
  try {
    Plan plan = prepare(s, output, chunk, force);
    err << printf_string("study '%s': %zu variants of %lld combinations, results in %s\n",
                         s.name.c_str(), s.variants.size(), s.grid_size, plan.folder.c_str());
    std::error_code ec;
    fs::create_directories(plan.folder / "slurm", ec);
    const std::string text = sbatch_script(plan, options, ccbuild);
    if (!fs::is_regular_file(script, ec) || read_text_file(script) != text)
      write_file_atomically(script, text, true);
    fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add, ec);
    std::string job = submit ? study::submit(plan, script) : std::string();
    return {std::move(plan), script, std::move(job)};
  } catch (const InputError& e) {
    if (!submit) throw;
    rollback.undo(err);
    std::vector<Diagnostic> all = e.diagnostics();
    all.push_back({folder.string(), 0, "", "the results folder is as it was before this run"});
    throw InputError(std::move(all));
  } catch (...) {
    if (submit) rollback.undo(err);
    throw;
  }
}

std::pair<fs::path, std::string> resubmit_variants(const Plan& plan, const std::vector<int>& again,
                                                   const SlurmOptions& options,
                                                   const fs::path& ccbuild, std::ostream& err) {
  std::error_code ec;
  fs::create_directories(plan.folder / "slurm", ec);
  int earlier = 0;  // resubmit-1.sbatch, resubmit-2.sbatch, ...
  for (const auto& entry : fs::directory_iterator(plan.folder / "slurm", ec))
    if (entry.path().filename().string().rfind("resubmit-", 0) == 0) ++earlier;
  const fs::path script = plan.folder / "slurm" / printf_string("resubmit-%d.sbatch", earlier + 1);
  Rollback rollback;
  rollback.file(script);
  try {
    write_file_atomically(script, sbatch_script(plan, options, ccbuild, again), true);
    return {script, submit(plan, script, again)};
  } catch (...) {
    rollback.undo(err);
    throw;
  }
}

}  // namespace ccbuild::study
