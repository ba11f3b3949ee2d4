// The seams the scheduler will stand on: a cost model that owns its layer, planning on
// several threads at once, plan re-use between layers of equal geometry, and waypoints
// that an independent check can trust.

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "layouts.hpp"
#include "test_support.hpp"

namespace ccbuild::planner {
namespace {

TEST(Seams, CostModelKeepsItsOwnLayer) {
  floors::Layer layer = testing::floor_plan_layer(6, 3);
  const CostModel model(layer, testing::simple_machine(), Metric::kEuclidean);
  Sequence sequence;
  for (int s = 0; s < static_cast<int>(layer.segments.size()); ++s) sequence.push_back({s, false});
  const double before = model.evaluate(sequence, PathSpec::closed_tour()).layer_time_s;
  // The caller's layer changes (or goes away): the model is not affected.
  for (auto& p : layer.points) p *= 3.0;
  layer.segments.clear();
  EXPECT_EQ(model.evaluate(sequence, PathSpec::closed_tour()).layer_time_s, before);
  EXPECT_EQ(model.layer().segments.size(), sequence.size());
}

TEST(Seams, LayersPlanInParallelExactlyAsAlone) {
  // The scheduler plans distinct layers on several threads: the answers must be those of
  // planning them one after another (kick budgets, not time, end the searches). The
  // connected bound runs GLPK on every thread at once.
  std::vector<floors::Layer> layers;
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    layers.push_back(testing::floor_plan_layer(10 + 2 * static_cast<int>(seed), seed));
  PlanOptions o;
  o.max_kicks = 400;
  o.bound = BoundKind::kConnected;
  o.objective = Objective::kTime;
  std::vector<LayerPlan> alone;
  for (const auto& layer : layers) alone.push_back(plan_layer(layer, testing::simple_machine(), o));
  for (int round = 0; round < 2; ++round) {
    std::vector<LayerPlan> together(layers.size());
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < layers.size(); ++k)
      threads.emplace_back(
          [&, k] { together[k] = plan_layer(layers[k], testing::simple_machine(), o); });
    for (auto& t : threads) t.join();
    for (std::size_t k = 0; k < layers.size(); ++k) {
      EXPECT_EQ(together[k].sequence, alone[k].sequence) << "layer " << k;
      EXPECT_EQ(together[k].lower_bound_m, alone[k].lower_bound_m) << "layer " << k;
      EXPECT_EQ(together[k].lower_bound_source, alone[k].lower_bound_source);
    }
  }
}

// The same walls as `layer`, renumbered, drawn the other way round and listed in another
// order: another layer of the same geometry.
floors::Layer disguised(const floors::Layer& layer) {
  std::vector<floors::PieceSpec> pieces;
  for (std::size_t k = layer.segments.size(); k-- > 0;) {
    const auto& s = layer.segments[k];
    pieces.push_back({s.wall_id + 1000, layer.end_m(s), layer.start_m(s), 0.0});
  }
  return floors::layer_from_pieces(pieces);
}

TEST(Seams, EqualGeometryIsProvenAndPlansReplayOnIt) {
  const floors::Layer layer = testing::floor_plan_layer(9, 4);
  const floors::Layer other = disguised(layer);
  EXPECT_EQ(floors::GeometryKey(layer), floors::GeometryKey(other));
  EXPECT_EQ(layer.geometry_hash, other.geometry_hash);
  const auto matches = floors::match_segments(layer, other);
  ASSERT_TRUE(matches);
  PlanOptions o;
  o.objective = Objective::kTime;
  o.max_kicks = 200;
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  const Sequence replay = map_sequence(plan.sequence, *matches);
  ASSERT_TRUE(covers_every_segment_once(replay, other.segments.size()));
  const CostModel model(other, testing::simple_machine(), Metric::kEuclidean);
  const Evaluation e = model.evaluate(replay, PathSpec::closed_tour());
  EXPECT_NEAR(e.layer_time_s, plan.evaluation.layer_time_s, 1e-9);
  EXPECT_NEAR(e.airtime_distance_m, plan.evaluation.airtime_distance_m, 1e-9);
  // Every replayed step visits the same points in the same order.
  for (std::size_t k = 0; k < replay.size(); ++k) {
    const CostModel original(layer, testing::simple_machine(), Metric::kEuclidean);
    EXPECT_LT((model.step_start_m(replay[k]) - original.step_start_m(plan.sequence[k])).norm(),
              1e-6);
  }
}

TEST(Seams, DifferentGeometryIsNeverTakenForEqual) {
  const floors::Layer layer = testing::floor_plan_layer(9, 4);
  // One wall moved by 2 micrometres: a different geometry, however the hash falls.
  floors::Layer moved = layer;
  moved.points[moved.segments[0].end_point].x() += 2e-6;
  EXPECT_NE(floors::GeometryKey(layer), floors::GeometryKey(moved));
  EXPECT_FALSE(floors::match_segments(layer, moved));
  // One wall fewer.
  std::vector<int> fewer;
  for (int s = 1; s < static_cast<int>(layer.segments.size()); ++s) fewer.push_back(s);
  const floors::Layer part = floors::sub_layer(layer, fewer);
  EXPECT_NE(floors::GeometryKey(layer), floors::GeometryKey(part));
  EXPECT_FALSE(floors::match_segments(layer, part));
  EXPECT_FALSE(floors::match_segments(part, layer));
}

// --- Waypoints, re-checked from their own numbers -------------------------------------

struct Checked {
  double deposited_m = 0.0;
  int walls = 0;
};

// Between consecutive waypoints the nozzle moves straight at constant speed: check speed
// limits (deposition exactly, travel, per axis when rectilinear, z, rotation), the
// stopper, and that each extruding stretch runs along a wall of the layer.
Checked check_waypoints(const std::vector<Waypoint>& w, const floors::Layer& layer,
                        const machine::MachineModel& m, Metric metric) {
  Checked out;
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    const Waypoint& a = w[k];
    const Waypoint& b = w[k + 1];
    const double dt = b.t_s - a.t_s;
    EXPECT_GE(dt, -1e-12) << "time runs backwards at " << k;
    const Eigen::Vector2d d = b.position_m - a.position_m;
    EXPECT_LE(std::abs(b.heading_rad - a.heading_rad), m.rotation_speed_rad_s * dt + 1e-9) << k;
    EXPECT_LE(std::abs(b.z_m - a.z_m), m.z.speed_m_s * dt + 1e-9) << k;
    EXPECT_GE(b.heading_rad, m.stopper_min_rad - 1e-9);
    EXPECT_LE(b.heading_rad, m.stopper_max_rad + 1e-9);
    if (a.extruding) {
      EXPECT_NEAR(d.norm(), m.deposition_speed_m_s * dt, 1e-9) << "deposition speed at " << k;
      // The stretch is a wall piece of the layer, with the wall's id.
      bool found = false;
      for (const auto& s : layer.segments) {
        const auto p = layer.start_m(s), q = layer.end_m(s);
        if (((a.position_m - p).norm() < 1e-9 && (b.position_m - q).norm() < 1e-9) ||
            ((a.position_m - q).norm() < 1e-9 && (b.position_m - p).norm() < 1e-9)) {
          found = s.wall_id == a.wall && s.piece + 1 == a.piece;
          break;
        }
      }
      EXPECT_TRUE(found) << "extruding stretch " << k << " is not wall " << a.wall;
      EXPECT_NEAR(b.z_m, a.z_m, 1e-12);
      out.deposited_m += d.norm();
      ++out.walls;
    } else if (metric == Metric::kEuclidean) {
      EXPECT_LE(d.norm(), m.travel_speed_m_s * dt + 1e-9) << "travel speed at " << k;
    } else {
      // One axis at a time, each within its own speed.
      EXPECT_TRUE(std::abs(d.x()) < 1e-9 || std::abs(d.y()) < 1e-9) << k;
      EXPECT_LE(std::abs(d.x()), m.x.speed_m_s * dt + 1e-9) << k;
      EXPECT_LE(std::abs(d.y()), m.y.speed_m_s * dt + 1e-9) << k;
    }
  }
  return out;
}

TEST(Seams, WaypointsAreCompleteAndWithinTheMachine) {
  const floors::Layer layer = testing::random_layer(9, 7);  // crossings: lifts
  for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear}) {
    for (bool rotate_while_moving : {true, false}) {
      for (bool closed : {true, false}) {
        machine::MachineModel m = testing::simple_machine();
        m.rotate_while_moving = rotate_while_moving;
        m.lift_height_m = 0.2;
        m.lift_time_s = 0.2 / m.z.speed_m_s;
        m.lower_time_s = 0.4 / m.z.speed_m_s;  // lowering slower than the z axis can
        PlanOptions o;
        o.metric = metric;
        o.objective = Objective::kTime;
        o.max_kicks = 100;
        o.path = closed ? PathSpec::closed_tour() : PathSpec::open_from({-1.0, 3.0});
        const LayerPlan plan = plan_layer(layer, m, o);
        SCOPED_TRACE(to_string(metric) + (rotate_while_moving ? " concurrent" : " added") +
                     (closed ? " closed" : " open"));
        const auto& w = plan.waypoints;
        ASSERT_GE(w.size(), 2 * layer.segments.size());
        // Every piece exactly once, at the deposition speed, all of its length.
        const Checked c = check_waypoints(w, layer, m, metric);
        EXPECT_EQ(c.walls, static_cast<int>(layer.segments.size()));
        EXPECT_NEAR(c.deposited_m, layer.total_length_m(), 1e-9);
        // Times agree with the cost model, and the path ends where it should.
        EXPECT_NEAR(w.front().t_s, 0.0, 1e-12);
        EXPECT_NEAR(w.back().t_s, plan.evaluation.layer_time_s, 1e-6);
        EXPECT_FALSE(w.back().extruding);
        if (closed)
          EXPECT_LT((w.back().position_m - w.front().position_m).norm(), 1e-9);
        else
          EXPECT_LT((w.front().position_m - Eigen::Vector2d(-1.0, 3.0)).norm(), 1e-12);
        // Lifts rise by the lift height over the layer's top, and come down again.
        double highest = -1.0;
        for (const auto& p : w) highest = std::max(highest, p.z_m);
        if (plan.evaluation.lift_count > 0)
          EXPECT_NEAR(highest, layer.z_top_m + 0.2, 1e-12);
        else
          EXPECT_NEAR(highest, layer.z_top_m, 1e-12);
        EXPECT_NEAR(w.back().z_m, layer.z_top_m, 1e-12);
      }
    }
  }
}

TEST(Seams, WaypointsRiseOverBuiltWallsAndOnlyThere) {
  // Wall 0 runs across the middle; building it first makes the move from wall 1 to wall 2
  // cross it (see CostModel.LiftOnlyOverWallsAlreadyBuilt): the nozzle rises by the lift
  // height for that move alone, at the z axis's speed, and comes back down.
  const auto layer = testing::layer_from_walls({{0, 5, 10, 5}, {2, 2, 4, 2}, {6, 8, 8, 8}});
  machine::MachineModel m = testing::simple_machine();
  m.lift_height_m = 0.25;
  m.lift_time_s = m.lower_time_s = 0.25 / m.z.speed_m_s;
  const CostModel model(layer, m, Metric::kEuclidean);
  const PathSpec open = PathSpec::open_from({0, 5});
  const Sequence s{{0, false}, {1, false}, {2, false}};
  const Evaluation e = model.evaluate(s, open);
  ASSERT_EQ(e.lift_count, 1);
  const auto w = waypoints_of(model, s, open, e, 1.5);
  int raised = 0;
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    const bool up = w[k].z_m > 1.5 + 1e-12 || w[k + 1].z_m > 1.5 + 1e-12;
    if (!up) continue;
    ++raised;
    EXPECT_FALSE(w[k].extruding);
    EXPECT_LE(std::abs(w[k + 1].z_m - w[k].z_m), m.z.speed_m_s * (w[k + 1].t_s - w[k].t_s) + 1e-9);
    // Raised only on the way from wall 1's end (4,2) to wall 2's start (6,8).
    EXPECT_GE(w[k].position_m.y(), 2.0 - 1e-9);
    EXPECT_LE(w[k].position_m.y(), 8.0 + 1e-9);
  }
  EXPECT_EQ(raised, 3);  // up, across at the top, down
  double highest = 0.0;
  for (const auto& p : w) highest = std::max(highest, p.z_m);
  EXPECT_NEAR(highest, 1.75, 1e-12);
}

TEST(Seams, TimelineIsTheWaypointsPositions) {
  const floors::Layer layer = testing::floor_plan_layer(7, 2);
  const machine::MachineModel m = testing::simple_machine();
  PlanOptions o;
  o.metric = Metric::kRectilinear;
  o.max_kicks = 50;
  const LayerPlan plan = plan_layer(layer, m, o);
  const CostModel model(layer, m, o.metric);
  const std::vector<double> waits{0.0, 3.0, 0.0, 1.5};
  const Timeline t = timeline_of(model, plan.sequence, o.path, plan.evaluation, waits);
  const auto w = waypoints_of(model, plan.sequence, o.path, plan.evaluation, 0.0, 0.0, waits);
  EXPECT_NEAR(t.end_s(), w.back().t_s, 1e-9);
  EXPECT_NEAR(t.end_s(), plan.evaluation.layer_time_s + 4.5, 1e-9);
  for (const auto& p : w) EXPECT_LT((t.at(p.t_s) - p.position_m).norm(), 1e-9) << p.t_s;
}

TEST(Seams, MultiNozzleWaypointsRunInLayerTimeAcrossStages) {
  const floors::Layer layer = testing::layer_from_walls(
      {{0, 0, 6, 0}, {6, 0, 6, 3}, {10, 0, 16, 0}, {16, 0, 16, 3}, {20, 0, 26, 0}, {26, 0, 26, 3}});
  MultiNozzleOptions o;
  o.nozzles = 2;
  o.gantry_width_m = 1.0;
  o.platform_width_m = 10.0;
  o.planning.max_kicks = 50;
  const MultiNozzlePlan plan = plan_layer_multi(layer, testing::simple_machine(), o);
  ASSERT_TRUE(plan.status) << plan.status.to_string();
  ASSERT_GE(plan.stages.size(), 2u);
  double deposited = 0.0;
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const Stage& stage = plan.stages[k];
    if (k > 0) {
      EXPECT_GT(stage.start_s, plan.stages[k - 1].start_s + plan.stages[k - 1].time_s);
    }
    for (const auto& n : stage.nozzles) {
      ASSERT_FALSE(n.waypoints.empty());
      EXPECT_NEAR(n.waypoints.front().t_s, stage.start_s, 1e-12);
      EXPECT_NEAR(n.waypoints.back().t_s, stage.start_s + n.finish_s, 1e-6);
      deposited +=
          check_waypoints(n.waypoints, n.layer, testing::simple_machine(), Metric::kEuclidean)
              .deposited_m;
    }
  }
  EXPECT_NEAR(deposited, layer.total_length_m(), 1e-9);
  EXPECT_NEAR(plan.stages.back().start_s + plan.stages.back().time_s, plan.layer_time_s, 1e-9);
}

TEST(Seams, OneDistanceForEveryMetric) {
  const Eigen::Vector2d a(1.0, 2.0), b(4.0, -2.0);
  EXPECT_DOUBLE_EQ(metric_distance_m(Metric::kEuclidean, a, b), 5.0);
  EXPECT_DOUBLE_EQ(metric_distance_m(Metric::kRectilinear, a, b), 7.0);
  const CostModel model(testing::layer_from_walls({{0, 0, 1, 0}}), testing::simple_machine(),
                        Metric::kRectilinear);
  EXPECT_DOUBLE_EQ(model.distance_m(a, b), 7.0);
  EXPECT_EQ(rail_coordinate(b, RailAxis::kY), -2.0);
  EXPECT_EQ(with_rail_coordinate(b, RailAxis::kX, 9.0), Eigen::Vector2d(9.0, -2.0));
}

}  // namespace
}  // namespace ccbuild::planner
