// Design studies: the study file's variants (grid order, seeded samples, ranges), its
// located errors, the inputs' digest that makes a study resumable, the measures of a
// schedule and the Pareto front; the files a study writes and reads back, read typed
// (issue 49); counts in checked integers; the results folder's owner; a variant's lock and
// a stop that ends its process group; the values of an sbatch script.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <set>
#include <thread>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/runner.hpp"
#include "ccbuild/study/slurm.hpp"
#include "ccbuild/study/study.hpp"
#include "process.hpp"
#include "run_command.hpp"
#include "study_files.hpp"
#include "test_support.hpp"

namespace ccbuild::study {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::expect_input_error;

/// A study file in a folder of its own, beside copies of the house and the bundled profiles.
struct StudyFolder {
  fs::path dir = testing::scratch_dir(
      "study", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  StudyFolder() {
    fs::copy_file(testing::source_path("config/machines/cc-gantry.yaml"), dir / "gantry.yaml");
    fs::copy_file(testing::source_path("config/materials/standard-mix.yaml"), dir / "mix.yaml");
  }
  ~StudyFolder() { fs::remove_all(dir); }
  fs::path write(const std::string& axes, const std::string& more = "") const {
    std::ofstream(dir / "s.yaml") << "name: test\nbase:\n  building: "
                                  << testing::source_path("config/buildings/house.yaml").string()
                                  << "\n  machine: gantry.yaml\n  material: mix.yaml\naxes:\n"
                                  << axes << more;
    return dir / "s.yaml";
  }
};

TEST(StudyFile, TheGridVariesTheFirstAxisSlowest) {
  StudyFolder f;
  const Study s =
      read_study(f.write("  machine.nozzles: [1, 2]\n  objective: [fewest-nozzles, shortest]\n"
                         "  material.max_layer_interval_s: {from: 1800, to: 2400, step: 300}\n"));
  ASSERT_EQ(s.variants.size(), 12u);
  EXPECT_EQ(s.grid_size, 12);
  EXPECT_EQ(s.variants[0].id, "v0001");
  EXPECT_EQ(s.variants[11].id, "v0012");
  // Both ends of the range are values: 1800, 2100, 2400.
  EXPECT_EQ(s.axes[2].values, (std::vector<std::string>{"1800", "2100", "2400"}));
  EXPECT_EQ(s.variants[0].settings[0].second, "1");
  EXPECT_EQ(s.variants[5].settings[0].second, "1");
  EXPECT_EQ(s.variants[6].settings[0].second, "2");     // the first axis changes after 2 x 3
  EXPECT_EQ(s.variants[1].settings[2].second, "2100");  // the last axis changes every time
  EXPECT_EQ(s.variants[3].objective, "shortest");
  ASSERT_EQ(s.variants[7].machine_keys.size(), 1u);
  EXPECT_EQ(s.variants[7].machine_keys[0], (std::pair<std::string, double>{"nozzles", 2.0}));
  EXPECT_EQ(s.variants[7].material_keys[0].second, 2100.0);
  EXPECT_EQ(s.variants[0].machine, fs::absolute(f.dir / "gantry.yaml").lexically_normal());
}

TEST(StudyFile, ARangeThatStopsShortOfItsEndKeepsOnlyTheStepsWithin) {
  StudyFolder f;
  // 0.15 + 2 x 0.05 lands on 0.25 within rounding: three values; to 0.249: two.
  EXPECT_EQ(
      read_study(f.write("  machine.deposition_speed_m_s: {from: 0.15, to: 0.25, step: 0.05}\n"))
          .variants.size(),
      3u);
  EXPECT_EQ(
      read_study(f.write("  machine.deposition_speed_m_s: {from: 0.15, to: 0.249, step: 0.05}\n"))
          .variants.size(),
      2u);
}

TEST(StudyFile, ARandomSampleIsTheSameForTheSameSeedAndDistinct) {
  StudyFolder f;
  const std::string axes =
      "  machine.deposition_speed_m_s: {from: 0.1, to: 0.5, step: 0.01}\n  objective: "
      "[fewest-nozzles, shortest]\n";
  const Study a = read_study(f.write(axes, "sample: {random: 20, seed: 7}\n"));
  const Study b = read_study(f.write(axes, "sample: {random: 20, seed: 7}\n"));
  const Study c = read_study(f.write(axes, "sample: {random: 20, seed: 8}\n"));
  ASSERT_EQ(a.variants.size(), 20u);
  EXPECT_EQ(a.grid_size, 82);
  std::set<std::vector<std::pair<std::string, std::string>>> seen;
  std::vector<std::vector<std::pair<std::string, std::string>>> sa, sb, sc;
  for (const auto& v : a.variants) seen.insert(v.settings), sa.push_back(v.settings);
  for (const auto& v : b.variants) sb.push_back(v.settings);
  for (const auto& v : c.variants) sc.push_back(v.settings);
  EXPECT_EQ(seen.size(), 20u);
  EXPECT_EQ(sa, sb);
  EXPECT_NE(sa, sc);
  // A sample as large as the grid is the grid.
  EXPECT_EQ(read_study(f.write(axes, "sample: {random: 82, seed: 3}\n")).variants.size(), 82u);
  const InputError over =
      expect_input_error([&] { read_study(f.write(axes, "sample: {random: 83}\n")); });
  EXPECT_TRUE(contains(over.what(), "sample.random")) << over.what();
  EXPECT_TRUE(contains(over.what(), "only 82 variants")) << over.what();
}

TEST(StudyFile, ErrorsNameTheFileTheLineAndTheField) {
  StudyFolder f;
  const auto error = [&](const std::string& axes, const std::string& more = "") {
    return std::string(expect_input_error([&] { read_study(f.write(axes, more)); }).what());
  };
  std::string e = error("  machine.nozzle: [1, 2]\n");
  EXPECT_TRUE(contains(e, "s.yaml:7")) << e;
  EXPECT_TRUE(contains(e, "has no number at `nozzle`")) << e;
  e = error("  machine.name: [a, b]\n");
  EXPECT_TRUE(contains(e, "axes.machine.name")) << e;
  e = error("  colour: [red]\n");
  EXPECT_TRUE(contains(e, "unknown axis 'colour'")) << e;
  e = error("  material: [mix.yaml, missing.yaml]\n");
  EXPECT_TRUE(contains(e, "no such file")) << e;
  EXPECT_TRUE(contains(e, "s.yaml:7")) << e;
  e = error("  machine.nozzles: [1, 1]\n");
  EXPECT_TRUE(contains(e, "listed twice")) << e;
  e = error("  machine.nozzles: [1, two]\n");
  EXPECT_TRUE(contains(e, "axes.machine.nozzles[1]")) << e;
  e = error("  machine.deposition_speed_m_s: {from: 0.1, to: 0.2, step: 0}\n");
  EXPECT_TRUE(contains(e, "step")) << e;
  e = error("  objective: [fastest]\n");
  EXPECT_TRUE(contains(e, "fewest-nozzles or shortest")) << e;
  // Five axes of 10 values and one of 11: over the limit of variants, with the way out.
  e = error(
      "  machine.deposition_speed_m_s: {from: 1, to: 10, step: 1}\n  machine.travel_speed_m_s: "
      "{from: 1, to: 10, step: 1}\n"
      "  machine.accel_delay_s: {from: 1, to: 10, step: 1}\n  machine.purge_s: {from: 1, to: 10, "
      "step: 1}\n"
      "  machine.lift_height_m: {from: 1, to: 10, step: 1}\n  seed: {from: 1, to: 11, step: 1}\n");
  EXPECT_TRUE(contains(e, "1100000 variants; at most 100000")) << e;
  EXPECT_TRUE(contains(e, "random")) << e;
  e = error("  machine.nozzles: [1]\n", "measures: [makespan_s, speed]\n");
  EXPECT_TRUE(contains(e, "unknown measure 'speed'")) << e;
}

TEST(StudyFile, TheInputsDigestFollowsTheFilesBytesAndTheSettings) {
  StudyFolder f;
  const Study s = read_study(f.write("  machine.nozzles: [1, 2]\n"));
  const std::string one = inputs_sha256(s.variants[0]);
  EXPECT_EQ(one, inputs_sha256(read_study(f.dir / "s.yaml").variants[0]));
  EXPECT_NE(one, inputs_sha256(s.variants[1]));              // another number
  std::ofstream(f.dir / "mix.yaml", std::ios::app) << "\n";  // one byte more
  EXPECT_NE(one, inputs_sha256(s.variants[0]));
}

TEST(StudyResults, MeasuresOfTheHousesSchedule) {
  const auto schedule = nlohmann::json::parse(
      read_text_file(testing::source_path("tests/regression/house.schedule.json")));
  const auto m = measures_of(schedule);
  EXPECT_EQ(m["makespan_s"].get<double>(), schedule["totals"]["makespan_s"].get<double>());
  int nozzles = 0;
  double idle = 0.0;
  for (const auto& l : schedule["layers"])
    nozzles = std::max(nozzles, l["nozzles"].get<int>()),
    idle = std::max(idle, l["max_idle_s"].get<double>());
  EXPECT_EQ(m["nozzles_max"].get<int>(), nozzles);
  EXPECT_DOUBLE_EQ(m["idle_margin_s"].get<double>(),
                   schedule["inputs"]["machine"]["nozzle_idle_limit_s"].get<double>() - idle);
  EXPECT_EQ(m.size(), all_measures().size());
  std::size_t k = 0;
  for (const auto& [key, value] : m.items()) EXPECT_EQ(key, all_measures()[k++]);
}

// A measure is what the schedule says: a value it is made of that the schedule lacks is an
// error naming where (it was taken as 0, so a study compared a variant's missing crew hours
// as none).
TEST(StudyResults, AValueAMeasureNeedsThatTheScheduleLacksIsAnErrorNotZero) {
  const auto golden = nlohmann::json::parse(
      read_text_file(testing::source_path("tests/regression/house.schedule.json")));
  for (const auto& [path, key] :
       std::vector<std::pair<std::string, std::string>>{{"/totals", "crew_h"},
                                                        {"/totals", "makespan_s"},
                                                        {"", "feasible"},
                                                        {"/layers/2", "max_idle_s"},
                                                        {"", "warnings"}}) {
    auto schedule = golden;
    schedule[nlohmann::json::json_pointer(path)].erase(key);
    const InputError e = testing::expect_input_error([&] { measures_of(schedule); });
    EXPECT_EQ(e.first().field, path) << key;
    EXPECT_TRUE(testing::contains(e.first().message, "\"" + key + "\" is missing"))
        << e.first().message;
  }
}

// Each wait counted once, under the cause that bound it: on the tower (its climbs wait
// for their anchors), the wait measures add up to the layers' and the climbs' waits.
TEST(StudyResults, WaitMeasuresCountEachCauseByItsBindingTime) {
  const auto schedule = nlohmann::json::parse(
      read_text_file(testing::source_path("tests/regression/tower.schedule.json")));
  const auto m = measures_of(schedule);
  double waited_s = 0.0, anchors_s = 0.0;
  for (const auto& l : schedule["layers"]) waited_s += l["wait_before_s"].get<double>();
  for (const auto& e : schedule["events"])
    if (e["kind"] == "climb") {
      waited_s += e["wait_before_s"].get<double>();
      for (const auto& r : e["wait_reasons"])
        if (r["kind"] == "anchor-strength") anchors_s += r["binding_s"].get<double>();
    }
  double measured_s = 0.0;
  for (const auto kind : schedule::wait_kinds()) measured_s += m[wait_measure(kind)].get<double>();
  EXPECT_NEAR(measured_s, waited_s, 1e-3);
  EXPECT_GT(anchors_s, 0.0);
  EXPECT_NEAR(m["wait_anchor_strength_s"].get<double>(), anchors_s, 1e-6);
}

TEST(StudyResults, TheParetoFrontKeepsTiesAndDropsWhatIsBeaten) {
  Collected c;
  // (cost, makespan): 0 and 1 tie; 2 is cheaper-slower's other end; 3 is beaten by 2;
  // 4 equals 2's makespan at a higher cost (beaten); 5 is infeasible.
  const std::vector<std::pair<double, double>> points = {{1, 10}, {1, 10}, {2, 9},
                                                         {2, 12}, {3, 9},  {0, 1}};
  for (std::size_t k = 0; k < points.size(); ++k) {
    nlohmann::ordered_json row;
    row["id"] = "v" + std::to_string(k);
    row["measures"] = {{"concrete_m3", points[k].first}, {"makespan_s", points[k].second}};
    c.rows.push_back(row);
    if (k < 5) c.feasible.push_back(static_cast<int>(k));
  }
  EXPECT_EQ(pareto_front(c, "concrete_m3"), (std::vector<int>{0, 1, 2}));
}

// A variant's process: its exit code, the signal that ended it (a crash), and, past its
// time, killed with every process it started (a variant that hangs cannot hold a worker or
// leave a child behind). Each is then a failed variant, listed and resubmitted.
TEST(StudyProcess, ExitCodesSignalsAndTimeoutsAreTold) {
  const fs::path dir = testing::scratch_dir("study", "process");
  const auto sh = [&](const std::string& script, double timeout_s) {
    return detail::run_process({"/bin/sh", "-c", script}, dir / "log.txt", timeout_s);
  };
  const detail::ProcessResult exited = sh("echo to the log; exit 3", 30);
  EXPECT_EQ(exited.exit_code, 3);
  EXPECT_EQ(exited.signal, 0);
  EXPECT_FALSE(exited.timed_out);
  EXPECT_TRUE(contains(testing::slurp(dir / "log.txt"), "to the log"));
  const detail::ProcessResult crashed = sh("ulimit -c 0; kill -SEGV $$", 30);
  EXPECT_EQ(crashed.signal, SIGSEGV);
  EXPECT_FALSE(crashed.timed_out);

  const auto began = std::chrono::steady_clock::now();
  const detail::ProcessResult hung =
      sh("sleep 60 & echo $! > " + (dir / "child").string() + "; wait", 1.0);
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  EXPECT_TRUE(hung.timed_out);
  EXPECT_EQ(hung.signal, SIGKILL);
  EXPECT_GE(took_s, 1.0);
  EXPECT_LT(took_s, 20.0);
  // Its child was killed with it (gone, or a zombie waiting for its new parent).
  const std::string child = testing::slurp(dir / "child");
  ASSERT_FALSE(child.empty());
  const pid_t pid = std::stoi(child);
  bool gone = false;
  for (int k = 0; k < 100 && !gone; ++k) {
    const std::string stat = testing::slurp("/proc/" + std::to_string(pid) + "/stat");
    gone = stat.empty() || contains(stat, ") Z ");
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(gone) << "pid " << pid << " still runs";
  fs::remove_all(dir);
}

// ---------------------------------------------------------------- issue 49 -------------

/// The text of line `line` (1-based) of `text`.
std::string line_of_text(const std::string& text, int line) {
  std::size_t at = 0;
  for (int k = 1; k < line && at != std::string::npos; ++k) at = text.find('\n', at) + 1;
  if (at == std::string::npos || (at == 0 && line > 1)) return "";
  return text.substr(at, text.find('\n', at) - at);
}

/// Whether `pid` no longer runs (gone, or a zombie waiting for its new parent).
bool gone(pid_t pid) {
  for (int k = 0; k < 100; ++k) {
    const std::string stat = testing::slurp("/proc/" + std::to_string(pid) + "/stat");
    if (stat.empty() || contains(stat, ") Z ")) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// Waits (up to 30 s) until `file` has at least `lines` lines.
bool wait_for_lines(const fs::path& file, std::size_t lines) {
  for (int k = 0; k < 600; ++k) {
    const std::string text = testing::slurp(file);
    if (static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) >= lines) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// A study of the house whose results folder is prepared (study.json written).
struct PreparedStudy : StudyFolder {
  fs::path results = dir / "results";
  Plan plan;
  explicit PreparedStudy(const std::string& axes = "  machine.nozzles: [1, 2]\n", int chunk = 1)
      : plan(prepare(read_study(write(axes)), results, chunk, false)) {}
};

/// study.json hand-edited: each a wrong type (or value) where the plan has another, made
/// from the file the study wrote. The error names study.json, the line of the value and its
/// JSON pointer, and says what was expected; never the JSON library's exception.
TEST(StudyFiles, AStudyJsonOfWrongTypesIsRefusedWithItsLineAndPointer) {
  const PreparedStudy p;
  const fs::path file = p.results / "study.json";
  const auto written = nlohmann::ordered_json::parse(testing::slurp(file));
  struct Case {
    std::function<void(nlohmann::ordered_json&)> edit;
    std::string pointer, expected;
  };
  const std::vector<Case> cases = {
      {[](auto& j) { j["chunk"] = "1"; }, "/chunk", "expected a whole number"},
      {[](auto& j) { j["chunk"] = 0; }, "/chunk", "must be from 1 to 100000"},
      {[](auto& j) { j["chunk"] = 1.5; }, "/chunk", "expected a whole number"},
      {[](auto& j) { j["study_file"] = 5; }, "/study_file", "expected a string"},
      {[](auto& j) { j["study_file"] = "s.yaml"; }, "/study_file", "absolute path"},
      {[](auto& j) { j["name"] = nlohmann::ordered_json::array(); }, "/name", "expected a string"},
      {[](auto& j) {
         j["variants"] = {{"v0001", 1}};
       },
       "/variants", "expected an array"},
      {[](auto& j) { j["variants"][1] = "v0002"; }, "/variants/1", "expected an object"},
      {[](auto& j) { j["variants"][1]["settings"] = {"1"}; }, "/variants/1/settings",
       "expected an object"},
      {[](auto& j) { j["variants"][0]["settings"]["machine.nozzles"] = 1; },
       "/variants/0/settings/machine.nozzles", "expected a string"},
      {[](auto& j) { j["variants"][0]["id"] = "x1"; }, "/variants/0/id", "variant's id"},
      {[](auto& j) { j["variants"][0]["id"] = nullptr; }, "/variants/0/id", "expected a string"},
      {[](auto& j) { j["chunks"] = 2; }, "/chunks", "unknown key \"chunks\""},
      {[](auto& j) { j.erase("variants"); }, "", "\"variants\" is missing"},
      {[](auto& j) { j["format"] = "ccbuild-schedule"; }, "", "not a study's plan"},
  };
  for (const Case& c : cases) {
    nlohmann::ordered_json edited = written;
    c.edit(edited);
    const std::string text = edited.dump(2) + "\n";
    std::ofstream(file, std::ios::trunc) << text;
    const InputError e = expect_input_error([&] { open_plan(p.results); });
    const Diagnostic& d = e.first();
    EXPECT_EQ(d.file, file.string()) << e.what();
    EXPECT_EQ(d.field, c.pointer) << e.what();
    EXPECT_TRUE(contains(d.message, c.expected));
    // The line is the value's (its key's, for a member).
    const std::string key = c.pointer.substr(c.pointer.rfind('/') + 1);
    ASSERT_GT(d.line, 0) << e.what();
    if (!key.empty() && !std::isdigit(static_cast<unsigned char>(key[0]))) {
      EXPECT_TRUE(contains(line_of_text(text, d.line), "\"" + key + "\"")) << e.what();
    }
  }
  // Not JSON at all, and nested past the limit: refused with the line too.
  std::ofstream(file, std::ios::trunc) << "{\n  \"format\": \"ccbuild-study-plan\",\n  oops\n}\n";
  EXPECT_EQ(expect_input_error([&] { open_plan(p.results); }).first().line, 3);
  std::ofstream(file, std::ios::trunc) << std::string(100, '[') << std::string(100, ']');
  EXPECT_TRUE(contains(expect_input_error([&] { open_plan(p.results); }).what(),
                       "nested more than 64 deep"));
}

TEST(StudyFiles, AStudyJsonNamingAStudyFileThatDoesNotReadNamesBoth) {
  const PreparedStudy p;
  const fs::path file = p.results / "study.json";
  auto edited = nlohmann::ordered_json::parse(testing::slurp(file));
  edited["study_file"] = (p.dir / "gone.yaml").string();
  std::ofstream(file, std::ios::trunc) << edited.dump(2) << "\n";
  const InputError e = expect_input_error([&] { open_plan(p.results); });
  ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
  EXPECT_EQ(e.diagnostics()[0].file, file.string());
  EXPECT_EQ(e.diagnostics()[0].line, 3);  // "format" on line 2, "study_file" on 3
  EXPECT_EQ(e.diagnostics()[0].field, "/study_file");
  EXPECT_EQ(e.diagnostics()[1].file, (p.dir / "gone.yaml").string());
}

/// A result.json of the variant, valid, as run_variant writes it.
nlohmann::ordered_json valid_result(const Plan& plan, int index) {
  const Variant& v = plan.study.variants[index];
  nlohmann::ordered_json r;
  r["id"] = v.id;
  r["index"] = index;
  r["inputs_sha256"] = inputs_sha256(v);
  r["settings"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : v.settings) r["settings"][name] = value;
  r["status"] = "feasible";
  r["measures"] = {
      {"makespan_s", 1234.5}, {"feasible", true}, {"nozzles_max", 2}, {"idle_margin_s", nullptr}};
  return r;
}

TEST(StudyFiles, AResultOfWrongTypesIsListedMissingWithItsLineAndPointer) {
  const PreparedStudy p;
  const fs::path dir = p.results / "variants" / p.plan.study.variants[0].id;
  fs::create_directories(dir);
  const fs::path file = dir / "result.json";
  std::ofstream(file) << valid_result(p.plan, 0).dump(2) << "\n";
  const detail::ResultFile read = detail::read_result_file(file);
  EXPECT_EQ(read.status, VariantStatus::kFeasible);
  ASSERT_TRUE(read.measures.has_value());
  EXPECT_EQ((*read.measures)["nozzles_max"], 2);
  struct Case {
    std::function<void(nlohmann::ordered_json&)> edit;
    std::string pointer, expected;
  };
  const std::vector<Case> cases = {
      {[](auto& j) { j["status"] = 5; }, "/status", "expected a string"},
      {[](auto& j) { j["status"] = "done"; }, "/status", "feasible, infeasible or failed"},
      {[](auto& j) { j["index"] = "0"; }, "/index", "expected a whole number"},
      {[](auto& j) { j["index"] = -1; }, "/index", "must be from 0"},
      {[](auto& j) { j["inputs_sha256"] = "xyz"; }, "/inputs_sha256", "64 lower-case hex"},
      {[](auto& j) {
         j["measures"] = {1, 2};
       },
       "/measures", "expected an object"},
      {[](auto& j) { j["measures"]["makespan_s"] = "long"; }, "/measures/makespan_s",
       "expected a number"},
      {[](auto& j) { j["measures"]["speed"] = 1; }, "/measures/speed", "unknown measure"},
      {[](auto& j) { j.erase("measures"); }, "", "\"measures\" is missing"},
      {[](auto& j) { j["settings"] = "1"; }, "/settings", "expected an object"},
  };
  for (const Case& c : cases) {
    nlohmann::ordered_json edited = valid_result(p.plan, 0);
    c.edit(edited);
    const std::string text = edited.dump(2) + "\n";
    std::ofstream(file, std::ios::trunc) << text;
    const InputError e = expect_input_error([&] { detail::read_result_file(file); });
    EXPECT_EQ(e.first().file, file.string());
    EXPECT_EQ(e.first().field, c.pointer) << e.what();
    EXPECT_GT(e.first().line, 0) << e.what();
    EXPECT_TRUE(contains(e.first().message, c.expected));
    // collect lists it as missing, saying why where it is.
    EXPECT_FALSE(finished(p.plan, 0));
    const Collected collected = collect(p.plan);
    EXPECT_EQ(collected.rows[0]["status"], "missing");
    EXPECT_EQ(collected.missing, (std::vector<int>{0, 1}));
    EXPECT_TRUE(contains(collected.rows[0]["reason"].get<std::string>(),
                         file.string() + ":" + std::to_string(e.first().line) + ": " + c.pointer))
        << collected.rows[0].dump();
  }
}

TEST(StudyFiles, AJobsFileOfWrongColumnsIsRefusedWithItsLineAndColumn) {
  const PreparedStudy p("  machine.nozzles: [1, 2, 3]\n", 2);  // two array tasks: 0, 1
  const fs::path file = p.results / "slurm" / "jobs.tsv";
  fs::create_directories(file.parent_path());
  const std::string good = "123\ttask\t0,1\n";
  std::ofstream(file) << good;
  EXPECT_EQ(detail::read_jobs_file(file, 2, 3).size(), 1u);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"abc\ttask\t0\n", "job"},      {"124\tchunk\t0\n", "runs"},
      {"124\ttask\t0,x\n", "tasks"},  {"124\ttask\t2\n", "tasks"},  // chunks are 0 and 1
      {"124\tvariant\t3\n", "tasks"},                               // variants are 0 to 2
      {"124\ttask\t-1\n", "tasks"},   {"124\ttask\t99999999999\n", "tasks"},
      {"124 task 0\n", ""},           {"\n", ""},
  };
  for (const auto& [line, column] : cases) {
    std::ofstream(file, std::ios::trunc) << good << line;
    const InputError e = expect_input_error([&] { task_state(p.plan, 0); });
    EXPECT_EQ(e.first().file, file.string());
    EXPECT_EQ(e.first().line, 2) << e.what();
    EXPECT_EQ(e.first().field, column) << e.what();
  }
}

TEST(StudyFiles, AScheduleOfWrongTypesGivesNoMeasuresButItsPointer) {
  const fs::path dir = testing::scratch_dir("study", "schedule_types");
  const std::string text =
      testing::slurp(testing::source_path("tests/regression/house.schedule.json"));
  const fs::path file = dir / "schedule.json";
  std::ofstream(file) << text;
  EXPECT_EQ(detail::measures_of_file(file).dump(), measures_of(nlohmann::json::parse(text)).dump());
  const auto schedule = nlohmann::ordered_json::parse(text);
  for (const auto& [edit, pointer] :
       std::vector<std::pair<std::function<void(nlohmann::ordered_json&)>, std::string>>{
           {[](auto& j) { j["totals"]["makespan_s"] = "long"; }, "/totals/makespan_s"},
           {[](auto& j) { j["layers"][0]["nozzles"] = 1.5; }, "/layers/0/nozzles"},
           {[](auto& j) {
              j["layers"] = {{"a", 1}};
            },
            "/layers"},
           {[](auto& j) { j["events"][0]["kind"] = 3; }, "/events/0/kind"},
           {[](auto& j) { j["feasible"] = "yes"; }, "/feasible"}}) {
    auto edited = schedule;
    edit(edited);
    std::ofstream(file, std::ios::trunc) << edited.dump(1) << "\n";
    const InputError e = expect_input_error([&] { detail::measures_of_file(file); });
    EXPECT_EQ(e.first().file, file.string());
    EXPECT_EQ(e.first().field, pointer) << e.what();
    EXPECT_GT(e.first().line, 0) << e.what();
  }
  fs::remove_all(dir);
}

/// Seven axes of 1,000 values make 10^21 combinations, past 2^63 - 1: refused where the axes
/// are (a sample too), never wrapped to a negative count. Six of 1,000 and one of 9 make
/// 9 x 10^18, under it: sampled, each variant a point of the grid.
// Found by tests/fuzz/fuzz.py (seed 3, study-00522): a profile's number written 1e-320 (a
// subnormal) passed the reader and ended the study in std::stod's out_of_range (exit 3).
TEST(StudyFile, AProfilesNumberIsReadAsEveryNumberIs) {
  StudyFolder f;
  const Study tiny = read_study(f.write("  machine.deposition_speed_m_s: [0.2, 1e-320]\n", ""));
  ASSERT_EQ(tiny.variants.size(), 2u);
  ASSERT_EQ(tiny.variants[1].machine_keys.size(), 1u);
  EXPECT_EQ(tiny.variants[1].machine_keys[0].second, 1e-320);
  const InputError e = expect_input_error(
      [&] { read_study(f.write("  material.max_layer_interval_s: [1800, 1e400]\n", "")); });
  EXPECT_EQ(e.first().line, 7) << e.what();  // the axis's line
  EXPECT_TRUE(contains(e.what(), "1e400")) << e.what();
}

TEST(StudyFile, AGridPast2To63IsRefusedNotWrapped) {
  StudyFolder f;
  const std::string six =
      "  machine.deposition_speed_m_s: {from: 1, to: 1000, step: 1}\n"
      "  machine.travel_speed_m_s: {from: 1, to: 1000, step: 1}\n"
      "  machine.accel_delay_s: {from: 1, to: 1000, step: 1}\n"
      "  machine.purge_s: {from: 1, to: 1000, step: 1}\n"
      "  machine.lift_height_m: {from: 1, to: 1000, step: 1}\n"
      "  material.density_kg_m3: {from: 1, to: 1000, step: 1}\n";
  for (const std::string& sample :
       {std::string(), std::string("sample: {random: 10, seed: 1}\n")}) {
    const InputError e = expect_input_error([&] {
      read_study(
          f.write(six + "  material.min_layer_interval_s: {from: 1, to: 1000, step: 1}\n", sample));
    });
    EXPECT_EQ(e.first().field, "axes") << e.what();
    EXPECT_EQ(e.first().line, 7) << e.what();  // where the axes begin
    EXPECT_TRUE(contains(e.what(), "more than 9223372036854775807 combinations"));
    EXPECT_FALSE(contains(e.what(), "-9223372036854775808"));
  }
  const Study nine = read_study(
      f.write(six + "  seed: {from: 1, to: 9, step: 1}\n", "sample: {random: 5, seed: 1}\n"));
  EXPECT_EQ(nine.grid_size, 9'000'000'000'000'000'000LL);
  ASSERT_EQ(nine.variants.size(), 5u);
  std::set<std::vector<std::pair<std::string, std::string>>> seen;
  for (const Variant& v : nine.variants) {
    seen.insert(v.settings);
    ASSERT_EQ(v.settings.size(), 7u);
    EXPECT_GE(v.seed, 1u);
    EXPECT_LE(v.seed, 9u);
    for (const auto& [key, value] : v.machine_keys) EXPECT_TRUE(value >= 1 && value <= 1000) << key;
  }
  EXPECT_EQ(seen.size(), 5u);
  const InputError ten = expect_input_error([&] {
    read_study(
        f.write(six + "  seed: {from: 1, to: 10, step: 1}\n", "sample: {random: 5, seed: 1}\n"));
  });
  EXPECT_TRUE(contains(ten.what(), "more than 9223372036854775807")) << ten.what();
}

/// A range's count is checked before it is cast: 1,000 values at most (1,001 refused), bounds
/// too far apart to count refused, and a step too small for its bounds (values that print
/// alike) refused; each where the range is written.
TEST(StudyFile, ARangeIsCountedBeforeItIsCast) {
  StudyFolder f;
  const auto range = [&](const std::string& r) {
    return f.write("  machine.deposition_speed_m_s: " + r + "\n");
  };
  EXPECT_EQ(read_study(range("{from: 1, to: 1000, step: 1}")).variants.size(), 1000u);
  const auto refused = [&](const std::string& r, const std::string& expected) {
    const InputError e = expect_input_error([&] { read_study(range(r)); });
    EXPECT_EQ(e.first().field, "axes.machine.deposition_speed_m_s") << e.what();
    EXPECT_EQ(e.first().line, 7) << e.what();
    EXPECT_TRUE(contains(e.what(), expected));
  };
  refused("{from: 1, to: 1001, step: 1}", "the range has 1001 values; at most 1000");
  refused("{from: -1e308, to: 1e308, step: 1}", "too many to count");
  refused("{from: 0, to: 1e300, step: 1e-300}", "too many to count");
  refused("{from: 1e15, to: 1.0000000000005e15, step: 1}", "the same at 10 significant digits");
}

TEST(StudyFile, ASeedWrittenWithAnExponentIsThatSeed) {
  StudyFolder f;
  const Study s = read_study(f.write("  seed: [1e3, 2]\n"));
  EXPECT_EQ(s.variants[0].seed, 1000u);
  EXPECT_EQ(s.variants[1].seed, 2u);
}

// The results folder: a new or empty one (empty folders inside hold nothing), or this
// study's own (a resume); anything else refused unless --force, with what is there.
TEST(StudyFolderOwner, OnlyAnEmptyFolderOrTheStudysOwnIsTaken) {
  StudyFolder f;
  // Two axes, not in alphabetical order: read back, the plan's settings are this study's.
  const Study s = read_study(f.write("  objective: [shortest]\n  machine.nozzles: [1, 2]\n"));
  const fs::path results = f.dir / "results";
  fs::create_directories(results / "variants" / "v0001");
  check_results_folder(s, results, false);  // empty folders only
  std::ofstream(results / "variants" / "v0001" / "notes.txt") << "mine\n";
  const InputError foreign = expect_input_error([&] { check_results_folder(s, results, false); });
  EXPECT_EQ(foreign.first().file, results.string());
  EXPECT_EQ(foreign.first().field, "-o");
  EXPECT_TRUE(contains(foreign.what(), "did not make (variants/v0001/notes.txt"));
  EXPECT_TRUE(contains(foreign.what(), "--force"));
  check_results_folder(s, results, true);
  fs::remove(results / "variants" / "v0001" / "notes.txt");
  // This study's own folder, again and again; another study's refused.
  prepare(s, results, 1, false);
  EXPECT_NO_THROW(check_results_folder(s, results, false)) << "its own folder refused";
  EXPECT_NO_THROW(prepare(s, results, 1, false));
  const Study other =
      read_study(f.write("  objective: [shortest]\n  machine.nozzles: [1, 2, 3]\n"));
  EXPECT_TRUE(
      contains(expect_input_error([&] { check_results_folder(other, results, false); }).what(),
               "from before its axes changed (2 variants then, 3 now)"));
  std::ofstream(f.dir / "t.yaml") << testing::slurp(f.dir / "s.yaml");
  const Study elsewhere = read_study(f.dir / "t.yaml");
  EXPECT_TRUE(
      contains(expect_input_error([&] { check_results_folder(elsewhere, results, false); }).what(),
               "holds the results of another study ('test', " + (f.dir / "s.yaml").string()));
  // A study.json that does not read: both named.
  std::ofstream(results / "study.json", std::ios::app) << "x";
  const InputError damaged = expect_input_error([&] { check_results_folder(s, results, false); });
  ASSERT_EQ(damaged.diagnostics().size(), 2u);
  EXPECT_EQ(damaged.diagnostics()[1].file, (results / "study.json").string());
}

/// A fake `ccbuild` for a variant: appends its pid to `starts`, then runs `then`.
fs::path fake_ccbuild(const fs::path& dir, const std::string& then) {
  const fs::path fake = dir / "fake-ccbuild";
  std::ofstream(fake) << "#!/bin/sh\necho $$ >> '" << (dir / "starts").string() << "'\n"
                      << then << "\n";
  fs::permissions(fake, fs::perms::owner_all);
  return fake;
}

std::vector<pid_t> starts(const fs::path& dir) {
  std::vector<pid_t> pids;
  std::istringstream lines(testing::slurp(dir / "starts"));
  for (pid_t pid; lines >> pid;) pids.push_back(pid);
  return pids;
}

/// Two runners of one variant at once (a resumed study beside a running one, or a Slurm
/// task): the second finds its lock held and does not run it.
TEST(StudyLock, AVariantRunningIsNotRunAgainBeside) {
  const PreparedStudy p;
  RunOptions options;
  options.ccbuild = fake_ccbuild(p.dir, "sleep 2; exit 2");
  Outcome first;
  std::thread runner([&] { first = run_variant(p.plan, 0, options); });
  ASSERT_TRUE(wait_for_lines(p.dir / "starts", 1));
  const Outcome second = run_variant(p.plan, 0, options);
  EXPECT_TRUE(second.locked);
  EXPECT_FALSE(second.status.has_value());
  EXPECT_TRUE(contains(second.reason, variant_lock_file(p.plan, 0).string()));
  runner.join();
  EXPECT_FALSE(first.locked);
  EXPECT_EQ(first.status, VariantStatus::kFailed);
  EXPECT_EQ(starts(p.dir).size(), 1u);
  // Another process's lock (flock on the same file) keeps it from running too.
  fs::create_directories(variant_lock_file(p.plan, 1).parent_path());
  const int fd = ::open(variant_lock_file(p.plan, 1).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  EXPECT_TRUE(run_variant(p.plan, 1, options).locked);
  ::close(fd);
  EXPECT_EQ(starts(p.dir).size(), 1u);
  EXPECT_EQ(run_variant(p.plan, 1, options).status, VariantStatus::kFailed);  // free again: run
  EXPECT_EQ(starts(p.dir).size(), 2u);
}

/// The lock belongs to the open file the variant's process inherits: a runner killed (its
/// descriptor closed) while its schedule runs leaves the variant locked until it ends.
TEST(StudyLock, TheVariantsProcessHoldsItsLockToo) {
  const fs::path dir = testing::scratch_dir("study", "lock_inherited");
  const fs::path lock = dir / "lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  std::thread child([&] {
    detail::run_process(
        {"/bin/sh", "-c", "echo started > " + (dir / "started").string() + "; sleep 2"},
        dir / "log.txt", 30, nullptr, fd);
  });
  ASSERT_TRUE(wait_for_lines(dir / "started", 1));
  ::close(fd);  // the runner's own descriptor gone
  const int other = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
  EXPECT_NE(::flock(other, LOCK_EX | LOCK_NB), 0) << "the variant's process did not hold it";
  child.join();
  EXPECT_EQ(::flock(other, LOCK_EX | LOCK_NB), 0);
  ::close(other);
  fs::remove_all(dir);
}

/// Asked to stop (a signal to the study), a variant's process group is killed and waited for,
/// and nothing is recorded for it: it is not finished, and the next run runs it.
TEST(StudyStop, AStoppedVariantLeavesNoProcessAndNoResult) {
  const PreparedStudy p;
  std::atomic<int> stop{0};
  RunOptions options;
  options.ccbuild =
      fake_ccbuild(p.dir, "sleep 60 & echo $! >> '" + (p.dir / "starts").string() + "'; wait");
  options.stop = &stop;
  std::thread asker([&] {
    if (wait_for_lines(p.dir / "starts", 2)) stop = SIGTERM;
  });
  const auto began = std::chrono::steady_clock::now();
  const Outcome o = run_variant(p.plan, 0, options);
  asker.join();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count(),
            detail::kStopGrace_s);
  EXPECT_TRUE(o.stopped);
  EXPECT_FALSE(o.status.has_value());
  EXPECT_FALSE(fs::exists(p.results / "variants" / "v0001" / "result.json"));
  const auto pids = starts(p.dir);
  ASSERT_EQ(pids.size(), 2u);
  EXPECT_TRUE(gone(pids[0])) << "the variant's process runs on";
  EXPECT_TRUE(gone(pids[1])) << "what it started runs on";
  // Once stopped, no variant is started.
  std::vector<int> told;
  run_variants(p.plan, {0, 1}, 2, options, [&](int i, const Outcome&) { told.push_back(i); });
  EXPECT_TRUE(told.empty());
  EXPECT_EQ(starts(p.dir).size(), 2u);
}

// A stop asks the group with SIGTERM, then SIGKILL after kStopGrace_s for one that ignores
// it; what the child started and left in its group goes with it either way.
TEST(StudyProcess, AStopEndsTheWholeGroup) {
  const fs::path dir = testing::scratch_dir("study", "stop");
  const auto stopped_run = [&](const std::string& script) {
    std::atomic<int> stop{0};
    fs::remove(dir / "child");
    std::thread asker([&] {
      if (wait_for_lines(dir / "child", 1)) stop = SIGTERM;
    });
    const detail::ProcessResult r =
        detail::run_process({"/bin/sh", "-c", script}, dir / "log.txt", 60, &stop);
    asker.join();
    return r;
  };
  const std::string child = "echo $! > " + (dir / "child").string();
  detail::ProcessResult r = stopped_run("sleep 60 & " + child + "; wait");
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.signal, SIGTERM);
  EXPECT_TRUE(gone(std::stoi(testing::slurp(dir / "child"))));
  // Its child ignores SIGTERM; it leaves when asked: the group is swept.
  r = stopped_run("trap 'exit 0' TERM; (trap '' TERM; exec sleep 60) & " + child + "; wait");
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(gone(std::stoi(testing::slurp(dir / "child"))));
  // Deaf to SIGTERM: SIGKILL after the grace.
  const auto began = std::chrono::steady_clock::now();
  r = stopped_run("trap '' TERM; sleep 60 & " + child + "; wait");
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count(),
            detail::kStopGrace_s);
  EXPECT_EQ(r.signal, SIGKILL);
  EXPECT_TRUE(gone(std::stoi(testing::slurp(dir / "child"))));
  fs::remove_all(dir);
}

/// A signal sent to the study and its variant alike (Slurm's scancel signals every process of
/// the job) may end the variant first: it was stopped, not failed. The same signal from
/// someone else, with no stop asked, is a failure (a crash).
TEST(StudyProcess, ASignalThatReachesTheVariantFirstIsAStop) {
  const fs::path dir = testing::scratch_dir("study", "signal_first");
  for (const bool asked : {true, false}) {
    std::atomic<int> stop{0};
    fs::remove(dir / "child");
    std::thread canceller([&] {
      if (!wait_for_lines(dir / "child", 1)) return;
      ::kill(std::stoi(testing::slurp(dir / "child")), SIGTERM);  // the variant first
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (asked) stop = SIGTERM;  // then the study
    });
    const detail::ProcessResult r = detail::run_process(
        {"/bin/sh", "-c", "echo $$ > " + (dir / "child").string() + "; exec sleep 60"},
        dir / "log.txt", 60, &stop);
    canceller.join();
    EXPECT_EQ(r.signal, SIGTERM);
    EXPECT_EQ(r.stopped, asked);
  }
  fs::remove_all(dir);
}

/// Every value that goes into an sbatch script: a control character refused by its flag
/// (a newline would add a line: `#SBATCH --wrap=...`); the rest quoted, for sbatch's own
/// parser in #SBATCH lines (a backslash escapes) and for bash in the command.
TEST(StudySlurm, ScriptValuesAreCheckedAndQuoted) {
  StudyFolder f;
  const Study s = read_study(f.write("  machine.nozzles: [1, 2]\n"));
  const fs::path ccbuild = f.dir / "it's bin" / "ccbuild";
  const auto refused = [&](SlurmOptions o, const fs::path& folder, const fs::path& binary,
                           const std::string& field, const std::string& expected) {
    const InputError e =
        expect_input_error([&] { check_sbatch_values(o, s, folder, "-o", binary); });
    EXPECT_EQ(e.first().field, field) << e.what();
    EXPECT_TRUE(contains(e.what(), expected));
  };
  SlurmOptions o;
  o.partition = "batch\n#SBATCH --wrap=rm";
  refused(o, f.dir / "r", ccbuild, "--partition", "control character (U+000A at character 6)");
  o.partition = "batch\x7f";
  refused(o, f.dir / "r", ccbuild, "--partition", "U+007F");
  o = {};
  o.time = "30\r";
  refused(o, f.dir / "r", ccbuild, "--time", "U+000D");
  o.time = "30min";
  refused(o, f.dir / "r", ccbuild, "--time", "Slurm's syntax");
  for (const char* time : {"30", "30:00", "2:00:00", "1-12", "1-0:30", "1-0:30:00", "infinite"}) {
    o.time = time;
    check_sbatch_values(o, s, f.dir / "r", "-o", ccbuild);
  }
  o = {};
  refused(o, f.dir / "r\nx", ccbuild, "-o", "the results folder's path");
  refused(o, f.dir / "r", f.dir / "bin\tx", "ccbuild", "the ccbuild binary's path");
  Study named = s;
  named.name = "a\nb";
  named.name_line = 1;
  const InputError name =
      expect_input_error([&] { check_sbatch_values({}, named, f.dir / "r", "-o", ccbuild); });
  EXPECT_EQ(name.first().file, s.file);
  EXPECT_EQ(name.first().line, 1);
  EXPECT_EQ(name.first().field, "name");

  // Quoted: a partition with a space, a quote, a backslash and a hash; a folder and a binary
  // with a quote and a space, run by bash.
  const fs::path results = f.dir / "it's results";
  const Plan plan = prepare(s, results, 1, false);
  o = {};
  o.partition = "a b'c\\d#e";
  fs::create_directories(ccbuild.parent_path());
  std::ofstream(ccbuild) << "#!/bin/sh\nfor a in \"$@\"; do echo \"[$a]\"; done\n";
  fs::permissions(ccbuild, fs::perms::owner_all);
  const std::string script = sbatch_script(plan, o, ccbuild);
  EXPECT_TRUE(contains(script, "\n#SBATCH --partition='a b\\'c\\\\d#e'\n")) << script;
  const fs::path file = f.dir / "study.sbatch";
  std::ofstream(file) << script;
  const testing::CommandResult run =
      testing::run_shell("SLURM_ARRAY_TASK_ID=0 bash '" + file.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "[study]\n[run]\n[" + plan.folder.string() + "]\n[--task]\n[0]\n");
}

}  // namespace
}  // namespace ccbuild::study
