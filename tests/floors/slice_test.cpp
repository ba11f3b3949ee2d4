// Slicing: layer counts, which wall pieces exist at which height, point merging, and the
// geometry hash that lets later stages plan each distinct layer once.

#include "ccbuild/floors/slice.hpp"

#include <gtest/gtest.h>

#include "ccbuild/floors/plan.hpp"
#include "test_support.hpp"

namespace ccbuild::floors {
namespace {

// One 10 m wall along x with a door (1-2 m, up to 2.1 m) and a window (5-7 m, 1.0-2.0 m).
FloorPlan wall_with_door_and_window() {
  FloorPlan plan;
  plan.vertices = {{1, {0, 0}, {}}, {2, {10, 0}, {}}};
  plan.walls = {{7, 1, 2, std::nullopt, {}}};
  plan.openings = {{"D1", 7, 1.0, 1.0, 0.0, 2.1, {}}, {"W1", 7, 5.0, 2.0, 1.0, 2.0, {}}};
  validate_plan(plan, 3.0);
  return plan;
}

Floor as_floor(const FloorPlan& plan, double height_m) {
  Floor floor;
  floor.name = "test";
  floor.height_m = height_m;
  floor.plan = plan;
  return floor;
}

// The pieces of a layer as (start, end) offsets along x.
std::vector<std::pair<double, double>> pieces(const Layer& layer) {
  std::vector<std::pair<double, double>> out;
  for (const auto& s : layer.segments) out.emplace_back(layer.start_m(s).x(), layer.end_m(s).x());
  return out;
}

using Pieces = std::vector<std::pair<double, double>>;

TEST(Slice, LayerCountIsCeilingOfHeightOverLayerHeight) {
  EXPECT_EQ(layer_count(3.0, 0.1), 30);  // not 31 from rounding
  EXPECT_EQ(layer_count(3.05, 0.1), 31);
  EXPECT_EQ(layer_count(3.0, 0.7), 5);
  EXPECT_EQ(layer_count(0.2, 0.5), 1);
  EXPECT_EQ(layer_count(10 * 0.3048, 0.4 * 0.3048), 25);
  // 2.7 / 0.03 is 90.00000000000001 in floating point: still 90 layers, and a hair more
  // than a whole number of layers is one more.
  EXPECT_EQ(layer_count(2.7, 0.03), 90);
  EXPECT_EQ(layer_count(2.7 + 1e-6, 0.03), 91);
  EXPECT_EQ(layer_count(0.03, 0.03), 1);
  EXPECT_EQ(layer_count(0.029, 0.03), 1);
}

TEST(Slice, DoorAndWindowCutTheRightLayers) {
  const auto layers = slice_floor(as_floor(wall_with_door_and_window(), 3.0), 0.5);
  ASSERT_EQ(layers.size(), 6u);  // mid-heights 0.25, 0.75, ..., 2.75
  const Pieces door_only = {{0, 1}, {2, 10}};
  const Pieces door_and_window = {{0, 1}, {2, 5}, {7, 10}};
  const Pieces whole = {{0, 10}};
  EXPECT_EQ(pieces(layers[0]), door_only);
  EXPECT_EQ(pieces(layers[1]), door_only);
  EXPECT_EQ(pieces(layers[2]), door_and_window);
  EXPECT_EQ(pieces(layers[3]), door_and_window);
  EXPECT_EQ(pieces(layers[4]), whole);  // 2.25 is above both heads
  EXPECT_EQ(pieces(layers[5]), whole);
  // Pieces keep their origin: wall 7, numbered from the wall's start.
  for (const auto& s : layers[2].segments) {
    EXPECT_EQ(s.wall_id, 7);
    EXPECT_EQ(s.piece_count, 3);
  }
  EXPECT_EQ(layers[2].segments[2].piece, 2);
  EXPECT_DOUBLE_EQ(layers[2].total_length_m(), 1.0 + 3.0 + 3.0);
}

TEST(Slice, OpeningIntervalIsClosedAtSillOpenAtHead) {
  FloorPlan plan = wall_with_door_and_window();
  plan.openings = {{"W", 7, 4.0, 2.0, 0.75, 1.25, {}}};
  // Mid-heights of 0.5 m layers: 0.25, 0.75 (== sill: cut), 1.25 (== head: not cut).
  const auto layers = slice_floor(as_floor(plan, 1.5), 0.5);
  ASSERT_EQ(layers.size(), 3u);
  EXPECT_EQ(layers[0].segments.size(), 1u);
  EXPECT_EQ(layers[1].segments.size(), 2u);
  EXPECT_EQ(layers[2].segments.size(), 1u);
}

// Issue 50: walls at their own height. A wall stops where its top is at or below a layer's
// mid-height, like an opening's head: one point is a wall of one height, three a gable.
TEST(Slice, AWallStopsAtItsTopAndAGableStepsUpLayerByLayer) {
  FloorPlan plan;
  plan.vertices = {{1, {0, 0}, {}}, {2, {6, 0}, {}}, {3, {6, 4}, {}}, {4, {0, 4}, {}}};
  plan.walls = {{1, 1, 2, std::nullopt, {}},
                {2, 2, 3, std::nullopt, {}},
                {3, 3, 4, std::nullopt, {}},
                {4, 4, 1, std::nullopt, {}}};
  plan.walls[0].top_m = {{0.0, 0.625}};                        // a knee wall
  plan.walls[1].top_m = {{0.0, 0.04}};                         // under the first mid
  plan.walls[2].top_m = {{0.0, 2.2}, {3.0, 4.5}, {6.0, 2.2}};  // a gable to 4.5 m
  validate_plan(plan, 4.6);
  const auto layers = slice_floor(as_floor(plan, 4.6), 0.1);
  ASSERT_EQ(layers.size(), 46u);
  const auto length_of = [&](const Layer& layer, std::int64_t wall) {
    double m = 0.0;
    for (const auto& s : layer.segments)
      if (s.wall_id == wall) m += s.length_m;
    return m;
  };
  // The knee wall: mids 0.05 to 0.55 print it, 0.65 does not. In layers of 0.25 m, whose
  // mids are exact in binary, the mid 0.625 at its top exactly leaves it out.
  EXPECT_NEAR(length_of(layers[5], 1), 6.0, 1e-12);
  EXPECT_EQ(length_of(layers[6], 1), 0.0);
  const auto quarters = slice_floor(as_floor(plan, 4.6), 0.25);
  EXPECT_NEAR(length_of(quarters[1], 1), 6.0, 1e-12);  // mid 0.375
  EXPECT_EQ(length_of(quarters[2], 1), 0.0);           // mid 0.625
  // Lower than half a layer: in no layer at all.
  for (const auto& layer : layers) EXPECT_EQ(length_of(layer, 2), 0.0) << layer.index;
  // The gable: whole under its eaves (mid 2.15), then the part whose top is above the mid:
  // |s - 3| < 3 (4.5 - mid) / 2.3, symmetric about the ridge; the ridge on the boundary
  // between layers 44 and 45 leaves layer 44 (mid 4.45) a piece and layer 45 none.
  EXPECT_NEAR(length_of(layers[21], 3), 6.0, 1e-12);
  for (int k : {22, 30, 44}) {
    const double mid = 0.1 * k + 0.05;
    EXPECT_NEAR(length_of(layers[k], 3), 6.0 * (4.5 - mid) / 2.3, 1e-9) << k;
  }
  EXPECT_EQ(length_of(layers[45], 3), 0.0);
  // The untopped wall is whole throughout; layers alike share their cut.
  EXPECT_NEAR(length_of(layers[45], 4), 4.0, 1e-12);
  EXPECT_EQ(layers[7].geometry_hash, layers[20].geometry_hash);
  EXPECT_NE(layers[22].geometry_hash, layers[23].geometry_hash);
}

TEST(Slice, LastLayerMayBeThinner) {
  const auto layers = slice_floor(as_floor(wall_with_door_and_window(), 2.3), 0.5);
  ASSERT_EQ(layers.size(), 5u);
  EXPECT_DOUBLE_EQ(layers.back().z_bottom_m, 2.0);
  EXPECT_DOUBLE_EQ(layers.back().z_top_m, 2.3);
}

TEST(Slice, IdenticalLayersShareAHashEvenWhenNotConsecutive) {
  FloorPlan plan = wall_with_door_and_window();
  plan.openings = {{"W1", 7, 5.0, 2.0, 1.0, 2.0, {}}};  // window band only
  const auto layers = slice_floor(as_floor(plan, 3.0), 0.5);
  EXPECT_EQ(layers[0].geometry_hash, layers[1].geometry_hash);
  EXPECT_NE(layers[1].geometry_hash, layers[2].geometry_hash);
  EXPECT_EQ(layers[2].geometry_hash, layers[3].geometry_hash);
  EXPECT_EQ(layers[0].geometry_hash, layers[4].geometry_hash);  // below and above the window
  EXPECT_EQ(layers[0].geometry_hash, layers[5].geometry_hash);
}

TEST(Slice, HashIgnoresWallIdsAndOrderButNotGeometry) {
  FloorPlan a;
  a.vertices = {{1, {0, 0}, {}}, {2, {4, 0}, {}}, {3, {4, 3}, {}}};
  a.walls = {{1, 1, 2, std::nullopt, {}}, {2, 2, 3, std::nullopt, {}}};
  FloorPlan b = a;
  b.walls = {{20, 3, 2, std::nullopt, {}},
             {10, 1, 2, std::nullopt, {}}};  // other ids, order, direction
  EXPECT_EQ(plan_as_layer(a).geometry_hash, plan_as_layer(b).geometry_hash);
  b.vertices[2].position_m.y() = 3.001;
  EXPECT_NE(plan_as_layer(a).geometry_hash, plan_as_layer(b).geometry_hash);
}

TEST(Slice, SharedEndpointsMergeWithinTolerance) {
  FloorPlan plan;
  // Walls 1 and 2 meet at (4, 0) give or take half a millimetre; wall 3 starts 5 mm away.
  plan.vertices = {{1, {0, 0}, {}},      {2, {4, 0}, {}},     {3, {4.0005, 0.0003}, {}},
                   {4, {4.0005, 3}, {}}, {5, {4.005, 0}, {}}, {6, {8, 0}, {}}};
  plan.walls = {
      {1, 1, 2, std::nullopt, {}}, {2, 3, 4, std::nullopt, {}}, {3, 5, 6, std::nullopt, {}}};
  const Layer layer = plan_as_layer(plan);
  ASSERT_EQ(layer.segments.size(), 3u);
  EXPECT_EQ(layer.segments[0].end_point, layer.segments[1].start_point);
  EXPECT_NE(layer.segments[0].end_point, layer.segments[2].start_point);
  EXPECT_EQ(layer.points.size(), 5u);
}

TEST(Slice, CottageDoorLayersSplitThePartition) {
  const FloorPlan plan = load_plan(testing::data("plans/cottage.yaml"));
  const auto layers = slice_floor(as_floor(plan, 3.0), 0.5);
  // Layer 0 (mid 0.25 m): door in wall 7 only. Layer 2 (mid 1.25 m): door and window.
  auto count = [](const Layer& l, std::int64_t id) {
    int n = 0;
    for (const auto& s : l.segments) n += s.wall_id == id;
    return n;
  };
  EXPECT_EQ(count(layers[0], 7), 2);
  EXPECT_EQ(count(layers[0], 3), 1);
  EXPECT_EQ(count(layers[2], 7), 2);
  EXPECT_EQ(count(layers[2], 3), 2);
  EXPECT_EQ(count(layers[5], 7), 1);
}

}  // namespace
}  // namespace ccbuild::floors
