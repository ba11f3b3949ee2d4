// Design studies: the study file's variants (grid order, seeded samples, ranges), its
// located errors, the inputs' digest that makes a study resumable, the measures of a
// schedule and the Pareto front.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <set>
#include <thread>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/study/results.hpp"
#include "ccbuild/study/study.hpp"
#include "process.hpp"
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

}  // namespace
}  // namespace ccbuild::study
