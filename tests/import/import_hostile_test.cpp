// Issue 49: hostile drawings and models, each generated here: duplicated and crowding lines,
// faces at the edges of the pairing rules, and STEP text that IFC++ reads differently from
// the standard (a second DATA section, comments, strings, white space, NaN, NUL). Each is
// read correctly or refused with the file and the line.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "ccbuild/floors/plan.hpp"
#include "ccbuild/import/dxf.hpp"
#include "ccbuild/import/ifc.hpp"
#include "dxf_writer.hpp"
#include "test_support.hpp"

namespace ccbuild::import {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::DxfWriter;
using testing::expect_input_error;

fs::path scratch(const std::string& name) {
  return testing::scratch_dir("import_hostile", name);
}

DxfOptions faces() {
  DxfOptions o;
  o.wall_layers = {"W"};
  return o;
}

std::size_t notes_containing(const std::vector<std::string>& notes, const std::string& part) {
  std::size_t n = 0;
  for (const auto& note : notes) n += note.find(part) != std::string::npos ? 1 : 0;
  return n;
}

// The 0.3 MB drawing of the fuzz: one wall's two faces drawn 1,500 times each (every other
// copy reversed), beside a wall drawn once. Each face is read once, each copy said, the
// first 50 one by one and the rest in one line.
TEST(DxfHostile, DuplicatedFaceLinesAreReadOnceAndSaidInAFewLines) {
  DxfWriter d(4);  // millimetres
  for (int copy = 0; copy < 1500; ++copy) {
    if (copy % 2 == 0) {
      d.line("W", 0, 0, 4000, 0);
      d.line("W", 4000, 200, 0, 200);
    } else {
      d.line("W", 4000, 0, 0, 0);
      d.line("W", 0, 200, 4000, 200);
    }
  }
  d.line("W", 0, 2000, 3000, 2000);
  d.line("W", 0, 2300, 3000, 2300);
  const fs::path dir = scratch("duplicated");
  d.write((dir / "d.dxf").string());
  const DxfPlan read = read_dxf_plan(dir / "d.dxf", faces());
  ASSERT_EQ(read.plan.walls.size(), 2u);
  EXPECT_NEAR(*read.plan.walls[0].thickness_m, 0.2, 1e-12);
  EXPECT_NEAR(read.plan.wall_length_m(read.plan.walls[0]), 4.0, 1e-9);
  EXPECT_NEAR(*read.plan.walls[1].thickness_m, 0.3, 1e-12);
  EXPECT_NO_THROW(floors::validate_plan(read.plan, 3.0));
  EXPECT_EQ(notes_containing(read.notes, "is drawn over entity"), 50u);
  ASSERT_EQ(read.notes.size(), 51u);
  EXPECT_EQ(read.notes.back(), "and 2948 more of the same kind: face lines drawn twice, read once");
  fs::remove_all(dir);
}

// The same faces copied 600 times, each copy 1 mm further along: no copy is another's
// duplicate, and every one faces every other across the wall. Refused where they crowd,
// with the entity's line, before the pairs run out of memory.
TEST(DxfHostile, LinesDrawnOverAndOverAreRefusedWhereTheyCrowd) {
  DxfWriter d(4);
  for (int copy = 0; copy < 600; ++copy) {
    d.line("W", copy, 0, 4000 + copy, 0);
    d.line("W", copy, 200, 4000 + copy, 200);
  }
  const fs::path dir = scratch("crowd");
  d.write((dir / "d.dxf").string());
  const InputError e = expect_input_error([&] { read_dxf_plan(dir / "d.dxf", faces()); });
  EXPECT_EQ(e.first().file, (dir / "d.dxf").string());
  std::smatch handle;
  const std::string field = e.first().field;
  ASSERT_TRUE(std::regex_match(field, handle, std::regex("entity ([0-9A-F]+)"))) << field;
  EXPECT_EQ(e.first().line, DxfWriter::handle_line(std::stoi(handle[1].str(), nullptr, 16)));
  EXPECT_TRUE(contains(e.what(), "more than 64 pairs of face lines per line lie within 0.6000 m"))
      << e.what();
  fs::remove_all(dir);
}

// Centrelines drawn over each other, partly (each copy 50 mm along): each is a wall, as
// centrelines are, and validation refuses the 4,740 overlaps in a screenful: the first 50,
// then how many more.
TEST(DxfHostile, CentrelinesDrawnOverEachOtherAreRefusedInAScreenful) {
  DxfWriter d(4);
  for (int copy = 0; copy < 100; ++copy) d.line("W", 50.0 * copy, 0, 4000 + 50.0 * copy, 0);
  d.line("W", 0, 0, 0, 3000);
  const fs::path dir = scratch("overlapping");
  d.write((dir / "d.dxf").string());
  DxfOptions o = faces();
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  const DxfPlan read = read_dxf_plan(dir / "d.dxf", o);
  EXPECT_EQ(read.plan.walls.size(), 101u);
  const InputError e = expect_input_error([&] { floors::validate_plan(read.plan, 3.0); });
  ASSERT_EQ(e.diagnostics().size(), 51u);
  EXPECT_TRUE(contains(e.diagnostics()[0].message, "overlaps wall")) << e.what();
  EXPECT_EQ(e.diagnostics().back().message,
            "and 4690 more problems (the first 50 are listed above)");
  fs::remove_all(dir);
}

// Faces a tenth of a degree either side of the x axis fall in the first and the last
// half-degree buckets of direction: they are still compared, and pair.
TEST(DxfHostile, FacesEitherSideOfTheXAxisPairAcrossTheLastBucket) {
  DxfWriter d(4);
  const double rise = 2000.0 * std::tan(0.1 * M_PI / 180.0);
  d.line("W", 0, 0, 2000, rise);          // 0.1 degrees
  d.line("W", 2000, 200 - rise, 0, 200);  // 179.9 degrees
  const fs::path dir = scratch("wrap");
  d.write((dir / "d.dxf").string());
  const DxfPlan read = read_dxf_plan(dir / "d.dxf", faces());
  ASSERT_EQ(read.plan.walls.size(), 1u);
  // As thick as the faces are apart where the second starts (they close in by 7 mm).
  EXPECT_NEAR(*read.plan.walls[0].thickness_m, 0.2 - 2 * rise / 1000.0, 1e-6);
  fs::remove_all(dir);
}

// Faces a little off parallel (0.5 degrees) pair as long as they stay within the maximum
// thickness over the stretch they share; ones that drift past it at one end do not.
TEST(DxfHostile, FacesPairOnlyWhereTheyStayWithinTheMaximumThickness) {
  for (const double far_mm : {590.0, 640.0}) {
    SCOPED_TRACE(far_mm);
    DxfWriter d(4);
    d.line("W", 0, 0, 10000, 0);
    d.line("W", 0, 550, 10000, far_mm);
    const fs::path dir = scratch("drift");
    d.write((dir / "d.dxf").string());
    if (far_mm < 600.0) {
      EXPECT_EQ(read_dxf_plan(dir / "d.dxf", faces()).plan.walls.size(), 1u);
    } else {
      const InputError e = expect_input_error([&] { read_dxf_plan(dir / "d.dxf", faces()); });
      EXPECT_TRUE(contains(e.what(), "no wall found")) << e.what();
      EXPECT_TRUE(contains(e.what(), "with no parallel face within 0.6 m")) << e.what();
    }
    fs::remove_all(dir);
  }
}

// A door insert off its wall's centreline, within 0.3 m of its face: on that wall.
TEST(DxfHostile, AnInsertBesideItsWallsFaceLiesOnIt) {
  std::string text = testing::slurp(testing::source_path("tests/data/drawings/centrelines_m.dxf"));
  // The door sits on the wall between the rooms at x = 3.0; move it 0.25 m off it.
  const std::string door = "INSERT\n5\n";
  const std::size_t at = text.find(door);
  ASSERT_NE(at, std::string::npos);
  const std::size_t x = text.find("\n10\n", at);
  const std::size_t x_end = text.find('\n', x + 4);
  text.replace(x + 4, x_end - (x + 4), "3.25");
  const fs::path dir = scratch("insert");
  std::ofstream(dir / "d.dxf") << text;
  DxfOptions o;
  o.wall_layers = {"WALLS"};
  o.door_layers = {"DOORS"};
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  const DxfPlan read = read_dxf_plan(dir / "d.dxf", o);
  ASSERT_EQ(read.plan.openings.size(), 1u) << (read.notes.empty() ? "" : read.notes[0]);
  const floors::Wall& on = *read.plan.find_wall(read.plan.openings[0].wall_id);
  EXPECT_NEAR(read.plan.wall_start_m(on).x(), 3.0, 1e-9);
  EXPECT_NEAR(read.plan.wall_end_m(on).x(), 3.0, 1e-9);
  fs::remove_all(dir);
}

// --- STEP text that IFC++ reads otherwise than the standard says ---------------------

std::string house_text() {
  return testing::slurp(testing::source_path("tests/data/ifc/house_ifc4.ifc"));
}

int line_of(const std::string& text, const std::string& part) {
  const std::size_t at = text.find(part);
  EXPECT_NE(at, std::string::npos) << part;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

/// The house with `statements` put at the end of its DATA section (before its ENDSEC).
std::string with_data(const std::string& statements) {
  std::string text = house_text();
  const std::size_t end = text.rfind("ENDSEC;");
  text.insert(end, statements);
  return text;
}

/// Refused, naming the file and the line where `part` is.
void expect_refused_at(const std::string& text, const std::string& part, const std::string& message,
                       const std::string& name) {
  SCOPED_TRACE(name);
  const fs::path dir = scratch("step");
  const fs::path file = dir / (name + ".ifc");
  std::ofstream(file, std::ios::binary) << text;
  const InputError e = expect_input_error([&] { read_ifc_building(file); });
  EXPECT_EQ(e.first().file, file.string());
  EXPECT_EQ(e.first().line, line_of(text, part)) << e.what();
  EXPECT_TRUE(contains(e.what(), message));
  fs::remove_all(dir);
}

TEST(IfcHostile, ASecondDataSectionIsRefusedWithItsLine) {
  // The fuzz's case: a second DATA section moving a wall's placement point, or NaN in it.
  std::string text = house_text();
  const std::string second = "DATA;\n#5=IFCCARTESIANPOINT((1.0E999,0.,0.));\nENDSEC;\n";
  text.insert(text.rfind("END-ISO-10303-21;"), second);
  expect_refused_at(text, "DATA;\n#5=", "a second DATA section: ccbuild reads models of one",
                    "second_data");
  std::string finite = house_text();
  finite.insert(finite.rfind("END-ISO-10303-21;"),
                "DATA;\n#5=IFCCARTESIANPOINT((5000.,0.,0.));\nENDSEC;\n");
  expect_refused_at(finite, "DATA;\n#5=", "a second DATA section", "second_data_finite");
  // An entity after the ENDSEC without a DATA of its own: IFC++ reads it all the same.
  std::string after = house_text();
  after.insert(after.rfind("END-ISO-10303-21;"), "#5=IFCCARTESIANPOINT((5000.,0.,0.));\n");
  expect_refused_at(after, "#5=IFCCARTESIANPOINT((5000.", "after the DATA section's ENDSEC",
                    "entity_after_endsec");
  // And after the end.
  expect_refused_at(house_text() + "#5=IFCCARTESIANPOINT((5000.,0.,0.));\n",
                    "#5=IFCCARTESIANPOINT((5000.", "after END-ISO-10303-21;", "after_end");
}

TEST(IfcHostile, NumbersAreCheckedAsIfcPlusPlusReadsThem) {
  // IFC++ drops white space: "1. E999" is one number to it.
  const std::string spaced = "#99999=IFCCARTESIANPOINT((1. E999,0.,0.));\n";
  expect_refused_at(with_data(spaced), spaced, "the number 1.E999 is not a finite number",
                    "spaced");
  // std::stod reads nan and inf.
  for (const std::string word : {"NAN", "inf", "Infinity"}) {
    const std::string st = "#99999=IFCCARTESIANPOINT((" + word + ",0.,0.));\n";
    expect_refused_at(with_data(st), st, "the number " + word + " is not a finite number", word);
  }
  // A comment ends at the first '/' after a '*', the opening one's too: "/*/" is a whole
  // comment to IFC++, and what follows it is read.
  const std::string comment = "/*/ #99999=IFCCARTESIANPOINT((1.0E999,0.,0.)); */\n";
  expect_refused_at(with_data(comment), comment, "the number 1.0E999", "comment");
  // \' does not end a string to IFC++, and the quote after it does: what follows is read.
  const std::string quote = "#99998=IFCLABEL('a\\'');#99999=IFCCARTESIANPOINT((1.0E999,0.,0.));\n";
  expect_refused_at(with_data(quote + "#99997=IFCLABEL('');\n"), "#99999=", "the number 1.0E999",
                    "backslash_quote");
}

TEST(IfcHostile, TextIfcPlusPlusWouldReadElsewhereIsRefused) {
  // A NUL byte: IFC++ stops reading there.
  const std::string nul = std::string("#99999=IFCLABEL('a") + '\0' + "');\n";
  expect_refused_at(with_data(nul), "#99999=", "a NUL byte", "nul");
  // "DATA;" in the header: IFC++ would start reading entities there.
  std::string header = house_text();
  header.replace(header.find("'ViewDefinition [CoordinationView]'"), 35, "'DATA;'");
  expect_refused_at(header, "DATA;\n#1=", "IFC++ reads from an earlier 'DATA;'", "data_in_header");
  // A statement in the DATA section that is no entity: IFC++ reads no entity after it.
  const std::string stray = "IFCWALL('x');\n";
  expect_refused_at(with_data(stray), stray, "holds entity instances (#1=...) only", "stray");
}

}  // namespace
}  // namespace ccbuild::import
