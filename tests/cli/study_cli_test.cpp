// `ccbuild study` end to end on issue 49's findings, each from inputs made here: a
// results folder whose study.json holds wrong types (exit 2 naming it, never 3), sbatch
// missing or refusing a job (exit 2, the folder as it was), a folder holding someone else's
// files (refused, nothing changed), values that would add lines to the sbatch script
// (refused by their flag), a grid too large to count (refused where the axes are).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild::testing {
namespace {
namespace fs = std::filesystem;

/// A scratch folder with a study of the house (two variants) in it; `suffix` tells apart
/// two of one test.
struct StudyScratch {
  fs::path dir;
  fs::path study;
  explicit StudyScratch(const std::string& axes = "  machine.nozzles: [1, 2]\n",
                        const std::string& more = "", const std::string& suffix = "")
      : dir(scratch_dir("study_cli",
                        ::testing::UnitTest::GetInstance()->current_test_info()->name() + suffix)),
        study(dir / "s.yaml") {
    std::ofstream(study) << "name: house\nbase:\n  building: "
                         << source_path("config/buildings/house.yaml").string() << "\n  machine: "
                         << source_path("config/machines/cc-gantry.yaml").string()
                         << "\n  material: "
                         << source_path("config/materials/standard-mix.yaml").string()
                         << "\naxes:\n"
                         << axes << more;
  }
  ~StudyScratch() { fs::remove_all(dir); }
  /// Runs `ccbuild ARGS` with `path` first on the PATH (a fake sbatch) or as the PATH.
  CommandResult run(const std::string& args, const std::string& path = "") const {
    const std::string env = path.empty() ? "" : "PATH='" + path + "' ";
    return run_shell(env + ccbuild_binary() + " " + args);
  }
};

/// Every file below `folder`: its bytes and modification time.
std::map<std::string, std::pair<std::string, fs::file_time_type>> snapshot(const fs::path& folder) {
  std::map<std::string, std::pair<std::string, fs::file_time_type>> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), folder).string()] = {slurp(entry.path()),
                                                            fs::last_write_time(entry.path())};
  return files;
}

/// A folder on the PATH with `sbatch` (that says `sbatch_says` and exits 1) and `squeue`.
fs::path fake_slurm(const fs::path& dir, const std::string& sbatch_says) {
  const fs::path bin = dir / "fake-slurm";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/sh\necho '" << sbatch_says << "' >&2\nexit 1\n";
  std::ofstream(bin / "squeue") << "#!/bin/sh\nexit 0\n";
  for (const char* tool : {"sbatch", "squeue"}) fs::permissions(bin / tool, fs::perms::owner_all);
  return bin;
}

/// Finding 1 and 8: `collect` on a study.json hand-edited to hold a wrong type exits 2 with
/// study.json's path, the line and the JSON pointer; never the internal error (exit 3).
TEST(StudyCli, CollectOnAStudyJsonOfWrongTypesExits2NamingIt) {
  const StudyScratch s;
  const fs::path results = s.dir / "r";
  ASSERT_EQ(s.run("study " + s.study.string() + " -o " + results.string() + " --slurm").exit_code,
            0);
  const fs::path file = results / "study.json";
  const auto written = nlohmann::ordered_json::parse(slurp(file));
  for (const auto& [edit, where] :
       std::vector<std::pair<std::function<void(nlohmann::ordered_json&)>, std::string>>{
           {[](auto& j) { j["chunk"] = "1"; }, ":5: /chunk: expected a whole number"},
           {[](auto& j) { j["variants"] = nlohmann::ordered_json::object(); },
            ":6: /variants: expected an array"},
           {[](auto& j) { j["variants"][0]["settings"] = {"1"}; },
            ": /variants/0/settings: expected an object"},
           {[](auto& j) { j["study_file"] = {1}; }, ":3: /study_file: expected a string"}}) {
    auto edited = written;
    edit(edited);
    std::ofstream(file, std::ios::trunc) << edited.dump(2) << "\n";
    const CommandResult r = s.run("study collect " + results.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, file.string())) << r.err;
    EXPECT_TRUE(contains(r.err, where));
    EXPECT_FALSE(contains(r.err, "internal error"));
  }
}

/// Finding 2: sbatch refusing the job is exit 2 with its words, and the folder is as it was:
/// a new one not made, an existing one (this study's, resumed) byte for byte and by date.
TEST(StudyCli, SubmitThatSbatchRefusesExits2AndLeavesTheFolderAsItWas) {
  const StudyScratch s;
  const fs::path bin = fake_slurm(s.dir, "sbatch: error: invalid partition specified: nope");
  const std::string path = bin.string() + ":/usr/bin:/bin";
  const fs::path results = s.dir / "r";
  CommandResult r =
      s.run("study " + s.study.string() + " -o " + results.string() + " --slurm --submit", path);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err,
                       "--submit: sbatch refused it (exit 1): sbatch: error: invalid "
                       "partition specified: nope; nothing was submitted"));
  EXPECT_FALSE(fs::exists(results)) << "a half-written results folder was left";
  // This study's own folder, prepared before (with chunks of 2; the submission asks for 1).
  ASSERT_EQ(s.run("study " + s.study.string() + " -o " + results.string() + " --slurm --chunk 2")
                .exit_code,
            0);
  std::ofstream(results / "variants" / "notes.txt") << "mine\n";
  const auto before = snapshot(results);
  r = s.run("study " + s.study.string() + " -o " + results.string() + " --slurm --submit", path);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(snapshot(results), before);
  EXPECT_FALSE(fs::exists(results / "slurm" / "jobs.tsv"));
  // collect --resubmit: its new script removed again.
  r = s.run("study collect " + results.string() + " --resubmit", path);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(results / "slurm" / "resubmit-1.sbatch"));
}

/// Finding 6: --submit without Slurm's commands writes nothing at all.
TEST(StudyCli, SubmitWithoutSlurmWritesNothing) {
  const StudyScratch s;
  const fs::path empty = s.dir / "no-slurm";
  fs::create_directories(empty);
  const fs::path results = s.dir / "r";
  const CommandResult r =
      s.run("study " + s.study.string() + " -o " + results.string() + " --slurm --submit",
            empty.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "--submit: sbatch and squeue are not on the PATH"));
  EXPECT_FALSE(fs::exists(results));
}

/// Finding 3: a folder holding files the study did not make, or another study's results, is
/// refused (exit 2, naming it, what is there and --force) with nothing changed or deleted;
/// this study's own folder is taken again (a resume); --force writes there, deleting nothing.
TEST(StudyCli, AFolderHoldingSomeoneElsesFilesIsRefusedAndKept) {
  const StudyScratch s;
  const fs::path results = s.dir / "r";
  fs::create_directories(results / "variants" / "v0001");
  std::ofstream(results / "results.csv") << "someone else's\n";
  std::ofstream(results / "variants" / "v0001" / "log.txt") << "someone else's log\n";
  auto before = snapshot(results);
  for (const std::string& how : {std::string(), std::string(" --slurm")}) {
    const CommandResult r = s.run("study " + s.study.string() + " -o " + results.string() + how);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(
        contains(r.err, results.string() + ": -o: holds files `ccbuild study` did not make"));
    EXPECT_TRUE(contains(r.err, "results.csv"));
    EXPECT_TRUE(contains(r.err, "--force"));
    EXPECT_EQ(snapshot(results), before);
  }
  // Another study's results: refused, kept.
  const StudyScratch other("  machine.nozzles: [2, 3]\n", "", "_other");
  const fs::path theirs = s.dir / "theirs";
  ASSERT_EQ(
      other.run("study " + other.study.string() + " -o " + theirs.string() + " --slurm").exit_code,
      0);
  before = snapshot(theirs);
  CommandResult r = s.run("study " + s.study.string() + " -o " + theirs.string() + " --slurm");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(
      contains(r.err, "holds the results of another study ('house', " + other.study.string()));
  EXPECT_EQ(snapshot(theirs), before);
  // Its own folder again: taken, its plan untouched (same bytes, same date).
  before = snapshot(theirs);
  r = other.run("study " + other.study.string() + " -o " + theirs.string() + " --slurm");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(snapshot(theirs).at("study.json"), before.at("study.json"));
  // --force: written there, nothing deleted.
  r = s.run("study " + s.study.string() + " -o " + results.string() + " --slurm --force");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(results / "variants" / "v0001" / "log.txt"), "someone else's log\n");
  EXPECT_EQ(slurp(results / "results.csv"), "someone else's\n");
}

/// Finding 7: a newline (any control character) in a value of the sbatch script is refused
/// by its flag before anything is written; nothing reaches the script.
TEST(StudyCli, ControlCharactersInSbatchValuesAreRefusedByTheirFlag) {
  const StudyScratch s;
  const fs::path results = s.dir / "r";
  for (const auto& [flags, flag] : std::vector<std::pair<std::string, std::string>>{
           {"--partition \"$(printf 'batch\\n#SBATCH --wrap=touch-x')\"", "--partition"},
           {"--time \"$(printf '30\\tx')\"", "--time"},
           {"--time 30min", "--time"}}) {
    const CommandResult r =
        s.run("study " + s.study.string() + " -o " + results.string() + " --slurm " + flags);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, flag + ": ")) << r.err;
    EXPECT_FALSE(fs::exists(results));
  }
  const fs::path newline = s.dir / "r\nx";
  CommandResult r = s.run("study " + s.study.string() + " -o \"$(printf '" +
                          (s.dir / "r").string() + "\\nx')\" --slurm");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "-o: the results folder's path holds a control character"));
  EXPECT_FALSE(fs::exists(newline));
  // The study's name goes into the script's comment: refused where the study file says it.
  const StudyScratch named("  machine.nozzles: [1, 2]\n", "", "_named");
  std::string text = slurp(named.study);
  text.replace(0, text.find('\n'), "name: \"house\\n#SBATCH --wrap=x\"");
  std::ofstream(named.study, std::ios::trunc) << text;
  r = named.run("study " + named.study.string() + " -o " + results.string() + " --slurm");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, named.study.string() + ":1: name: the study's name holds"));
  // Without --slurm the name is only printed: the study is not refused for it.
  EXPECT_FALSE(fs::exists(results));
}

/// Finding 5: a random sample of a grid past 2^63 - 1 combinations is refused where the axes
/// are, never printed as a negative count.
TEST(StudyCli, AGridPast2To63IsRefusedWhereTheAxesAre) {
  std::string axes;
  for (const char* key : {"machine.deposition_speed_m_s", "machine.travel_speed_m_s",
                          "machine.accel_delay_s", "machine.purge_s", "machine.lift_height_m",
                          "material.density_kg_m3", "material.min_layer_interval_s"})
    axes += std::string("  ") + key + ": {from: 1, to: 1000, step: 1}\n";
  const StudyScratch s(axes, "sample: {random: 10, seed: 1}\n");
  const fs::path results = s.dir / "r";
  const CommandResult r = s.run("study " + s.study.string() + " -o " + results.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, s.study.string() + ":"));
  EXPECT_TRUE(contains(r.err, "axes: the axes make more than 9223372036854775807 combinations"));
  EXPECT_FALSE(contains(r.err + r.out, "-9223372036854775808"));
  EXPECT_FALSE(fs::exists(results));
}

}  // namespace
}  // namespace ccbuild::testing
