// IFC models on the command line: `ccbuild validate MODEL.ifc` prints what the import left
// out; `ccbuild import MODEL.ifc` writes a building and its plans that schedule exactly as
// the model named directly; hostile models exit 2 naming the file.

#include <gtest/gtest.h>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::run_ccbuild;
using testing::slurp;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_ifc_cli_" + name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(IfcCommands, ValidateReadsAModelAndSaysWhatWasLeftOut) {
  const auto r = run_ccbuild("validate tests/data/ifc/house_ifc4.ifc");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "valid building"));
  EXPECT_TRUE(contains(r.out, "(bundled default)"));  // the model names no profiles
  EXPECT_TRUE(contains(r.out, "'Glass screen': a curtain wall, not printable; left out"));
  EXPECT_TRUE(contains(r.out, "imported 10 walls and 4 openings on 2 floors"));
  EXPECT_TRUE(contains(r.out, "total: 2 floor(s), 10 walls, 4 openings"));
  // Any case of the extension; and a model of 0.3 m walls, printed as two skins each.
  const fs::path dir = scratch("validate");
  fs::copy_file(testing::source_path("tests/data/ifc/house_ifc2x3.ifc"), dir / "HOUSE.IFC");
  EXPECT_EQ(run_ccbuild("validate " + (dir / "HOUSE.IFC").string()).exit_code, 0);
  const auto thick = run_ccbuild("validate tests/data/ifc/thick_ifc4.ifc");
  EXPECT_EQ(thick.exit_code, 0) << thick.err;
  fs::remove_all(dir);
}

TEST(IfcCommands, AModelImportedSchedulesAsTheModelNamedDirectly) {
  const fs::path dir = scratch("import");
  const std::string model = testing::source_path("tests/data/ifc/house_ifc4.ifc").string();
  const std::string building = (dir / "house.yaml").string();
  const auto imported = run_ccbuild("import " + model + " -o " + building);
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_TRUE(contains(imported.out, "2 floors, 10 walls, 4 openings (IFC4)"));
  EXPECT_TRUE(contains(imported.err, "'Curved garden wall': its axis is curved"));
  ASSERT_TRUE(fs::exists(dir / "house.1.plan.yaml"));
  ASSERT_TRUE(fs::exists(dir / "house.2.plan.yaml"));
  const std::string plan = slurp(dir / "house.1.plan.yaml");
  EXPECT_TRUE(contains(plan, "guid: \""));
  EXPECT_TRUE(contains(plan, "'South wall'"));
  EXPECT_TRUE(contains(slurp(building), "#   IfcCurtainWall "));  // the notes, for review
  EXPECT_EQ(run_ccbuild("validate " + building).exit_code, 0);
  for (const auto& [input, output] :
       {std::pair{building, "imported.json"}, std::pair{model, "direct.json"}}) {
    const auto s = run_ccbuild("schedule " + input + " --quiet -o " + (dir / output).string());
    ASSERT_EQ(s.exit_code, 0) << input << "\n" << s.err;
  }
  const auto diff = run_ccbuild("diff " + (dir / "imported.json").string() + " " +
                                (dir / "direct.json").string());
  EXPECT_EQ(diff.exit_code, 0) << diff.out;
  // Provenance: both routes' schedules name each wall's GlobalId under its floor and id,
  // and the report's tooltips look them up there.
  const auto guid_at = plan.find("guid: \"");
  ASSERT_NE(guid_at, std::string::npos);
  const std::string guid = plan.substr(guid_at + 7, 22);
  for (const char* output : {"imported.json", "direct.json"}) {
    const auto doc = nlohmann::json::parse(slurp(dir / output));
    const auto& floor0 = doc.at("inputs").at("provenance").at(0);
    EXPECT_EQ(floor0.at("floor"), 0) << output;
    EXPECT_EQ(floor0.at("walls").at("1"), guid) << output;
    EXPECT_EQ(floor0.at("openings").size(), 3u) << output;
  }
  const auto report = run_ccbuild("report " + (dir / "direct.json").string() + " -o " +
                                  (dir / "report.html").string());
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_TRUE(contains(slurp(dir / "report.html"), "IFC GlobalId "));
  EXPECT_TRUE(contains(diff.out, "agree"));
  // Nothing replaced without --force, never the model; DXF flags are refused for a model.
  const std::string before = slurp(building);
  EXPECT_EQ(run_ccbuild("import " + model + " -o " + building).exit_code, 2);
  EXPECT_EQ(slurp(building), before);
  EXPECT_EQ(run_ccbuild("import " + model + " -o " + building + " --force").exit_code, 0);
  EXPECT_EQ(run_ccbuild("import " + model + " -o " + model + " --force").exit_code, 2);
  const auto layers =
      run_ccbuild("import " + model + " --wall-layers A -o " + (dir / "x.yaml").string());
  EXPECT_EQ(layers.exit_code, 2);
  EXPECT_TRUE(contains(layers.err, "is for DXF drawings"));
  EXPECT_FALSE(fs::exists(dir / "x.yaml"));
  // Filters: the gypsum partition printed too.
  const auto all =
      run_ccbuild("import " + model + " --no-material-filter -o " + (dir / "all.yaml").string());
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_TRUE(contains(slurp(dir / "all.2.plan.yaml"), "'Bedroom partition'"));
  fs::remove_all(dir);
}

TEST(IfcCommands, ThePublicDuplexIsPlacedOnTheRailsAndItsThickWallsPrintedAsBeads) {
  // Its concrete and CMU walls are 0.417-0.55 m thick; its model coordinates are off the
  // bundled gantry's rails until centred. (IndependentCheck.ScheduleIfcDuplexCentred
  // schedules it and re-checks the schedule and its report.)
  const auto off = run_ccbuild("validate tests/data/ifc/public/Duplex_A_20110907.ifc");
  EXPECT_EQ(off.exit_code, 2);
  EXPECT_TRUE(contains(off.err, "or centre it with --place centre")) << off.err;
  const auto r = run_ccbuild("validate tests/data/ifc/public/Duplex_A_20110907.ifc --place centre");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "imported 23 walls and 26 openings on 4 floors")) << r.out;
}

TEST(IfcCommands, HostileModelsExitTwoNamingTheFile) {
  const fs::path dir = scratch("hostile");
  const std::string out = (dir / "out.yaml").string();
  for (const char* name : {"truncated.ifc", "self_placement.ifc", "nan.ifc", "no_walls.ifc"}) {
    const std::string file = "tests/data/ifc/" + std::string(name);
    for (const std::string& args :
         {"validate " + file, "schedule " + file + " --quiet", "import " + file + " -o " + out}) {
      const auto r = run_ccbuild(args);
      EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
      EXPECT_TRUE(contains(r.err, file)) << args;
    }
  }
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild
