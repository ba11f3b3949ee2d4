// Issue 49: drawings as big as ccbuild takes, generated here, read in near-linear time: the
// searches for faces to pair, ends to join and gaps to close look only near each line.
// CTest's TIMEOUT (60 s, tests/CMakeLists.txt) catches a blow-up; the tests assert the
// result, never a time.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>

#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/import/dxf.hpp"
#include "dxf_writer.hpp"
#include "test_support.hpp"

namespace ccbuild::import {
namespace {
namespace fs = std::filesystem;
using testing::DxfWriter;

// 100,000 walls (as many as a floor takes), each two horizontal face lines in one angle
// bucket: 2 m long, 0.2 m thick, in rows 1 m apart (0.8 m between the faces of two rows:
// more than the thickest wall) and 3 m apart along them. Each pair of faces is one wall.
TEST(DxfScale, AHundredThousandParallelFacePairsAreAHundredThousandWalls) {
  const int columns = 400, rows = 250;
  static_assert(400 * 250 == floors::limits::kMaxWalls);
  DxfWriter d(6);  // metres
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const double x = 3.0 * c, y = 1.0 * r;
      d.line("W", x, y, x + 2.0, y);
      d.line("W", x + 2.0, y + 0.2, x, y + 0.2);
    }
  const fs::path dir = testing::scratch_dir("import_scale", "pairs");
  d.write((dir / "pairs.dxf").string());
  DxfOptions o;
  o.wall_layers = {"W"};
  const DxfPlan read = read_dxf_plan(dir / "pairs.dxf", o);
  EXPECT_TRUE(read.notes.empty()) << read.notes.front();
  ASSERT_EQ(read.plan.walls.size(), static_cast<std::size_t>(columns * rows));
  // Each wall along the middle of its faces, as long as they are, once.
  std::map<std::pair<long, long>, int> starts;
  std::map<std::int64_t, Eigen::Vector2d> at;  // (FloorPlan's lookups are linear)
  for (const auto& v : read.plan.vertices) at[v.id] = v.position_m;
  for (const auto& w : read.plan.walls) {
    ASSERT_NEAR(*w.thickness_m, 0.2, 1e-12);
    const Eigen::Vector2d a = at.at(w.start_vertex), b = at.at(w.end_vertex);
    ASSERT_NEAR(std::abs(b.x() - a.x()), 2.0, 1e-9);
    const double y = a.y() - 0.1;
    ASSERT_NEAR(y, std::round(y), 1e-9);
    ASSERT_NEAR(b.y(), a.y(), 1e-12);
    ++starts[{std::lround(std::min(a.x(), b.x()) / 3.0), std::lround(y)}];
  }
  EXPECT_EQ(starts.size(), static_cast<std::size_t>(columns * rows));
  fs::remove_all(dir);
}

// A dashed line of 20,000 dashes (0.4 m drawn, 0.6 m left) read with gap_openings: one wall
// with an opening in each of its 19,999 gaps, every other one a window (a glazing line in
// it), the rest doors.
TEST(DxfScale, TwentyThousandDashesAreOneWallWithAnOpeningInEachGap) {
  const int dashes = 20000;
  DxfWriter d(6);
  for (int k = 0; k < dashes; ++k) d.line("W", 1.0 * k, 5.0, 1.0 * k + 0.4, 5.0);
  for (int k = 0; k + 1 < dashes; k += 2) d.line("G", 1.0 * k + 0.5, 5.0, 1.0 * k + 0.9, 5.0);
  const fs::path dir = testing::scratch_dir("import_scale", "dashes");
  d.write((dir / "dashes.dxf").string());
  DxfOptions o;
  o.wall_layers = {"W"};
  o.window_layers = {"G"};
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  o.gap_openings = true;
  const DxfPlan read = read_dxf_plan(dir / "dashes.dxf", o);
  ASSERT_EQ(read.plan.walls.size(), 1u);
  EXPECT_NEAR(read.plan.wall_length_m(read.plan.walls[0]), dashes - 0.6, 1e-6);
  ASSERT_EQ(read.plan.openings.size(), static_cast<std::size_t>(dashes - 1));
  // The chain starts at the first dash's free end: offsets from x = 0.
  EXPECT_NEAR(read.plan.wall_start_m(read.plan.walls[0]).x(), 0.0, 1e-12);
  for (int k = 0; k + 1 < dashes; ++k) {
    const floors::Opening& g = read.plan.openings[static_cast<std::size_t>(k)];
    ASSERT_NEAR(g.width_m, 0.6, 1e-9) << k;
    ASSERT_NEAR(g.offset_m, k + 0.4, 1e-6) << k;  // gap k: from x = k + 0.4 to k + 1
    ASSERT_EQ(g.id[1], k % 2 == 0 ? 'W' : 'D') << k;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::import
