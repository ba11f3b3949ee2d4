// Hostile input is normal input. The classes a 3,600-run mutation fuzz found (stack
// overflows, recursive destructors, aborts, hangs, memory exhaustion, silent acceptance)
// each give exit code 2 and a clear message now, never a signal, exit 3 or a hang; and a
// small seeded mutation fuzz of good inputs runs here on every build.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::run_ccbuild;
using testing::run_shell;

// A folder of generated inputs for one test, removed afterwards.
class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("ccbuild_hostile_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
  }
  ~Scratch() { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

// A file's bytes; relative paths are in the source tree, where ccbuild runs.
std::string slurp(const std::string& path) {
  std::ifstream in(fs::path(path).is_absolute() ? fs::path(path) : testing::source_path(path),
                   std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// ccbuild ARGS under a deadline: a hang is a failure (exit code 124), not a stuck test.
testing::CommandResult run_bounded(const std::string& args, int seconds = 60) {
  return run_shell("timeout " + std::to_string(seconds) + " " + testing::ccbuild_binary() + " " +
                   args);
}

void expect_refused(const testing::CommandResult& r, const std::string& message,
                    const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  EXPECT_TRUE(contains(r.err, "ccbuild: error: ")) << what;
  EXPECT_TRUE(contains(r.err, message)) << what;
  EXPECT_FALSE(contains(r.err, "internal error")) << what;
  EXPECT_TRUE(r.out.empty()) << what << ": " << r.out;
}

struct Case {
  const char* args;
  const char* message;
};

TEST(HostileInput, FixturesAreRefusedWithAReason) {
  const Case cases[] = {
      {"validate tests/data/hostile/self_alias.yaml", "nested more than 64 levels"},
      {"validate tests/data/hostile/billion_laughs.yaml",
       "more than 2000000 values once its aliases are expanded"},
      {"validate tests/data/hostile/second_document.yaml",
       "second_document.yaml:9: a second YAML document starts here"},
      {"plan-layer tests/data/hostile/huge_coordinate.yaml",
       "huge_coordinate.yaml:5: vertices[1].x: must be from -100000 to 100000 m, got 1e200 m"},
      {"validate tests/data/hostile/zero_id.yaml",
       "zero_id.yaml:3: vertices[0].id: expected a positive integer id, got '0'"},
      {"validate tests/data/hostile/sill_equals_head.yaml",
       "sill (1.200 m) must be below head (1.200 m)"},
      {"validate tests/data/hostile/tiny_layers.yaml",
       "200000 layers of 0.001 m make this building; ccbuild plans at most 100000"},
      {"layers tests/data/hostile/tall_tower.yaml",
       "the building is 25.00 m tall, and the nozzle lifts 0.15 m over its walls, but the "
       "machine's z joint reaches 18.00 m"},
      {"validate tests/data/hostile/thin_wall_refused.yaml",
       "walls[0].thickness: wall 1 is 0.050 m thick, but CC gantry, up to three nozzles lays "
       "beads 0.100 m to 0.250 m wide (bead_width_m, else nozzle_width_m), and a wall is printed "
       "at least one bead wide: make it 0.100 m or more, or use a machine whose beads reach "
       "0.050 m (the narrowest of bead_width_m), or leave it to the crew (print: {thin_walls: "
       "leave-out})"},
      {"validate tests/data/hostile/bad_wall_pattern.yaml",
       "bad_wall_pattern.yaml:4: wall_pattern: expected skins, solid or skins-with-ties"},
      {"plan-layer tests/data/hostile/high_window.yaml",
       "head (3.500 m) is above the floor height (3.000 m)"},
      {"validate tests/data/hostile/feet_opening_off_wall.yaml",
       "offset 18.000 ft + width 4.000 ft = 22.000 ft, but the wall is 20.000 ft long"},
      {"validate tests/data/plans/cottage.yaml --machine tests/data/hostile/absurd_delay.yaml",
       "absurd_delay.yaml:8: accel_delay_s: must be from 0 to 60 s, got 1e308 s"},
      {"validate tests/data/plans/cottage.yaml --machine tests/data/hostile/absurd_velocity.yaml",
       "absurd_velocity.urdf:5: joint[rail_x].limit.velocity: must be more than 0 and at most 10 "
       "m/s, got 1e+308 m/s"},
      {"layers tests/data/plans/cottage.yaml --material tests/data/hostile/absurd_material.yaml",
       "strength_curve[1].strength_mpa: must be from 0 to 200 MPa, got 1e9 MPa"},
      {"validate /dev/zero", "/dev/zero: is not a regular file"},
      {"schedule tests/data/hostile/tiny_room.yaml",
       "tiny_room.yaml:11: walls[0]: wall 1 is 0.0005 m long; walls must be longer than 0.001 m"},
      {"schedule tests/data/hostile/all_openings.yaml",
       "all_openings.yaml: nothing to print: no layer of any floor has a wall outside its "
       "openings"},
      {"plan-layer tests/data/hostile/all_openings.yaml",
       "all_openings.yaml: floor 0 layer 0 (the first layer; --layer names another) has no "
       "walls to plan"},
      {"plan-layer tests/data/hostile/all_openings.yaml --layer 2",
       "--layer: floor 0 layer 2 has no walls to plan"},
      {"validate tests/data", "tests/data: is a directory, expected a file"},
  };
  for (const auto& c : cases) expect_refused(run_bounded(c.args), c.message, c.args);
}

TEST(HostileInput, GeneratedMonstersAreRefusedWithAReason) {
  const Scratch scratch;
  // JSON nested 200,000 deep once overflowed the stack destroying its own tree.
  const std::string deep_json =
      scratch.write("deep.json", std::string(200000, '[') + std::string(200000, ']'));
  expect_refused(run_bounded("validate " + deep_json), "nested more than 64 levels deep",
                 "deep JSON");
  // The same in YAML (yaml-cpp's own guard, with our message).
  const std::string deep_yaml =
      scratch.write("deep.yaml", "a: " + std::string(200000, '[') + std::string(200000, ']'));
  expect_refused(run_bounded("validate " + deep_yaml), "too deeply nested", "deep YAML");
  // A URDF nested 50,000 deep once overflowed TinyXML's recursion inside urdfdom.
  std::string urdf = "<robot name=\"deep\">";
  for (int k = 0; k < 50000; ++k) urdf += "<link name=\"l\">";
  scratch.write("deep.urdf", urdf);
  const std::string profile = scratch.write(
      "deep-machine.yaml",
      "name: deep\nurdf: deep.urdf\njoints: {x: rail_x, y: bridge_y, z: lift_z, nozzle: "
      "nozzle_yaw}\ndeposition_speed_m_s: 0.2\ntravel_speed_m_s: 0.5\nrotate_while_moving: "
      "true\naccel_delay_s: 0.5\nlift_height_m: 0.15\nnozzle_idle_limit_s: 300\n");
  expect_refused(run_bounded("validate tests/data/plans/cottage.yaml --machine " + profile),
                 "XML elements are nested more than 64 levels deep", "deep URDF");
  // A 33 MiB file would be read whole: refused before reading.
  const std::string big = scratch.path("big.yaml");
  ASSERT_EQ(::truncate(scratch.write("big.yaml", "").c_str(), 33l * 1024 * 1024), 0);
  expect_refused(run_bounded("validate " + big), "ccbuild reads input files of at most 32 MiB",
                 "33 MiB");
  // A FIFO once hung the run waiting for a writer.
  const std::string fifo = scratch.path("plan.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused(run_bounded("validate " + fifo, 20), "is not a regular file", "FIFO");
}

TEST(HostileInput, FlagsThatDoNotFitAreRefused) {
  const Case cases[] = {
      {"validate tests/data/plans/cottage.yaml --floor-height nan", "expected a number"},
      {"validate tests/data/plans/cottage.yaml --floor-height inf", "expected a number"},
      {"layers tests/data/plans/cottage.yaml --layer-height nan", "expected a number"},
      {"validate tests/data/plans/cottage.yaml --rotate nan", "--rotate: expected a number"},
      {"validate tests/data/plans/cottage.yaml --rotate 360.001", "--rotate: Value 360.001 not in"},
      {"layers tests/data/plans/cottage.yaml --layer-height 1e-9 --floor-height 3",
       "--layer-height: must be from 0.001 to 1 m, got 1e-09 m"},
      {"plan-layer tests/data/plans/cottage.yaml --seed -1", "--seed"},
      {"plan-layer tests/data/plans/cottage.yaml --max-kicks 9223372036854775808",
       "must be from 0 to 1000000000, got 9223372036854775808"},
      {"plan-layer tests/data/plans/cottage.yaml --floor 99999999999", "--floor"},
      {"plan-layer tests/data/plans/cottage.yaml --time-limit 1e999", "expected a number"},
      {"plan-layer tests/data/plans/cottage.yaml --nozzles 2 --gantry-width 1e300",
       "--gantry-width: must be more than 0 and at most 1000 m"},
      {"plan-layer tests/data/plans/cottage.yaml --lyer 3", "did you mean '--layer'?"},
      {"plan-lyaer tests/data/plans/cottage.yaml", "did you mean 'plan-layer'?"},
      {"frobnicate", "the commands are: validate, import, layers, plan-layer, sweep, fit, climb"},
      // An empty output name (`-o "$UNSET"`) would otherwise write nothing, silently.
      {"plan-layer tests/data/plans/cottage.yaml --svg ''",
       "--svg: expected a file name, got an empty one"},
      {"plan-layer tests/data/plans/cottage.yaml --bound-certificate ''",
       "--bound-certificate: expected a file name"},
      {"schedule tests/data/buildings/cottage.yaml -o ''", "--output: expected a file name"},
      {"schedule tests/data/buildings/cottage.yaml --report ''", "--report: expected a file name"},
      {"report tests/data/plans/cottage.yaml -o ''", "--output: expected a file name"},
      {"climb tests/data/buildings/cottage.yaml --svg ''", "--svg: expected a file name"},
      {"sweep tests/data/plans/cottage.yaml --nozzles 2 --gantry-width 1m --csv ''",
       "--csv: expected a file name"},
      {"dry-run tests/data/buildings/cottage.yaml --journal ''", "--journal: expected a file name"},
      {"dry-run tests/data/buildings/cottage.yaml --state-dir ''",
       "--state-dir: expected a file name"},
      {"dry-run tests/data/buildings/cottage.yaml --log ''", "--log: expected a file name"},
  };
  for (const auto& c : cases) expect_refused(run_bounded(c.args), c.message, c.args);
}

TEST(HostileInput, NoOutputReplacesAFileTheRunReads) {
  // The building names a plan, a material, a machine and its URDF: --force may replace
  // an old drawing, never any of them.
  const char* inputs[] = {"tests/data/buildings/cottage.yaml",
                          "tests/data/buildings/plans/cottage.yaml",
                          "config/materials/standard-mix.yaml", "config/machines/cc-gantry.yaml",
                          "config/machines/cc_gantry.urdf"};
  for (const char* input : inputs) {
    const std::string before = slurp(input);
    const auto r = run_bounded(
        std::string("plan-layer tests/data/buildings/cottage.yaml --force --svg ") + input);
    expect_refused(r, "output would overwrite an input file", input);
    EXPECT_EQ(slurp(input), before) << input;
  }
  const Scratch scratch;
  const std::string csv = scratch.write("plan-copy.yaml", slurp("tests/data/plans/cottage.yaml"));
  const auto r = run_bounded("sweep " + csv +
                             " --nozzles 2 --platform-width 20m --gantry-width 1m "
                             "--rail-axis x --force --csv " +
                             csv);
  expect_refused(r, "output would overwrite an input file", "sweep --csv onto its input");
}

TEST(HostileInput, ABrokenInvariantExitsThreeWithAMessage) {
  const auto r = run_shell("CCBUILD_SELFTEST_INTERNAL_CHECK=1 " + testing::ccbuild_binary() +
                           " validate tests/data/plans/cottage.yaml");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "ccbuild: internal error: internal check failed at"));
  EXPECT_TRUE(contains(r.err, "self-test of the internal-error path"));
}

TEST(HostileInput, ErrorsAreJsonOnStdoutWhenJsonIsAsked) {
  const auto r = run_bounded("validate tests/data/broken/unknown_vertex.yaml --json");
  EXPECT_EQ(r.exit_code, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["error"]["kind"], "input");
  EXPECT_EQ(j["error"]["exit_code"], 2);
  ASSERT_GE(j["error"]["diagnostics"].size(), 1u);
  const auto& d = j["error"]["diagnostics"][0];
  EXPECT_EQ(d["file"], "tests/data/broken/unknown_vertex.yaml");
  EXPECT_EQ(d["line"], 7);
  EXPECT_EQ(d["field"], "walls[1].end");
  // A usage error too.
  const auto usage = run_bounded("plan-layer tests/data/plans/cottage.yaml --json --nozzles x");
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(nlohmann::json::parse(usage.out)["error"]["kind"], "usage");
}

// A seeded mutation fuzz of good inputs: numbers swapped for extreme ones, lines dropped,
// doubled or cut short, aliases and nesting inserted. Whatever comes out, ccbuild answers
// with exit 0, 1 or 2 and a message, within the time limit.
TEST(HostileInput, MutatedInputsNeverCrashOrHang) {
  const Scratch scratch;
  const std::vector<std::string> seeds = {
      "tests/data/plans/cottage.yaml", "tests/data/plans/cottage.json",
      "tests/data/plans/cottage.txt", "tests/data/plans/narrow_room.txt"};
  const std::vector<std::string> numbers = {
      "1e200", "-1e308", "nan",  ".inf", "-.inf", "0", "-0", "1e-300", "99999999999999999999",
      "-1",    "0x10",   "3.0e", "1.5"};
  std::mt19937_64 rng(20261201);
  int accepted = 0, refused = 0;
  for (int round = 0; round < 80; ++round) {
    const std::string& seed = seeds[rng() % seeds.size()];
    std::vector<std::string> lines;
    {
      std::istringstream in(slurp(seed));
      std::string line;
      while (std::getline(in, line)) lines.push_back(line);
    }
    const int mutations = 1 + static_cast<int>(rng() % 3);
    for (int m = 0; m < mutations && !lines.empty(); ++m) {
      std::string& line = lines[rng() % lines.size()];
      switch (rng() % 6) {
        case 0: {  // a number becomes an extreme one
          const auto digit = line.find_first_of("0123456789");
          if (digit != std::string::npos) {
            auto end = line.find_first_not_of("0123456789.", digit);
            if (end == std::string::npos) end = line.size();
            line.replace(digit, end - digit, numbers[rng() % numbers.size()]);
          }
          break;
        }
        case 1:
          line.clear();
          break;
        case 2:
          lines.push_back(line);
          break;
        case 3:
          line = line.substr(0, rng() % (line.size() + 1));
          break;
        case 4:
          line += rng() % 2 ? " &x [*x]" : " [[[[[[[[";
          break;
        default:
          line = "---";
          break;
      }
    }
    std::string text;
    for (const auto& l : lines) text += l + "\n";
    const std::string file = scratch.write("mutant" + fs::path(seed).extension().string(), text);
    std::vector<testing::CommandResult> results;
    for (const char* command : {"validate", "plan-layer --time-limit 5"}) {
      const auto r = run_bounded(std::string(command) + " " + file, 30);
      SCOPED_TRACE(std::string(command) + " on a mutant of " + seed + ":\n" + text);
      EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << "exit " << r.exit_code << ": " << r.err;
      EXPECT_FALSE(contains(r.err, "internal error"));
      if (r.exit_code == 2) {
        EXPECT_TRUE(contains(r.err, "ccbuild: error: "));
      }
      results.push_back(r);
    }
    // Both commands open the file the same way: the same verdict, and on a refusal the
    // same first line (file, line, field and what was expected).
    SCOPED_TRACE("a mutant of " + seed + ":\n" + text);
    EXPECT_EQ(results[0].exit_code, results[1].exit_code) << results[0].err << results[1].err;
    if (results[0].exit_code == 2 && results[1].exit_code == 2) {
      EXPECT_EQ(results[0].err.substr(0, results[0].err.find('\n')),
                results[1].err.substr(0, results[1].err.find('\n')));
    }
    accepted += results[0].exit_code == 0 ? 1 : 0;
    refused += results[0].exit_code == 2 ? 1 : 0;
  }
  // The fuzz reaches both sides: some mutants are still valid plans, some are not.
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace ccbuild
