// Issue 49: `ccbuild import` on hostile inputs generated here (tests/tools/make_ifc.py and
// tests/support/dxf_writer.hpp): names and file names YAML must escape read back exactly,
// duplicated linework imports in bounded memory and says so in a few lines, a second DATA
// section and counts past the limits are refused with the file and the line.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "dxf_writer.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::DxfWriter;

/// `text` as one word for /bin/sh, whatever it holds.
std::string sh(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// ccbuild ARGS in at most 1.5 GB of address space and 60 s: running out of either is a
/// failure (a signal or exit 3), not a stuck machine.
testing::CommandResult run_bounded(const std::string& args) {
  return testing::run_shell("ulimit -v 1500000; timeout 60 " + testing::ccbuild_binary() + " " +
                            args);
}

testing::CommandResult make_ifc(const std::string& args) {
  return testing::run_shell("python3 tests/tools/make_ifc.py " + args);
}

const DocNode& entry(const DocNode& map, const std::string& key) {
  for (const auto& [k, v] : map.entries)
    if (k == key) return v;
  ADD_FAILURE() << "no key " << key;
  return map;
}

/// Every line of stderr is one import note (none split by a line break in a name).
void expect_only_notes(const std::string& err) {
  std::istringstream lines(err);
  std::string line;
  while (std::getline(lines, line)) EXPECT_EQ(line.rfind("import: note: ", 0), 0u) << line;
}

// The names, the GlobalId, the notes and the file names of the model hold line breaks,
// quotes, '#', ': ', tabs and non-ASCII: the building and its plans read back (validate),
// with each name exactly as in the model, and no comment spills onto a line of its own.
TEST(ImportHostile, NamesThatYamlMustEscapeReadBackExactly) {
  const fs::path dir = testing::scratch_dir("import_cli", "names");
  const std::string model = (dir / "model\n#1 \"x\": \xC3\xA9\t.ifc").string();
  ASSERT_EQ(make_ifc("--hostile-names " + sh(model)).exit_code, 0);
  const fs::path out = dir / "b\n\"#1\": \xC3\xA9.yaml";
  // A material filter of the user's own naming, written into the building's print spec.
  const std::string odd_material = "gl\"ass: #1 [\xC3\xA9] {x} '";
  const auto r = run_bounded("import " + sh(model) + " --exclude-materials " +
                             sh("glass," + odd_material) + " -o " + sh(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_only_notes(r.err);
  EXPECT_TRUE(contains(r.err, "and 70 more of the same kind: curtain walls left out"));
  const auto valid = run_bounded("validate " + sh(out.string()));
  EXPECT_EQ(valid.exit_code, 0) << valid.err << valid.out;

  const Document building = load_document(out);
  std::set<std::string> keys;
  for (const auto& [key, value] : building.root.entries) keys.insert(key);
  EXPECT_EQ(keys, (std::set<std::string>{"name", "units", "layer_height", "material", "machine",
                                         "print", "floors"}));
  const auto& excluded = entry(entry(building.root, "print"), "exclude_materials").items;
  ASSERT_EQ(excluded.size(), 2u);
  EXPECT_EQ(excluded[0].text, "glass");
  EXPECT_EQ(excluded[1].text, odd_material);
  EXPECT_EQ(entry(building.root, "name").text, "Block \"A\"\n# not: a comment");
  const auto& floors = entry(building.root, "floors").items;
  ASSERT_EQ(floors.size(), 2u);
  EXPECT_EQ(entry(floors[0], "name").text,
            "Ground\nfloor #1: \"hall\"\t\xC3\xA9t\xC3\xA9 \xE2\x98\x83 \xF0\x9F\x98\x80");
  EXPECT_EQ(entry(floors[1], "name").text,
            "First floor: 'up'\xE2\x80\xA8# x: y\xC2\xA0"
            "end");
  EXPECT_EQ(entry(floors[0], "plan").text, "b\n\"#1\": \xC3\xA9.1.plan.yaml");
  // The ground floor's plan: the door by its name, the south wall by its GlobalId.
  const Document plan = load_document(dir / entry(floors[0], "plan").text);
  const auto& openings = entry(plan.root, "openings").items;
  ASSERT_EQ(openings.size(), 1u);
  EXPECT_EQ(entry(openings[0], "id").text, "Front door\n\"main\": #1\t\xC3\xA9");
  int hostile_guids = 0;
  for (const auto& wall : entry(plan.root, "walls").items)
    for (const auto& [key, value] : wall.entries)
      hostile_guids += key == "guid" && value.text == "0wall\n#\"guid\": x\t\xC3\xA9" ? 1 : 0;
  EXPECT_EQ(hostile_guids, 1);
  // The notes are comments of the building file, 50 curtain walls and a count of the rest.
  const std::string text = testing::slurp(out);
  EXPECT_TRUE(contains(text, "#   and 70 more of the same kind: curtain walls left out\n"));
  EXPECT_TRUE(contains(text, "'Glass\\nscreen # \\\"x\\\": y': a curtain wall"));
  fs::remove_all(dir);
}

// A filter the building file could not hold back (a control character, a type that is not
// an IFC entity, 101 names) is refused by import, naming its flag, before anything is
// written; the boundary values (100 characters, 100 names) are taken.
TEST(ImportHostile, FiltersTheBuildingCouldNotReadBackAreRefusedAtTheFlag) {
  const fs::path dir = testing::scratch_dir("import_cli", "filters");
  const std::string model = (dir / "m.ifc").string();
  ASSERT_EQ(make_ifc("--hostile-names " + sh(model)).exit_code, 0);
  const std::string out = (dir / "b.yaml").string();
  // "glass," then COUNT - 1 more names: m1,m2,...
  const auto materials = [](int count) {
    std::string list = "glass";
    for (int i = 1; i < count; ++i) list += ",m" + std::to_string(i);
    return list;
  };
  for (const auto& [flags, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--exclude-materials " + sh("glass,gyp\tsum"),
            "--exclude-materials: expected a material's name"},
           {"--exclude-materials " + sh(std::string(101, 'x')),
            "--exclude-materials: expected a material's name"},
           {"--wall-types " + sh("IfcWall,Wall"), "--wall-types: expected an IFC entity name"},
           {"--wall-types " + sh("IfcWall\"x"), "--wall-types: expected an IFC entity name"},
           {"--exclude-materials " + materials(101),
            "--exclude-materials: expected at most 100 names, got 101"}}) {
    const auto r = run_bounded("import " + sh(model) + " " + flags + " -o " + sh(out));
    EXPECT_EQ(r.exit_code, 2) << flags << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, expected)) << r.err;
    EXPECT_FALSE(fs::exists(out)) << flags;
  }
  const auto longest = run_bounded("import " + sh(model) + " --exclude-materials " + materials(99) +
                                   "," + std::string(100, 'x') + " -o " + sh(out));
  ASSERT_EQ(longest.exit_code, 0) << longest.err;
  const auto valid = run_bounded("validate " + sh(out));
  EXPECT_EQ(valid.exit_code, 0) << valid.err;
  fs::remove_all(dir);
}

// 1,000 copies of one centreline (89 MB of overlaps on stderr, 20 s, before): each a wall,
// as centrelines are; refused, the 499,500 overlaps said in 51 lines.
TEST(ImportHostile, ALineDrawnAThousandTimesIsRefusedInAScreenful) {
  const fs::path dir = testing::scratch_dir("import_cli", "thousand");
  DxfWriter d(6);
  for (int copy = 0; copy < 1000; ++copy) d.line("W", 0, 0, 6, 0);
  d.line("W", 6, 0, 6, 4);
  d.line("W", 6, 4, 0, 4);
  d.line("W", 0, 4, 0, 0);
  d.write((dir / "d.dxf").string());
  const std::string out = (dir / "b.yaml").string();
  const auto r = run_bounded("import " + (dir / "d.dxf").string() +
                             " --wall-layers W --wall-lines centrelines -o " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err.substr(0, 2000);
  EXPECT_LT(r.err.size(), 16'000u);
  EXPECT_TRUE(contains(r.err, "d.dxf: entity ")) << r.err.substr(0, 2000);
  EXPECT_TRUE(contains(r.err, " on the same line; each stretch of wall must be drawn once"));
  EXPECT_TRUE(contains(r.err, "and 499450 more problems (the first 50 are listed above)"));
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

// The fuzz's 0.3 MB drawing: a room's eight face lines drawn 800 times each, which once ran
// out of memory (3.3 GB). In bounded memory: the room, and the copies said in a few lines.
TEST(ImportHostile, DuplicatedFaceLinesImportInBoundedMemory) {
  const fs::path dir = testing::scratch_dir("import_cli", "faces");
  DxfWriter d(4);  // millimetres; walls 150 mm thick (one bead)
  for (int copy = 0; copy < 800; ++copy) {
    d.line("W", 0, 0, 6000, 0);
    d.line("W", 6000, 0, 6000, 4000);
    d.line("W", 6000, 4000, 0, 4000);
    d.line("W", 0, 4000, 0, 0);
    d.line("W", 150, 150, 5850, 150);
    d.line("W", 5850, 150, 5850, 3850);
    d.line("W", 5850, 3850, 150, 3850);
    d.line("W", 150, 3850, 150, 150);
  }
  d.write((dir / "d.dxf").string());
  ASSERT_GT(fs::file_size(dir / "d.dxf"), 250'000u);
  const std::string out = (dir / "b.yaml").string();
  const auto r = run_bounded("import " + (dir / "d.dxf").string() + " --wall-layers W -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err.substr(0, 2000);
  EXPECT_LT(r.err.size(), 16'000u);
  EXPECT_TRUE(contains(r.err, "and 6342 more of the same kind: face lines drawn twice, read once"));
  EXPECT_TRUE(contains(r.out, "4 walls (4 with their drawn thickness)")) << r.out;
  const auto valid = run_bounded("validate " + out);
  EXPECT_EQ(valid.exit_code, 0) << valid.err;
  fs::remove_all(dir);
}

// A second DATA section after the first one's ENDSEC: refused with the file and its line.
TEST(ImportHostile, ASecondDataSectionIsRefusedWithTheFileAndLine) {
  const fs::path dir = testing::scratch_dir("import_cli", "second_data");
  std::string text = testing::slurp(testing::source_path("tests/data/ifc/house_ifc4.ifc"));
  const std::size_t end = text.rfind("END-ISO-10303-21;");
  text.insert(end, "DATA;\n#5=IFCCARTESIANPOINT((1.0E999,0.,0.));\nENDSEC;\n");
  const int line =
      1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(end), '\n'));
  const fs::path model = dir / "two.ifc";
  std::ofstream(model) << text;
  const auto r = run_bounded("import " + model.string() + " -o " + (dir / "b.yaml").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(
      contains(r.err, model.string() + ":" + std::to_string(line) + ": a second DATA section"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "b.yaml"));
  fs::remove_all(dir);
}

// Storeys (each matched against every wall) up to a building's floors, 500; a wall's axis
// up to 1,000 straight pieces. At the limit: imported; one past it: refused, naming it.
TEST(ImportHostile, StoreysAndAWallsPiecesAreTakenUpToTheirLimits) {
  const fs::path dir = testing::scratch_dir("import_cli", "limits");
  const auto import = [&](const std::string& kind, int n) {
    const std::string model = (dir / (kind + std::to_string(n) + ".ifc")).string();
    EXPECT_EQ(make_ifc("--" + kind + " " + std::to_string(n) + " " + model).exit_code, 0);
    return run_bounded("import " + model + " -o " +
                       (dir / (kind + std::to_string(n) + ".yaml")).string());
  };
  const auto storeys = import("storeys", 500);
  EXPECT_EQ(storeys.exit_code, 0) << storeys.err.substr(0, 2000);
  EXPECT_TRUE(contains(storeys.err, "and 449 more of the same kind: storeys without walls"));
  const auto too_many = import("storeys", 501);
  EXPECT_EQ(too_many.exit_code, 2);
  EXPECT_TRUE(contains(too_many.err, "storeys501.ifc: IfcBuildingStorey "));
  EXPECT_TRUE(contains(too_many.err,
                       "'Storey 501': the model has storeys at 501 elevations; "
                       "ccbuild takes buildings of at most 500 floors"))
      << too_many.err;
  const auto zigzag = import("zigzag", 1000);
  EXPECT_EQ(zigzag.exit_code, 0) << zigzag.err.substr(0, 2000);
  EXPECT_TRUE(contains(zigzag.out, "1 floors, 1000 walls")) << zigzag.out;
  const auto turns = import("zigzag", 1001);
  EXPECT_EQ(turns.exit_code, 2);
  EXPECT_TRUE(contains(turns.err,
                       "'Zigzag': its axis turns into 1001 straight pieces; ccbuild "
                       "reads walls of at most 1000"))
      << turns.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild
