// Walls thicker than one bead sliced into beads: skins along the faces and around the
// ends, then the pattern's core or ties; at L, T and X junctions, at openings, and at the
// thicknesses where the number of beads changes.

#include <gtest/gtest.h>

#define BOOST_ALLOW_DEPRECATED_HEADERS
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#undef BOOST_ALLOW_DEPRECATED_HEADERS

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/beads.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/slice.hpp"
#include "plans.hpp"

namespace ccbuild::floors {
namespace {

constexpr double kBead = 0.15;
constexpr double kTol = 1e-6;

using Vec = Eigen::Vector2d;

struct WallSpec {
  double x0, y0, x1, y1, thickness;
};

FloorPlan plan_of(const std::vector<WallSpec>& walls, WallPattern pattern = WallPattern::kSolid) {
  std::vector<std::array<double, 4>> lines;
  std::vector<double> thicknesses;
  for (const auto& w : walls) {
    lines.push_back({w.x0, w.y0, w.x1, w.y1});
    thicknesses.push_back(w.thickness);
  }
  FloorPlan plan = testing::plan_from_walls(lines, thicknesses);
  plan.beads = {kBead, pattern};
  return plan;
}

double cross(const Vec& a, const Vec& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double point_segment(const Vec& p, const Vec& a, const Vec& b) {
  const Vec d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

namespace bg = boost::geometry;
using Footprint = bg::model::polygon<bg::model::d2::point_xy<double>>;

// The ground a bead covers: its centre line widened by half its width each side.
Footprint footprint(const Vec& a, const Vec& b, double width_m) {
  const Vec d = (b - a).normalized();
  const Vec h = 0.5 * width_m * Vec(-d.y(), d.x());
  Footprint f;
  for (const Vec& v : {Vec(a - h), Vec(a + h), Vec(b + h), Vec(b - h), Vec(a - h)})
    bg::append(f.outer(), bg::model::d2::point_xy<double>(v.x(), v.y()));
  bg::correct(f);
  return f;
}

double overlap_m2(const Footprint& f, const Footprint& g) {
  std::vector<Footprint> common;
  bg::intersection(f, g, common);
  double area = 0.0;
  for (const auto& c : common) area += bg::area(c);
  return area;
}

// The wall (of the plan) whose outline, reaching past a junction end by half the thickest
// wall met there, holds `p` with `margin` to spare across; -1 when none does.
std::int64_t wall_holding(const FloorPlan& plan, const Vec& p, double margin) {
  for (const auto& w : plan.walls) {
    const Vec a = plan.wall_start_m(w), b = plan.wall_end_m(w);
    const double length = (b - a).norm();
    const Vec dir = (b - a) / length, normal(-dir.y(), dir.x());
    double reach[2] = {0.0, 0.0};
    for (const auto& o : plan.walls) {
      if (o.id == w.id) continue;
      const Vec c = plan.wall_start_m(o), d = plan.wall_end_m(o);
      if (point_segment(a, c, d) < kTol) reach[0] = std::max(reach[0], 0.5 * *o.thickness_m);
      if (point_segment(b, c, d) < kTol) reach[1] = std::max(reach[1], 0.5 * *o.thickness_m);
    }
    const double s = (p - a).dot(dir), n = (p - a).dot(normal);
    if (s >= -reach[0] - kTol && s <= length + reach[1] + kTol &&
        std::abs(n) <= 0.5 * *w.thickness_m - margin + kTol)
      return w.id;
  }
  return -1;
}

// What every bead layer must hold: each bead inside a wall's outline by half its width;
// no two beads' footprints overlap unless they meet end to end (at a corner, where they
// share the corner's square), and those never double back along each other; bead widths
// the nozzle's (the core excepted).
void expect_sound(const FloorPlan& plan, const Layer& layer) {
  ASSERT_FALSE(layer.segments.empty());
  for (const auto& s : layer.segments) {
    const Vec a = layer.start_m(s), b = layer.end_m(s);
    // A pass or skin at its wall's width by the rule; the default spec's is the nozzle's.
    if (s.role != BeadRole::kCore) {
      const Wall& w = *plan.find_wall(s.wall_id);
      const double expected = wall_beads(w.thickness_m.value_or(kBead), plan.beads).bead_width_m;
      EXPECT_NEAR(s.width_m, expected, kTol) << "wall " << s.wall_id;
      if (plan.beads.narrowest_m == 0.0) EXPECT_NEAR(s.width_m, kBead, kTol);
    }
    for (const Vec& p : {a, Vec(0.5 * (a + b)), b})
      EXPECT_NE(wall_holding(plan, p, 0.5 * s.width_m), -1)
          << "wall " << s.wall_id << " piece " << s.piece << " (" << bead_role_name(s.role)
          << ") at " << p.transpose() << " is outside every wall's outline";
  }
  for (std::size_t i = 0; i < layer.segments.size(); ++i)
    for (std::size_t j = i + 1; j < layer.segments.size(); ++j) {
      const auto& s = layer.segments[i];
      const auto& t = layer.segments[j];
      const bool meet = s.start_point == t.start_point || s.start_point == t.end_point ||
                        s.end_point == t.start_point || s.end_point == t.end_point;
      const Vec a = layer.start_m(s), b = layer.end_m(s), c = layer.start_m(t), d = layer.end_m(t);
      if (meet) {
        // End to end, never doubling back along each other.
        const Vec u = (b - a).normalized(), v = (d - c).normalized();
        const bool collinear = std::abs(cross(u, v)) < 1e-9;
        const bool overlap =
            collinear && (point_segment(c, a, b) < kTol && point_segment(d, a, b) < kTol);
        EXPECT_FALSE(overlap) << "beads " << i << " and " << j << " overlap";
        continue;
      }
      // A micrometre's overlap is rounding.
      EXPECT_LE(overlap_m2(footprint(a, b, s.width_m), footprint(c, d, t.width_m)),
                1e-6 * std::max(s.width_m, t.width_m))
          << "wall " << s.wall_id << " piece " << s.piece << " (" << bead_role_name(s.role)
          << ") and wall " << t.wall_id << " piece " << t.piece << " (" << bead_role_name(t.role)
          << ") overlap";
    }
}

std::vector<const LayerSegment*> of_role(const Layer& layer, BeadRole role) {
  std::vector<const LayerSegment*> out;
  for (const auto& s : layer.segments)
    if (s.role == role) out.push_back(&s);
  return out;
}

// Every skin end is shared by exactly two skins: the skins close into rings.
void expect_closed_skins(const Layer& layer) {
  std::map<int, int> degree;
  for (const auto* s : of_role(layer, BeadRole::kSkin))
    ++degree[s->start_point], ++degree[s->end_point];
  ASSERT_FALSE(degree.empty());
  for (const auto& [point, count] : degree)
    EXPECT_EQ(count, 2) << "skin end at " << layer.points[point].transpose();
}

// The beads of one wall that run along it at `across_m` from its middle, as intervals of
// distance along it, merged; their union must be [from, to].
void expect_covered(const FloorPlan& plan, const Layer& layer, std::int64_t wall_id,
                    double across_m, double from_m, double to_m) {
  const Wall& w = *plan.find_wall(wall_id);
  const Vec a = plan.wall_start_m(w), b = plan.wall_end_m(w);
  const Vec dir = (b - a).normalized(), normal(-dir.y(), dir.x());
  std::vector<std::pair<double, double>> spans;
  for (const auto& s : layer.segments) {
    const Vec p = layer.start_m(s), q = layer.end_m(s);
    if (s.wall_id != wall_id) continue;
    if (std::abs((p - a).dot(normal) - across_m) > kTol ||
        std::abs((q - a).dot(normal) - across_m) > kTol)
      continue;
    const double u = (p - a).dot(dir), v = (q - a).dot(dir);
    spans.emplace_back(std::min(u, v), std::max(u, v));
  }
  std::sort(spans.begin(), spans.end());
  ASSERT_FALSE(spans.empty()) << "no bead at " << across_m << " across wall " << wall_id;
  EXPECT_NEAR(spans.front().first, from_m, kTol);
  double reach = spans.front().first;
  for (const auto& [u, v] : spans) {
    EXPECT_LE(u, reach + kTol) << "a gap along wall " << wall_id << " at " << across_m;
    reach = std::max(reach, v);
  }
  EXPECT_NEAR(reach, to_m, kTol);
}

// The nozzle's width only: one pass at exactly one bead, refused strictly between one and
// two (and under one), two skins and the fill from two beads on.
TEST(Beads, WithTheNozzlesWidthOnlyOneBeadOrTwoSkins) {
  const BeadSpec one{0.15, WallPattern::kSolid};
  EXPECT_EQ(wall_beads(0.15, one).how, WallPrint::kOnePass);
  EXPECT_EQ(wall_beads(0.15 + 5e-7, one).how, WallPrint::kOnePass);  // within a micrometre
  EXPECT_EQ(wall_beads(0.15 - 5e-7, one).how, WallPrint::kOnePass);
  EXPECT_NEAR(wall_beads(0.15 - 5e-7, one).bead_width_m, 0.15, 1e-12);
  EXPECT_EQ(wall_beads(0.15 - 2e-6, one).how, WallPrint::kTooThin);
  EXPECT_EQ(wall_beads(0.151, one).how, WallPrint::kBetween);
  EXPECT_EQ(wall_beads(0.299, one).how, WallPrint::kBetween);
  EXPECT_EQ(wall_beads(0.30, one).how, WallPrint::kSkinsAndFill);
  EXPECT_EQ(wall_beads(0.30 - 5e-7, one).how, WallPrint::kSkinsAndFill);  // within a micrometre
  EXPECT_EQ(wall_beads(0.30 - 2e-6, one).how, WallPrint::kBetween);
  EXPECT_EQ(wall_beads(0.60, one).how, WallPrint::kSkinsAndFill);
  EXPECT_NEAR(wall_beads(0.60, one).bead_width_m, 0.15, 1e-12);
}

// A range of widths (0.10 to 0.25 m, the nozzle 0.15 m): one pass of the wall's own width
// from the narrowest to the widest bead, both ends included; two skins of half the wall
// from there up to two nozzle widths; then skins of the nozzle's width and the fill.
TEST(Beads, ARangeOfWidthsMakesEachWallTheFewestBeads) {
  const BeadSpec range{0.15, WallPattern::kSolid, 0.10, 0.25};
  const auto how = [&](double t) { return wall_beads(t, range).how; };
  const auto width = [&](double t) { return wall_beads(t, range).bead_width_m; };
  EXPECT_EQ(how(0.10), WallPrint::kOnePass);  // exactly the narrowest
  EXPECT_NEAR(width(0.10), 0.10, 1e-12);
  EXPECT_EQ(how(0.10 - 2e-6), WallPrint::kTooThin);  // just under one bead
  EXPECT_EQ(how(0.20), WallPrint::kOnePass);
  EXPECT_NEAR(width(0.20), 0.20, 1e-12);
  EXPECT_EQ(how(0.24), WallPrint::kOnePass);  // 0.24 m masonry: one bead of its width
  EXPECT_NEAR(width(0.24), 0.24, 1e-12);
  EXPECT_EQ(how(0.25), WallPrint::kOnePass);  // exactly the widest
  EXPECT_NEAR(width(0.25), 0.25, 1e-12);
  EXPECT_EQ(how(0.25 + 2e-6), WallPrint::kTwoSkins);  // just over one bead: two
  EXPECT_NEAR(width(0.25 + 2e-6), 0.125 + 1e-6, 1e-12);
  EXPECT_EQ(how(0.27), WallPrint::kTwoSkins);  // a cavity wall's 0.27 m: two of 0.135 m
  EXPECT_NEAR(width(0.27), 0.135, 1e-12);
  EXPECT_EQ(how(0.30 - 2e-6), WallPrint::kTwoSkins);
  EXPECT_EQ(how(0.30), WallPrint::kSkinsAndFill);         // two nozzle widths: skins, no core
  EXPECT_EQ(how(0.50 + 2e-6), WallPrint::kSkinsAndFill);  // just over two widest
  EXPECT_NEAR(width(0.50), 0.15, 1e-12);
}

// Where the widest bead is under two narrowest (0.12 to 0.16 m), a wall between them is
// refused; at exactly two narrowest it is two skins.
TEST(Beads, BetweenTheWidestBeadAndTwoNarrowestAWallCannotBePrinted) {
  const BeadSpec range{0.15, WallPattern::kSolid, 0.12, 0.16};
  EXPECT_EQ(wall_beads(0.16, range).how, WallPrint::kOnePass);
  EXPECT_EQ(wall_beads(0.17, range).how, WallPrint::kBetween);
  EXPECT_EQ(wall_beads(0.24 - 4e-6, range).how, WallPrint::kBetween);
  EXPECT_EQ(wall_beads(0.24, range).how, WallPrint::kTwoSkins);
  EXPECT_NEAR(wall_beads(0.24, range).bead_width_m, 0.12, 1e-12);
}

FloorPlan ranged(const std::vector<WallSpec>& walls, WallPattern pattern = WallPattern::kSolid) {
  FloorPlan plan = plan_of(walls, pattern);
  plan.beads.narrowest_m = 0.10;
  plan.beads.widest_m = 0.25;
  return plan;
}

TEST(Beads, AWallWithinTheRangeIsOnePassOfItsOwnWidth) {
  const FloorPlan plan = ranged({{0, 0, 4, 0, 0.24}});
  const Layer layer = plan_as_layer(plan);
  ASSERT_EQ(layer.segments.size(), 1u);
  EXPECT_EQ(layer.segments[0].role, BeadRole::kPass);
  EXPECT_NEAR(layer.segments[0].width_m, 0.24, kTol);
  expect_covered(plan, layer, 1, 0.0, 0.0, 4.0);
}

// 0.27 m: two skins of 0.135 m, a quarter of the wall in from each face, closed by returns
// at the ends, and nothing between them; they lay the wall's own volume.
TEST(Beads, AWallOverTheWidestBeadIsTwoSkinsOfHalfItsWidth) {
  const double t = 0.27, skin = 0.135;
  const FloorPlan plan = ranged({{0, 0, 4, 0, t}});
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  EXPECT_TRUE(of_role(layer, BeadRole::kCore).empty());
  for (const auto& s : layer.segments) EXPECT_NEAR(s.width_m, skin, kTol);
  expect_covered(plan, layer, 1, +0.5 * skin, 0.5 * skin, 4 - 0.5 * skin);
  expect_covered(plan, layer, 1, -0.5 * skin, 0.5 * skin, 4 - 0.5 * skin);
  EXPECT_EQ(layer.segments.size(), 4u);
  double area = 0.0;
  for (const auto& s : layer.segments) area += s.width_m * s.length_m;
  EXPECT_NEAR(area, 4 * t, 1e-9);
}

// Walls of three kinds meeting: a 0.5 m wall (skins of the nozzle's width and a core), a
// 0.27 m one at an L (skins of 0.135 m) and a 0.2 m pass at a T: no bead overlaps another,
// each lies in its wall at its wall's width, and the skins close into one ring.
TEST(Beads, WallsOfDifferentBeadsMeetWithoutOverlapping) {
  const FloorPlan plan = ranged({{0, 0, 5, 0, 0.5}, {5, 0, 5, 4, 0.27}, {2.5, 0, 2.5, 3, 0.2}});
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  EXPECT_FALSE(of_role(layer, BeadRole::kCore).empty());
  bool narrow = false, pass = false;
  for (const auto& s : layer.segments) {
    narrow |= s.wall_id == 2 && std::abs(s.width_m - 0.135) < kTol;
    pass |= s.wall_id == 3 && s.role == BeadRole::kPass && std::abs(s.width_m - 0.2) < kTol;
  }
  EXPECT_TRUE(narrow);
  EXPECT_TRUE(pass);
}

TEST(Beads, AWallOneBeadThickIsOnePassAlongItsMiddle) {
  const FloorPlan plan = plan_of({{0, 0, 4, 0, kBead}});
  const Layer layer = plan_as_layer(plan);
  ASSERT_EQ(layer.segments.size(), 1u);
  EXPECT_EQ(layer.segments[0].role, BeadRole::kPass);
  EXPECT_NEAR(layer.segments[0].length_m, 4.0, kTol);
  EXPECT_NEAR(layer.segments[0].width_m, kBead, kTol);
}

TEST(Beads, AWallTwoBeadsThickIsTwoSkinsClosedAroundItsEnds) {
  const FloorPlan plan = plan_of({{0, 0, 4, 0, 2 * kBead}});
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  EXPECT_TRUE(of_role(layer, BeadRole::kCore).empty());  // nothing left between the skins
  // Each face's skin runs the wall's length less the returns' half bead at each end.
  expect_covered(plan, layer, 1, +0.5 * kBead, 0.5 * kBead, 4 - 0.5 * kBead);
  expect_covered(plan, layer, 1, -0.5 * kBead, 0.5 * kBead, 4 - 0.5 * kBead);
  EXPECT_EQ(layer.segments.size(), 4u);  // two skins and two returns
}

TEST(Beads, BetweenOneAndTwoBeadsAWallIsRefusedWithItsId) {
  FloorPlan plan = plan_of({{0, 0, 4, 0, 0.2}});
  plan.walls[0].source = {"plan.yaml", 7, "walls[0]"};
  try {
    plan_as_layer(plan);
    FAIL() << "a 0.2 m wall with 0.15 m beads was sliced";
  } catch (const InputError& e) {
    EXPECT_EQ(e.first().line, 7);
    EXPECT_EQ(e.first().field, "walls[0].thickness");
    EXPECT_NE(std::string(e.what()).find("wall 1"), std::string::npos) << e.what();
  }
}

TEST(Beads, AtAnLTheSkinsTurnTheCornerAndTheCoresMeet) {
  const double t = 3 * kBead;
  const FloorPlan plan = plan_of({{0, 0, 0, 4, t}, {0, 0, 3, 0, t}});
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  // Wall 1 runs up x = 0 from the corner; its outer face is at x = -t/2 (across +t/2).
  expect_covered(plan, layer, 1, 0.5 * t - 0.5 * kBead, -0.5 * t + 0.5 * kBead, 4 - 0.5 * kBead);
  const auto cores = of_role(layer, BeadRole::kCore);
  ASSERT_EQ(cores.size(), 2u);
  for (const auto* c : cores) EXPECT_NEAR(c->width_m, t - 2 * kBead, kTol);
  // Both cores start at the corner's middle.
  EXPECT_TRUE((layer.start_m(*cores[0]) - Vec(0, 0)).norm() < kTol ||
              (layer.end_m(*cores[0]) - Vec(0, 0)).norm() < kTol);
}

TEST(Beads, AtATAndAnXNoBeadCrossesAnother) {
  const double t = 0.45;
  const FloorPlan tee = plan_of({{0, 0, 3, 0, t}, {3, 0, 6, 0, t}, {3, 0, 3, 4, t}});
  const Layer tee_layer = plan_as_layer(tee);
  expect_sound(tee, tee_layer);
  expect_closed_skins(tee_layer);
  // The back face of the T runs unbroken from end to end, shared by its two walls.
  expect_covered(tee, tee_layer, 1, -0.5 * t + 0.5 * kBead, 0.5 * kBead, 3);
  expect_covered(tee, tee_layer, 2, -0.5 * t + 0.5 * kBead, 0, 3 - 0.5 * kBead);

  const FloorPlan cross_plan =
      plan_of({{0, 0, 3, 0, t}, {3, 0, 6, 0, t}, {3, -3, 3, 0, t}, {3, 0, 3, 3, t}},
              WallPattern::kSkinsWithTies);
  const Layer x_layer = plan_as_layer(cross_plan);
  expect_sound(cross_plan, x_layer);
  expect_closed_skins(x_layer);
  EXPECT_EQ(of_role(x_layer, BeadRole::kSkin).size() % 4, 0u);  // four arms alike
}

TEST(Beads, SkinsTurnAtAnOpeningsJambsAndNothingIsPrintedInIt) {
  FloorPlan plan = plan_of({{0, 0, 6, 0, 0.3}});
  plan.openings.push_back({"D1", 1, 2.0, 1.0, 0.0, 2.1, {}});
  const Layer layer = slice_plan_at(plan, 1.0, 1.1);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  for (const auto& s : layer.segments)
    for (const Vec& p : {layer.start_m(s), layer.end_m(s)})
      EXPECT_FALSE(p.x() > 2.0 + kTol && p.x() < 3.0 - kTol)
          << "a bead in the door at " << p.transpose();
  // Returns close each jamb half a bead in from it.
  int returns = 0;
  for (const auto* s : of_role(layer, BeadRole::kSkin)) {
    const Vec a = layer.start_m(*s), b = layer.end_m(*s);
    if (std::abs(a.x() - b.x()) < kTol &&
        (std::abs(a.x() - 1.925) < kTol || std::abs(a.x() - 3.075) < kTol))
      ++returns;
  }
  EXPECT_EQ(returns, 2);
  // Above the door the wall is whole again: one ring.
  EXPECT_EQ(slice_plan_at(plan, 2.2, 2.3).segments.size(), 4u);
}

TEST(Beads, TiesZigZagBetweenTheSkinsTouchingTheirInnerEdges) {
  const double t = 0.6;  // a core of 0.3 m: ties swing 0.075 m either side of the middle
  const FloorPlan plan = plan_of({{0, 0, 5, 0, t}}, WallPattern::kSkinsWithTies);
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  const auto ties = of_role(layer, BeadRole::kTie);
  ASSERT_GE(ties.size(), 2u);
  for (const auto* s : ties)
    for (const Vec& p : {layer.start_m(*s), layer.end_m(*s)})
      EXPECT_NEAR(std::abs(p.y()), 0.5 * (t - 2 * kBead - kBead), kTol);
  const FloorPlan cavity = plan_of({{0, 0, 5, 0, t}}, WallPattern::kSkins);
  EXPECT_EQ(plan_as_layer(cavity).segments.size(), 4u);
}

TEST(Beads, AOneBeadWallStopsAtAThickWallsFace) {
  const FloorPlan plan = plan_of({{0, 0, 6, 0, 0.3}, {3, 0, 3, 3, kBead}});
  const Layer layer = plan_as_layer(plan);
  expect_sound(plan, layer);
  const auto passes = of_role(layer, BeadRole::kPass);
  ASSERT_EQ(passes.size(), 1u);
  EXPECT_NEAR(std::min(layer.start_m(*passes[0]).y(), layer.end_m(*passes[0]).y()), 0.15, kTol);
}

TEST(Beads, WithoutABeadWidthEveryWallIsOnePassAsBefore) {
  FloorPlan plan = plan_of({{0, 0, 4, 0, 0.45}, {0, 0, 0, 4, 0.45}});
  plan.beads = {};
  const Layer layer = plan_as_layer(plan);
  ASSERT_EQ(layer.segments.size(), 2u);
  for (const auto& s : layer.segments) EXPECT_EQ(s.width_m, 0.0);
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {

// Placed far from the origin (as a site places a building), the skins still lie exactly
// half a bead inside their faces: the library's offset is corrected onto them.
TEST(Beads, FarFromTheOriginSkinsLieExactlyHalfABeadInsideTheFaces) {
  // Wall 3 stands on wall 1 (a T whose through wall is not cut there): its core and ties
  // stop at the side of wall 1's.
  const double x0 = 41.3, y0 = 23.7, t = 0.6;
  for (auto pattern : {WallPattern::kSolid, WallPattern::kSkinsWithTies}) {
    const FloorPlan p = plan_of(
        {{x0, y0, x0 + 5, y0, t}, {x0 + 5, y0, x0 + 5, y0 + 4, t}, {x0 + 2, y0, x0 + 2, y0 + 4, t}},
        pattern);
    expect_sound(p, plan_as_layer(p));
  }
  const FloorPlan plan = plan_of(
      {{x0, y0, x0 + 5, y0, t}, {x0 + 5, y0, x0 + 5, y0 + 4, t}, {x0 + 2, y0, x0 + 2, y0 + 4, t}});
  const Layer layer = plan_as_layer(plan);
  int checked = 0;
  for (const auto* s : of_role(layer, BeadRole::kSkin)) {
    const Vec a = layer.start_m(*s), b = layer.end_m(*s);
    if (std::abs(a.y() - b.y()) < 1e-9 && s->wall_id == 1) {
      EXPECT_NEAR(std::abs(a.y() - y0), 0.5 * t - 0.5 * kBead, 1e-9) << a.transpose();
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {

double deposited_m2(const Layer& layer) {
  double area = 0.0;
  for (const auto& s : layer.segments) area += s.width_m * s.length_m;
  return area;
}

// Solid walls deposit their own volume (bead width times length, summed, against the
// outline's area): a free-standing wall, and an L (outline (4 + 3) t: the corner square
// counted once; the cores overlap in one quarter of the corner's core square and leave
// another unfilled, which cancel); cavity walls deposit their skins only.
TEST(Beads, ASolidWallDepositsItsOwnVolume) {
  const double t = 0.45;
  EXPECT_NEAR(deposited_m2(plan_as_layer(plan_of({{0, 0, 4, 0, t}}))), 4 * t, 1e-9);
  EXPECT_NEAR(deposited_m2(plan_as_layer(plan_of({{0, 0, 0, 4, t}, {0, 0, 3, 0, t}}))), (4 + 3) * t,
              1e-9);
  const double ring_m = 2 * ((4 - kBead) + (t - kBead));
  EXPECT_NEAR(deposited_m2(plan_as_layer(plan_of({{0, 0, 4, 0, t}}, WallPattern::kSkins))),
              ring_m * kBead, 1e-9);
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {

// Two rooms whose partition (0.3 m) has a door, the outer walls 0.3 m as a drawing in
// millimetres gives them (0.29999999999999998): the skins at the door's jambs turn exactly
// half a bead inside the partition's faces.
TEST(Beads, AtADoorInAPartitionTheReturnsTurnExactly) {
  FloorPlan plan = plan_of({{0.15, 0.15, 3, 0.15, 0.29999999999999998},
                            {3, 0.15, 5.85, 0.15, 0.29999999999999998},
                            {5.85, 0.15, 5.85, 3.85, 0.29999999999999998},
                            {5.85, 3.85, 3, 3.85, 0.29999999999999998},
                            {3, 3.85, 0.15, 3.85, 0.29999999999999998},
                            {0.15, 3.85, 0.15, 0.15, 0.29999999999999998},
                            {3, 0.15, 3, 3.85, 0.3}});
  plan.openings.push_back({"D", 7, 0.85, 0.9, 0.0, 2.1, {}});
  const Layer layer = slice_plan_at(plan, 0.0, 0.5);
  expect_sound(plan, layer);
  expect_closed_skins(layer);
  for (const auto& s : layer.segments) {
    if (s.wall_id != 7) continue;
    for (const Vec& p : {layer.start_m(s), layer.end_m(s)}) {
      EXPECT_NEAR(std::abs(p.x() - 3.0), 0.075, 1e-9) << p.transpose();
      if (std::abs(p.y() - 0.925) < 1e-3) EXPECT_NEAR(p.y(), 0.925, 1e-9);
    }
  }
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {

// slice_floor cuts layers alike in their open openings once: each layer it gives is the
// one slice_floor_layer gives on its own, beads, heights and all.
TEST(Beads, AFloorSlicedWholeIsItsLayersSlicedOneByOne) {
  Floor floor;
  floor.index = 1;
  floor.height_m = 3.0;
  floor.base_elevation_m = 3.2;
  floor.plan = plan_of({{0, 0, 6, 0, 0.3}, {6, 0, 6, 4, 0.45}});
  floor.plan.openings.push_back({"D", 1, 2.0, 1.0, 0.0, 2.1, {}});
  floor.plan.openings.push_back({"W", 2, 1.0, 1.2, 0.9, 2.1, {}});
  const auto layers = slice_floor(floor, 0.4, {});  // the last layer 0.2 m thin
  ASSERT_EQ(layers.size(), 8u);
  for (int k = 0; k < 8; ++k) {
    const Layer one = slice_floor_layer(floor, 0.4, k);
    EXPECT_TRUE(GeometryKey(layers[k]) == GeometryKey(one)) << "layer " << k;
    EXPECT_EQ(layers[k].index, k);
    EXPECT_DOUBLE_EQ(layers[k].z_bottom_m, one.z_bottom_m);
    EXPECT_DOUBLE_EQ(layers[k].z_top_m, one.z_top_m);
    EXPECT_EQ(layers[k].floor_index, 1);
  }
  EXPECT_FALSE(GeometryKey(layers[0]) == GeometryKey(layers[3]));  // window open at 1.0-1.4
  EXPECT_FALSE(GeometryKey(layers[0]) == GeometryKey(layers[7]));  // door closed above 2.1
}

}  // namespace
}  // namespace ccbuild::floors
