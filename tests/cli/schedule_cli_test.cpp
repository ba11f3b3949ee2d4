// `ccbuild schedule` and `ccbuild diff`: exit codes (0 feasible, 1 infeasible or
// differing, 2 bad input), the schedule file written whole and never over an input, the
// same bytes whatever --jobs, and diff naming what changed and honouring its tolerance.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "ccbuild/common/format.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::run_ccbuild;
using testing::slurp;

fs::path scratch(const std::string& name) {
  return testing::scratch_dir("schedule_cli", name);
}

TEST(ScheduleCommand, OnASiteInWeatherTheSameInputsGiveTheSameBytes) {
  const fs::path dir = scratch("site_bytes");
  const std::string site = " --site config/sites/weekdays-berlin-2027-weather.yaml";
  const auto one = run_ccbuild("schedule config/buildings/house.yaml --quiet --jobs 1 -o " +
                               (dir / "one.json").string() + site);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_TRUE(contains(one.out, "site: from Mon 2027-03-01 07:00 (Europe/Berlin, +01:00)"))
      << one.out;
  EXPECT_TRUE(contains(one.out, "weather: ")) << one.out;
  EXPECT_TRUE(contains(one.out, "working days with printing")) << one.out;
  const auto two = run_ccbuild("schedule config/buildings/house.yaml --quiet --jobs 2 -o " +
                               (dir / "two.json").string() + site);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(slurp(dir / "one.json"), slurp(dir / "two.json"));
  // The weather file is an input: recorded with its checksum.
  EXPECT_TRUE(contains(slurp(dir / "one.json"), "berlin-spring-2027.csv"));
  // A site file with an unknown key is bad input, naming it.
  std::ofstream(dir / "typo.yaml") << "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"
                                      "holiday: [2027-03-02]\n";
  const auto typo = run_ccbuild("schedule config/buildings/house.yaml --quiet --site " +
                                (dir / "typo.yaml").string());
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_TRUE(contains(typo.err, "typo.yaml:3")) << typo.err;
  EXPECT_TRUE(contains(typo.err, "holidays")) << typo.err;
}

TEST(ScheduleCommand, TheHouseSchedulesWithTheSameBytesWhateverTheJobs) {
  const fs::path dir = scratch("jobs");
  const auto one = run_ccbuild("schedule config/buildings/house.yaml --quiet --jobs 1 -o " +
                               (dir / "one.json").string());
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_TRUE(contains(one.out, "60 layers"));
  EXPECT_TRUE(contains(one.out, "feasible"));
  EXPECT_TRUE(contains(one.out, "schedule written to"));
  EXPECT_TRUE(one.err.empty()) << one.err;  // --quiet: no progress
  const auto two = run_ccbuild("schedule config/buildings/house.yaml --jobs 2 -o " +
                               (dir / "two.json").string());
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_TRUE(contains(two.err, "planning 6 layer plans"));  // progress on stderr
  EXPECT_EQ(slurp(dir / "one.json"), slurp(dir / "two.json"));
  const auto doc = nlohmann::json::parse(slurp(dir / "one.json"));
  EXPECT_EQ(doc["format"], "ccbuild-schedule");
  EXPECT_EQ(doc["schema_version"], 2);
  EXPECT_EQ(doc["inputs"]["files"].size(), 6u);
  EXPECT_EQ(doc["inputs"]["files"][0]["sha256"].get<std::string>().size(), 64u);
  // The same schedule: diff agrees.
  const auto same =
      run_ccbuild("diff " + (dir / "one.json").string() + " " + (dir / "two.json").string());
  EXPECT_EQ(same.exit_code, 0) << same.out;
  EXPECT_TRUE(contains(same.out, "agree"));
  // The "objectives:" line compares with the other objective scheduled in full (from the
  // plans this run made): the shortest schedule of its own says the same makespan.
  // --no-compare leaves the line out.
  const auto shortest =
      run_ccbuild("schedule config/buildings/house.yaml --quiet --no-compare --objective shortest");
  ASSERT_EQ(shortest.exit_code, 0) << shortest.err;
  EXPECT_FALSE(contains(shortest.out, "objectives:")) << shortest.out;
  const auto makespan = [](const std::string& out) {
    const auto at = out.find("total: ");
    return at == std::string::npos ? std::string("?")
                                   : out.substr(at + 7, out.find(" from", at) - at - 7);
  };
  EXPECT_TRUE(contains(one.out, "objectives: fewest-nozzles " + makespan(one.out) + " (up to"))
      << one.out;
  EXPECT_TRUE(contains(one.out, "; shortest " + makespan(shortest.out) + " (up to")) << one.out;
  fs::remove_all(dir);
}

// The apartment on the climber keeps its limits by millimetres: the two-nozzle plan of
// floors 1 and 2 keeps its 1.5 m gantries 1.524 m apart, and the last climb passes under a
// millimetre from a wall. Both are warned in the text and in the JSON, saying where, in the
// building's feet (small lengths in inches: 24 mm is 0.93 in, 0.7 mm 0.03 in).
TEST(Margins, TheApartmentsGantriesAndClimbAreWarned) {
  const fs::path dir = scratch("margins");
  const auto r = run_ccbuild(
      "schedule config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml "
      "--quiet -o " +
      (dir / "s.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gantries =
      "margin: the 2 gantries of plan g5n2 come within 0.93 in of each other (4.999 ft between "
      "centres, 4.921 ft wide), on floor 1 layers 7-16, floor 2 layers 7-16; warned under 2.0 in";
  const std::string climb =
      "margin: 1 climb passes within 0.79 in of a wall; the closest, from "
      "stage 3 to 4 (after floor 3 layer 24), passes 0.03 in from it";
  EXPECT_TRUE(contains(r.out, "warning: " + gantries)) << r.out;
  EXPECT_TRUE(contains(r.out, "warning: " + climb)) << r.out;
  const auto json = nlohmann::json::parse(slurp(dir / "s.json"));
  std::string warnings;
  for (const auto& w : json.at("warnings")) warnings += w.get<std::string>() + "\n";
  EXPECT_TRUE(contains(warnings, gantries)) << warnings;
  EXPECT_TRUE(contains(warnings, climb)) << warnings;
}

TEST(ScheduleCommand, NeverWritesOverAnInputNorAnOutputWithoutForce) {
  const fs::path dir = scratch("force");
  const fs::path out = dir / "s.json";
  std::ofstream(out) << "precious";
  const auto refused =
      run_ccbuild("schedule config/buildings/house.yaml --quiet -o " + out.string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_TRUE(contains(refused.err, "--force"));
  EXPECT_EQ(slurp(out), "precious");
  const auto input = run_ccbuild(
      "schedule config/buildings/house.yaml --quiet --force -o config/buildings/house/ground.yaml");
  EXPECT_EQ(input.exit_code, 2);
  EXPECT_TRUE(contains(input.err, "ground.yaml"));
  fs::remove_all(dir);
}

TEST(ScheduleCommand, AnInfeasibleBuildingExitsOneAndStillWritesItsSchedule) {
  const fs::path dir = scratch("infeasible");
  std::ofstream(dir / "impatient.yaml")
      << "name: impatient\ndensity_kg_m3: 2200\nmin_layer_interval_s: 10\n"
         "max_layer_interval_s: 60\nstrength_curve:\n  - {age_min: 0, strength_mpa: 0.01}\n"
         "  - {age_min: 60, strength_mpa: 1}\n";
  const auto r =
      run_ccbuild("schedule config/buildings/house.yaml --quiet --material " +
                  (dir / "impatient.yaml").string() + " -o " + (dir / "s.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.out, "NOT feasible"));
  EXPECT_TRUE(contains(r.out, "floor 0 layer 1"));
  EXPECT_TRUE(contains(r.out, "fix: a maximum layer interval of at least"));
  const auto doc = nlohmann::json::parse(slurp(dir / "s.json"));
  EXPECT_FALSE(doc["feasible"].get<bool>());
  EXPECT_EQ(doc["infeasibility"]["kind"], "max-interval");
  EXPECT_GT(doc["infeasibility"]["fix"]["max_interval_needed_s"].get<double>(), 60.0);
  EXPECT_EQ(doc["layers"].size(), 60u);
  fs::remove_all(dir);
}

TEST(ScheduleCommand, ABuildingOffTheRailsIsRefusedAndCentredOnRequest) {
  // The cottage moved 60 m along the rails of the bundled gantry (x -2..62 m): its length
  // fits, its place does not.
  const fs::path dir = scratch("site");
  std::string text = slurp(testing::source_path("tests/data/buildings/cottage.yaml"));
  const std::string data = testing::source_path("tests/data/buildings").string() + "/";
  for (const std::string key : {"material: ", "machine: ", "plan: "})
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1))
      text.insert(at + key.size(), data);
  text.replace(text.find("floors:"), 0, "site: {origin: [60, 0]}\n");
  std::ofstream(dir / "b.yaml") << text;
  const std::string out = (dir / "s.json").string();
  const auto refused = run_ccbuild("schedule " + (dir / "b.yaml").string() + " --quiet -o " + out);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_TRUE(contains(refused.err, "past the end of its x travel (62.00 m)")) << refused.err;
  EXPECT_FALSE(fs::exists(out));
  const auto centred =
      run_ccbuild("schedule " + (dir / "b.yaml").string() + " --quiet --place centre -o " + out);
  ASSERT_EQ(centred.exit_code, 0) << centred.err;
  const auto doc = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(doc["inputs"]["placement"]["how"], "centred");
  // Every waypoint of every plan stands within the machine's x and y travel, and the
  // footprint's middle on the travel's middle.
  double lo_x = 1e9, hi_x = -1e9;
  for (const auto& [key, plan] : doc["plans"].items())
    for (const auto& nozzle : plan["nozzles"])
      for (const auto& w : nozzle["waypoints"]) {
        const double x = w["x_m"].get<double>(), y = w["y_m"].get<double>();
        EXPECT_GE(x, -2.0);
        EXPECT_LE(x, 62.0);
        EXPECT_GE(y, -2.0);
        EXPECT_LE(y, 27.0);
        lo_x = std::min(lo_x, x);
        hi_x = std::max(hi_x, x);
      }
  EXPECT_NEAR(0.5 * (lo_x + hi_x), 30.0, 1e-6);
  fs::remove_all(dir);
}

TEST(ImportCommand, ADrawingImportedSchedulesAsTheDrawingNamedDirectly) {
  const fs::path dir = scratch("import");
  const std::string drawing =
      testing::source_path("tests/data/drawings/centrelines_m.dxf").string();
  const std::string building = (dir / "two.yaml").string();
  const std::string args =
      " --wall-layers WALLS --door-layers DOORS --wall-lines centrelines "
      "--floors 2 --floor-height 3 -o " +
      building;
  const auto imported = run_ccbuild("import " + drawing + args);
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_TRUE(contains(imported.out, "5 walls (0 with their drawn thickness), 1 openings"));
  ASSERT_TRUE(fs::exists(dir / "two.plan.yaml"));
  // The same drawing named by a building file directly.
  const std::string config = testing::source_path("config").string();
  std::ofstream(dir / "direct.yaml")
      << "units: m\nlayer_height: 0.1\nmaterial: " << config << "/materials/standard-mix.yaml\n"
      << "machine: " << config << "/machines/cc-gantry.yaml\nfloors:\n"
      << "  - {height: 3, plan: {dxf: " << drawing
      << ", wall_layers: WALLS, door_layers: DOORS, wall_lines: centrelines}}\n"
      << "  - {height: 3, plan: {dxf: " << drawing
      << ", wall_layers: WALLS, door_layers: DOORS, wall_lines: centrelines}}\n";
  for (const char* name : {"two", "direct"})
    ASSERT_EQ(run_ccbuild("schedule " + (dir / (std::string(name) + ".yaml")).string() +
                          " --quiet -o " + (dir / (std::string(name) + ".json")).string())
                  .exit_code,
              0)
        << name;
  const auto diff =
      run_ccbuild("diff " + (dir / "two.json").string() + " " + (dir / "direct.json").string());
  EXPECT_EQ(diff.exit_code, 0) << diff.out;
  // Nothing replaced without --force, and never the drawing; a bad layer writes nothing.
  const std::string before = slurp(building);
  EXPECT_EQ(run_ccbuild("import " + drawing + args).exit_code, 2);
  EXPECT_EQ(slurp(building), before);
  EXPECT_EQ(run_ccbuild("import " + drawing + " --wall-layers WALLS -o " + drawing).exit_code, 2);
  const auto layer =
      run_ccbuild("import " + drawing + " --wall-layers A-WALL -o " + (dir / "none.yaml").string());
  EXPECT_EQ(layer.exit_code, 2);
  EXPECT_TRUE(contains(layer.err, "its layers (entities): DOORS (1), WALLS (2)")) << layer.err;
  EXPECT_FALSE(fs::exists(dir / "none.yaml"));
  EXPECT_FALSE(fs::exists(dir / "none.plan.yaml"));
  // Doors and windows left as gaps in 0.3 m face lines: openings with --gap-openings, and
  // the imported building (its walls as beads) schedules as the one naming the drawing.
  const std::string gaps = testing::source_path("tests/data/drawings/gaps_faces_mm.dxf").string();
  const std::string gapped = (dir / "gaps.yaml").string();
  const auto with = run_ccbuild("import " + gaps +
                                " --wall-layers A-WALL --window-layers A-GLAZ --gap-openings "
                                "--layer-height 0.5 -o " +
                                gapped);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_TRUE(contains(with.out, "7 walls (7 with their drawn thickness), 2 openings")) << with.out;
  const std::string plan = slurp(dir / "gaps.plan.yaml");
  EXPECT_TRUE(contains(plan, "offset: 0.85, width: 0.9, sill: 0, head: 2.1")) << plan;
  EXPECT_TRUE(contains(plan, "offset: 0.8, width: 1.2, sill: 0.9, head: 2.1")) << plan;
  ASSERT_EQ(
      run_ccbuild("schedule " + gapped + " --quiet -o " + (dir / "gaps.json").string()).exit_code,
      0);
  ASSERT_EQ(run_ccbuild("schedule tests/data/buildings/drawn-gaps.yaml --quiet -o " +
                        (dir / "drawn.json").string())
                .exit_code,
            0);
  const auto same =
      run_ccbuild("diff " + (dir / "gaps.json").string() + " " + (dir / "drawn.json").string());
  EXPECT_EQ(same.exit_code, 0) << same.out;
  const auto without =
      run_ccbuild("import " + gaps + " --wall-layers A-WALL -o " + (dir / "nogaps.yaml").string());
  EXPECT_TRUE(contains(without.out, "9 walls (9 with their drawn thickness), 0 openings"))
      << without.out;
  fs::remove_all(dir);
}

// A drafted drawing's door and window blocks without SILL or HEAD attributes take their
// layer's heights, else the defaults, given as import flags or in a building naming the
// drawing: both give the same schedule. A layer that holds no doors or windows, or a layer
// given no height, is refused with exit 2 and nothing written.
TEST(ImportCommand, DrawnOpeningsTakeTheirLayersHeightsFromFlagsOrTheBuilding) {
  const fs::path dir = scratch("layer_heights");
  const std::string drafted = testing::source_path("tests/data/drawings/drafted_mm.dxf").string();
  const std::string layers = " --wall-layers A-WALL --door-layers A-DOOR --window-layers A-GLAZ";
  const auto imported = run_ccbuild("import " + drafted + layers +
                                    " --door-head 2.3 --layer-heights a-glaz=1.2: --layer-height "
                                    "0.5 -o " +
                                    (dir / "flags.yaml").string());
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  const std::string plan = slurp(dir / "flags.plan.yaml");
  EXPECT_TRUE(contains(plan, "width: 0.9, sill: 0, head: 2.3}  # insert 11C of block DOOR900"))
      << plan;
  EXPECT_TRUE(contains(plan, "sill: 1, head: 2.2}  # insert 11D of block WIN1200")) << plan;
  EXPECT_TRUE(contains(plan, "sill: 1.2, head: 2.1}  # insert 121 of block WIN1200")) << plan;
  const std::string config = testing::source_path("config").string();
  const auto building = [&](const std::string& heights) {
    return "units: m\nlayer_height: 0.5\nmaterial: " + config +
           "/materials/standard-mix.yaml\nmachine: " + config +
           "/machines/cc-gantry.yaml\nfloors:\n  - {height: 3, plan: {dxf: " + drafted +
           ", wall_layers: A-WALL, door_layers: A-DOOR, window_layers: A-GLAZ, door_head: 2.3, " +
           "layer_heights: " + heights + "}}\n";
  };
  std::ofstream(dir / "direct.yaml") << building("[{layer: A-GLAZ, sill: 1.2}]");
  for (const char* name : {"flags", "direct"})
    ASSERT_EQ(
        run_ccbuild("schedule " + (dir / (std::string(name) + ".yaml")).string() +
                    " --quiet --no-compare -o " + (dir / (std::string(name) + ".json")).string())
            .exit_code,
        0)
        << name;
  const auto diff =
      run_ccbuild("diff " + (dir / "flags.json").string() + " " + (dir / "direct.json").string());
  EXPECT_EQ(diff.exit_code, 0) << diff.out;
  const auto walls = run_ccbuild("import " + drafted + layers + " --layer-heights A-WALL=1:2 -o " +
                                 (dir / "walls.yaml").string());
  EXPECT_EQ(walls.exit_code, 2);
  EXPECT_TRUE(contains(walls.err,
                       "--layer-heights: layer 'A-WALL' is not among --door-layers or "
                       "--window-layers"))
      << walls.err;
  EXPECT_FALSE(fs::exists(dir / "walls.yaml"));
  EXPECT_FALSE(fs::exists(dir / "walls.plan.yaml"));
  std::ofstream(dir / "none.yaml") << building("[{layer: A-GLAZ}]");
  const auto none = run_ccbuild("validate " + (dir / "none.yaml").string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(contains(none.err, "none.yaml:6")) << none.err;
  EXPECT_TRUE(contains(none.err, "give the layer's sill, its head or both")) << none.err;
  fs::remove_all(dir);
}

TEST(ScheduleCommand, BadInputIsExitTwo) {
  EXPECT_EQ(run_ccbuild("schedule tests/data/buildings/missing_plan.yaml --quiet").exit_code, 2);
  const auto jobs = run_ccbuild("schedule config/buildings/house.yaml --jobs -1");
  EXPECT_EQ(jobs.exit_code, 2);
  EXPECT_TRUE(contains(jobs.err, "--jobs"));
  const auto typo = run_ccbuild("schedule config/buildings/house.yaml --job 2");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_TRUE(contains(typo.err, "did you mean '--jobs'"));
  EXPECT_EQ(run_ccbuild("schedule config/buildings/house.yaml --layer-time-limit 0").exit_code, 2);
}

TEST(DiffCommand, NamesWhatChangedAndHonoursTheTolerance) {
  const fs::path dir = scratch("diff");
  const std::string old_json = (dir / "old.json").string();
  ASSERT_EQ(run_ccbuild("schedule tests/data/buildings/twin-cottages.yaml --quiet -o " + old_json)
                .exit_code,
            0);
  // The same schedule started 10 s later: every layer and event moves by 10 s (a valid
  // schedule, unlike one layer moved alone, which read_schedule refuses).
  auto doc = nlohmann::ordered_json::parse(slurp(old_json));
  for (auto& l : doc["layers"])
    for (const char* key : {"start_s", "end_s"}) l[key] = l[key].get<double>() + 10.0;
  for (auto& e : doc["events"])
    for (const char* key : {"start_s", "end_s"}) e[key] = e[key].get<double>() + 10.0;
  for (auto& d : doc["deliveries"]) d["due_s"] = d["due_s"].get<double>() + 10.0;
  doc["totals"]["makespan_s"] = doc["totals"]["makespan_s"].get<double>() + 10.0;
  std::ofstream(dir / "later.json") << doc.dump(1) << "\n";
  const std::string files = old_json + " " + (dir / "later.json").string();
  const auto differ = run_ccbuild("diff " + files);
  EXPECT_EQ(differ.exit_code, 1) << differ.err;
  EXPECT_TRUE(contains(differ.out, "floor 0 layer 0: start_s"));
  EXPECT_TRUE(contains(differ.out, "20 layers"));
  // 10 s moved: a tolerance of 10 s allows it, 9.999 s does not.
  EXPECT_EQ(run_ccbuild("diff " + files + " --tolerance 10s").exit_code, 0);
  EXPECT_EQ(run_ccbuild("diff " + files + " --tolerance 9.999s").exit_code, 1);
  // A nozzle count is never within a tolerance: the twin cottages with a mix that one
  // nozzle keeps up with.
  const std::string one = (dir / "one.json").string();
  ASSERT_EQ(run_ccbuild("schedule tests/data/buildings/twin-cottages.yaml --quiet --material "
                        "tests/data/materials/quick-set-mix.yaml -o " +
                        one)
                .exit_code,
            0);
  const auto nozzles = run_ccbuild("diff " + old_json + " " + one + " --tolerance 100%");
  EXPECT_EQ(nozzles.exit_code, 1);
  EXPECT_TRUE(contains(nozzles.out, "nozzles 2 -> 1"));
  EXPECT_TRUE(contains(nozzles.out, "note: input tests/data/materials/quick-set-mix.yaml is new"));
  // Plans are compared by key: one more plan, though no layer uses it, is a change.
  auto extra = nlohmann::ordered_json::parse(slurp(old_json));
  const std::string key = extra["layers"][0]["plan"];
  extra["plans"]["g99n1"] = extra["plans"][key];
  extra["plans"]["g99n1"]["nozzles_used"] = 2;
  std::ofstream(dir / "extra.json") << extra.dump(1) << "\n";
  const auto plans = run_ccbuild("diff " + old_json + " " + (dir / "extra.json").string());
  EXPECT_EQ(plans.exit_code, 1) << plans.err;
  EXPECT_TRUE(contains(plans.out, "plan g99n1: only in the new schedule"));
  // ... and no plans at all is not a schedule.
  extra["plans"] = nlohmann::ordered_json::object();
  std::ofstream(dir / "none.json") << extra.dump(1) << "\n";
  const auto none = run_ccbuild("diff " + old_json + " " + (dir / "none.json").string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(contains(none.err, "none.json:"));
  EXPECT_TRUE(contains(none.err, "/layers/0/plan: plans:"));
  fs::remove_all(dir);
}

TEST(DiffCommand, RefusesWhatIsNotASchedule) {
  const fs::path dir = scratch("notschedule");
  std::ofstream(dir / "a.json") << "{\"format\": \"ccbuild-climbs-1\"}";
  std::ofstream(dir / "b.json") << "{\"format\": \"ccbuild-schedule\",\n \"schema_version\": 2,";
  const auto foreign =
      run_ccbuild("diff " + (dir / "a.json").string() + " " + (dir / "a.json").string());
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_TRUE(contains(foreign.err, "a.json"));
  EXPECT_TRUE(contains(foreign.err, "format"));
  const auto truncated =
      run_ccbuild("diff " + (dir / "b.json").string() + " " + (dir / "b.json").string());
  EXPECT_EQ(truncated.exit_code, 2);
  EXPECT_TRUE(contains(truncated.err, "b.json:2"));
  EXPECT_TRUE(contains(truncated.err, "not valid JSON"));
  const auto tolerance = run_ccbuild("diff " + (dir / "a.json").string() + " " +
                                     (dir / "a.json").string() + " --tolerance 5");
  EXPECT_EQ(tolerance.exit_code, 2);
  EXPECT_TRUE(contains(tolerance.err, "--tolerance"));
  fs::remove_all(dir);
}

TEST(ReportCommand, WritesOneSelfContainedPageAndNeverOverAnInput) {
  const fs::path dir = scratch("report");
  const std::string json = (dir / "s.json").string(), html = (dir / "r.html").string();
  ASSERT_EQ(run_ccbuild("schedule config/buildings/house.yaml --quiet -o " + json).exit_code, 0);
  const auto r = run_ccbuild("report " + json + " -o " + html);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "written to"));
  const std::string page = slurp(html);
  // Self-contained: the schedule, three.js and the report's script inline; nothing fetched.
  EXPECT_TRUE(contains(page, "<script id=\"schedule-data\" type=\"application/json\">"));
  EXPECT_TRUE(contains(page, "WebGLRenderer"));
  EXPECT_TRUE(contains(page, "OrbitControls"));
  EXPECT_EQ(page.find("src=\"http"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_TRUE(contains(page, "<section id=\"gantt\">"));
  // An existing output needs --force; the schedule it reads, never.
  EXPECT_EQ(run_ccbuild("report " + json + " -o " + html).exit_code, 2);
  EXPECT_EQ(run_ccbuild("report " + json + " -o " + html + " --force").exit_code, 0);
  const std::string before = slurp(json);
  const auto over = run_ccbuild("report " + json + " -o " + json + " --force");
  EXPECT_EQ(over.exit_code, 2);
  EXPECT_EQ(slurp(json), before);
  // Not a schedule: exit 2, naming the file.
  const auto foreign = run_ccbuild("report config/buildings/house.yaml -o " + html + " --force");
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_TRUE(contains(foreign.err, "house.yaml"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild

namespace ccbuild {
namespace {

// Bad input to `ccbuild dry-run` is refused (exit 2, naming the flag or file) before any
// machine starts or any message is sent, and no file the user gave is touched.
TEST(DryRunCommand, BadInputIsExitTwoBeforeAnythingStarts) {
  const std::string schedule = "tests/regression/house.schedule.json";
  for (const std::string inject : {"clog=0", "clog=0:x", "drop=1.5", "delay=-0.1", "pin=0",
                                   "crash=x", "stall=-1", "wobble=1", "drop"}) {
    const auto r = testing::run_ccbuild("dry-run " + schedule + " --inject " + inject);
    EXPECT_EQ(r.exit_code, 2) << inject;
    EXPECT_TRUE(testing::contains(r.err, "--inject")) << inject << ": " << r.err;
  }
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_dry_run_cli" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path log = dir / "old.lcmlog", journal = dir / "notes.txt";
  std::ofstream(log) << "precious";
  std::ofstream(journal) << "not a journal, and precious too";
  const auto kept = testing::run_ccbuild("dry-run " + schedule + " --log " + log.string());
  EXPECT_EQ(kept.exit_code, 2);
  EXPECT_TRUE(testing::contains(kept.err, "--force")) << kept.err;
  EXPECT_EQ(testing::slurp(log), "precious");
  const auto wrong = testing::run_ccbuild("dry-run " + schedule + " --journal " + journal.string());
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_TRUE(testing::contains(wrong.err, "notes.txt")) << wrong.err;
  EXPECT_EQ(testing::slurp(journal), "not a journal, and precious too");
  EXPECT_EQ(testing::run_ccbuild("dry-run " + schedule + " --speed 0").exit_code, 2);
  EXPECT_EQ(testing::run_ccbuild("dry-run config/machines/cc-gantry.yaml").exit_code, 2);
  const auto not_schedule = testing::run_ccbuild("dry-run tests/data/plans/cottage.json");
  EXPECT_EQ(not_schedule.exit_code, 2) << not_schedule.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild

namespace ccbuild {
namespace {

TEST(ValidateCommand, SaysWhichWallsArePrintedAsBeadsAndHow) {
  const auto solid = testing::run_ccbuild("validate tests/data/buildings/masonry.yaml");
  ASSERT_EQ(solid.exit_code, 0) << solid.err;
  EXPECT_TRUE(
      testing::contains(solid.out,
                        "walls      1 in one pass (beads 0.10 m to 0.25 m), 8 as two skins of "
                        "0.15 m and a poured core (wall_pattern: solid)"))
      << solid.out;
  const auto ties = testing::run_ccbuild("validate tests/data/buildings/masonry-ties.yaml");
  EXPECT_TRUE(testing::contains(ties.out, "8 as two skins of 0.15 m and a zig-zag tie"))
      << ties.out;
}

}  // namespace
}  // namespace ccbuild

namespace ccbuild {
namespace {

// The print spec (issue 50): a wall thinner than the machine's narrowest bead is left out
// for the crew by default, said by validate and schedule, recorded in the schedule's
// inputs, and nothing of it is printed; `print: {thin_walls: refuse}` stops instead
// (HostileInput).
TEST(PrintSpec, AWallThinnerThanTheNarrowestBeadIsLeftOutForTheCrew) {
  const std::string said =
      "wall 1 is 0.050 m thick, thinner than the machine's narrowest bead (0.100 m): left "
      "out, for the crew to build [tests/data/hostile/thin_wall.yaml:8]";
  const auto validated = run_ccbuild("validate tests/data/hostile/thin_wall.yaml");
  ASSERT_EQ(validated.exit_code, 0) << validated.err;
  EXPECT_TRUE(contains(validated.out, "left out   floor '")) << validated.out;
  EXPECT_TRUE(contains(validated.out, said)) << validated.out;
  const fs::path dir = scratch("print_spec");
  const auto scheduled = run_ccbuild("schedule tests/data/hostile/thin_wall.yaml --quiet -o " +
                                     (dir / "s.json").string());
  ASSERT_EQ(scheduled.exit_code, 0) << scheduled.err;
  EXPECT_TRUE(contains(scheduled.err, said)) << scheduled.err;
  const auto doc = nlohmann::json::parse(slurp(dir / "s.json"));
  ASSERT_TRUE(doc["inputs"].contains("left_out")) << doc["inputs"].dump();
  const auto& left = doc["inputs"]["left_out"];
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0]["floor"], 0);
  EXPECT_EQ(left[0]["wall"], 1);
  EXPECT_DOUBLE_EQ(left[0]["thickness_m"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(left[0]["narrowest_bead_m"].get<double>(), 0.10);
  int pieces = 0;
  for (const auto& [key, plan] : doc["plans"].items())
    for (const auto& piece : plan["pieces"]) {
      EXPECT_NE(piece["wall"], 1) << key;
      ++pieces;
    }
  EXPECT_GT(pieces, 0);
  // Read back and written again, the record is kept.
  const auto diffed =
      run_ccbuild("diff " + (dir / "s.json").string() + " " + (dir / "s.json").string());
  EXPECT_EQ(diffed.exit_code, 0) << diffed.err;
  // A building that states no print spec records none (its schedule keeps its bytes).
  EXPECT_FALSE(doc["inputs"].contains("print")) << doc["inputs"].dump();
  fs::remove_all(dir);
}

// The print spec's model filters, stated in a building, are recorded and shown; a type that
// is not an IFC entity's name or a list that is not one is refused, naming the line.
TEST(PrintSpec, AModelsFiltersAreStatedInTheBuildingAndRecorded) {
  const fs::path dir = scratch("print_filters");
  const std::string plan = testing::source_path("tests/data/hostile/thin_wall.yaml").string();
  const auto building = [&](const std::string& print) {
    const fs::path file = dir / "b.yaml";
    std::ofstream(file) << "units: m\nlayer_height: 0.1\n"
                        << print << "\nfloors:\n  - {height: 1, plan: " << plan << "}\n";
    return file.string();
  };
  const std::string good = building(
      "print: {thin_walls: leave-out, wall_types: [IfcWall, IfcWallElementedCase], "
      "exclude_materials: [glass, \"Gypsum board\"]}");
  const auto shown = run_ccbuild("validate " + good);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_TRUE(contains(shown.out,
                       "  print      walls thinner than the narrowest bead left out for the crew; "
                       "the model's IfcWall, IfcWallElementedCase read as walls, but not those all "
                       "of whose materials' names hold one of: glass, Gypsum board\n"))
      << shown.out;
  const auto scheduled =
      run_ccbuild("schedule " + good + " --quiet --no-compare -o " + (dir / "s.json").string());
  ASSERT_EQ(scheduled.exit_code, 0) << scheduled.err;
  const auto doc = nlohmann::json::parse(slurp(dir / "s.json"));
  EXPECT_EQ(doc["inputs"]["print"],
            nlohmann::json::parse(
                R"({"thin_walls":"leave-out","wall_types":["IfcWall","IfcWallElementedCase"],)"
                R"("exclude_materials":["glass","Gypsum board"]})"));
  EXPECT_EQ(
      run_ccbuild("diff " + (dir / "s.json").string() + " " + (dir / "s.json").string()).exit_code,
      0);
  // A schedule whose recorded names the building file could not hold is refused on reading,
  // by the same rule, naming the field.
  for (const auto& [field, name] : std::vector<std::pair<std::string, std::string>>{
           {"wall_types", "Wall"}, {"exclude_materials", "gyp\tsum"}}) {
    auto bad = doc;
    bad["inputs"]["print"][field][1] = name;
    const fs::path file = dir / ("bad_" + field + ".json");
    std::ofstream(file) << bad.dump();
    const auto refused = run_ccbuild("diff " + file.string() + " " + (dir / "s.json").string());
    EXPECT_EQ(refused.exit_code, 2) << field;
    EXPECT_TRUE(contains(refused.err, "/inputs/print/" + field + "/1")) << refused.err;
  }
  for (const auto& [print, said] : std::vector<std::pair<std::string, std::string>>{
           {"print: {wall_types: [Wall]}", "wall_types[0]: expected an IFC entity name"},
           {"print: {wall_types: IfcWall}", "wall_types: expected a list of names"},
           {"print: {wall_types: []}", "wall_types: name at least one wall type"},
           {"print: {exclude_materials: [\"\"]}", "expected a material's name"},
           {"print: {thin_wall: refuse}", "thin_wall"}}) {
    const auto refused = run_ccbuild("validate " + building(print));
    EXPECT_EQ(refused.exit_code, 2) << print;
    EXPECT_TRUE(contains(refused.err, "b.yaml:3")) << print << ": " << refused.err;
    EXPECT_TRUE(contains(refused.err, said)) << print << ": " << refused.err;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild

namespace ccbuild {
namespace {

// The cottage's climb in March weather waits for its youngest anchor (cold weeks slow
// it), then for working hours: the text gives each cause the hours it held the climb, as
// the JSON's binding times say, and those are the hours worked out by hand from the
// reasons (the anchors from the start, the night from when they were strong).
TEST(WaitCauses, AClimbsWaitIsToldByTheHoursEachCauseHeldIt) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_causes_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto run = run_ccbuild(
      "schedule tests/data/buildings/cottage-on-site.yaml --machine "
      "config/machines/cc-climber-family.yaml --site "
      "config/sites/weekdays-berlin-2027-weather.yaml "
      "--no-compare -o " +
      (dir / "s.json").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json doc = nlohmann::json::parse(slurp(dir / "s.json"));
  int climbs = 0;
  for (const auto& e : doc["events"]) {
    if (e["kind"] != "climb") continue;
    ++climbs;
    double anchors_s = 0.0, night_s = 0.0, anchors_bound_s = 0.0, night_bound_s = 0.0,
           night_from_s = -1.0;
    for (const auto& r : e["wait_reasons"]) {
      if (r["kind"] == "anchor-strength") {
        anchors_s = std::max(anchors_s, r["required_s"].get<double>());
        anchors_bound_s += r["binding_s"].get<double>();
      } else if (r["kind"] == "off-shift") {
        night_s = r["required_s"].get<double>();
        night_from_s = r["from_s"].get<double>();
        night_bound_s += r["binding_s"].get<double>();
      }
    }
    ASSERT_GT(anchors_s, 0.0);
    ASSERT_GT(night_s, anchors_s);  // the night found once the anchors were strong
    EXPECT_NEAR(night_from_s, anchors_s, 1e-5);
    EXPECT_NEAR(anchors_bound_s, anchors_s, 1e-5);
    EXPECT_NEAR(night_bound_s, night_s - anchors_s, 1e-5);
    EXPECT_NEAR(anchors_bound_s + night_bound_s, e["wait_before_s"].get<double>(), 1e-5);
    // The text, in the wait's unit: the same hours, to its two decimals.
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        run.out, m,
        std::regex(
            R"(after a wait of ([0-9.]+) (\w+) \(anchor-strength ([0-9.]+) (\w+), off-shift ([0-9.]+) (\w+)\))")))
        << run.out;
    const std::map<std::string, double> per_unit_s = {
        {"s", 1.0}, {"min", 60.0}, {"h", 3600.0}, {"d", 86400.0}};
    ASSERT_TRUE(per_unit_s.count(m[4]) && per_unit_s.count(m[6])) << m[0];
    EXPECT_EQ(m[2], m[4]);  // one unit
    EXPECT_NEAR(std::stod(m[3]) * per_unit_s.at(m[4]), anchors_bound_s,
                0.005 * per_unit_s.at(m[4]));
    EXPECT_NEAR(std::stod(m[5]) * per_unit_s.at(m[6]), night_bound_s, 0.005 * per_unit_s.at(m[6]));
    // The anchor waits the text totals are the anchors' binding hours, not the night's.
    EXPECT_TRUE(contains(run.out, "anchor waits: " + duration_text(anchors_bound_s) + " of"))
        << run.out;
  }
  EXPECT_EQ(climbs, 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild
