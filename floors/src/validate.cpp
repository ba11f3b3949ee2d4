// Semantic checks of a floor plan. Every problem is collected and reported together,
// each at the line (or field path) where the offending element was written.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plan.hpp"
#include "plan_internal.hpp"

namespace ccbuild::floors {
namespace {

constexpr double kLengthTolerance_m = 1e-6;

std::string where(const SourceRef& source) {
  if (source.line > 0) return "line " + std::to_string(source.line);
  return source.path.empty() ? "elsewhere" : source.path;
}

std::string describe_opening(const Opening& o) {
  return o.id.empty() ? "opening on wall " + std::to_string(o.wall_id)
                      : "opening '" + o.id + "' on wall " + std::to_string(o.wall_id);
}

struct WallGeometry {
  const Wall* wall;
  Eigen::Vector2d a, b;
  double min_x, max_x, min_y, max_y;
};

// Two walls on one line sharing more than a point would be deposited twice.
void check_collinear_overlaps(const std::vector<WallGeometry>& walls, LengthUnit unit,
                              DiagnosticSink& sink) {
  std::vector<const WallGeometry*> order;
  for (const auto& w : walls) order.push_back(&w);
  std::sort(order.begin(), order.end(), [](const WallGeometry* p, const WallGeometry* q) {
    return p->min_x < q->min_x || (p->min_x == q->min_x && p->wall->id < q->wall->id);
  });
  const double tol = kLengthTolerance_m;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const WallGeometry& p = *order[i];
    const Eigen::Vector2d dir = (p.b - p.a).normalized();
    const Eigen::Vector2d normal(-dir.y(), dir.x());
    for (std::size_t j = i + 1; j < order.size() && order[j]->min_x <= p.max_x + tol; ++j) {
      const WallGeometry& q = *order[j];
      if (q.min_y > p.max_y + tol || q.max_y < p.min_y - tol) continue;
      if (std::abs(normal.dot(q.a - p.a)) > tol || std::abs(normal.dot(q.b - p.a)) > tol) continue;
      const double p0 = 0.0, p1 = (p.b - p.a).norm();
      const double q0 = dir.dot(q.a - p.a), q1 = dir.dot(q.b - p.a);
      const double overlap = std::min(p1, std::max(q0, q1)) - std::max(p0, std::min(q0, q1));
      if (overlap > tol) {
        const Wall& later = p.wall->source.line > q.wall->source.line ? *p.wall : *q.wall;
        const Wall& earlier = &later == p.wall ? *q.wall : *p.wall;
        sink.add(at(later.source, "",
                    "wall " + std::to_string(later.id) + " overlaps wall " +
                        std::to_string(earlier.id) + " (" + where(earlier.source) + ") along " +
                        length_text(overlap, unit) +
                        " on the same line; each stretch of wall must be drawn once"));
      }
    }
  }
}

}  // namespace

void validate_plan(const FloorPlan& plan, std::optional<double> floor_height_m,
                   const std::string& context) {
  DiagnosticSink sink;
  const std::string prefix = context.empty() ? "" : context + ": ";
  // In the plan's unit, whatever it is.
  auto in_unit = [&](double value_m) { return length_text(value_m, plan.units); };
  // Lengths too short for three decimals ("0.0005 m").
  auto exact = [&](double value_m) {
    return plain_number(value_m / meters_per(plan.units)) + " " + to_string(plan.units);
  };

  if (plan.walls.empty())
    sink.add(Diagnostic{plan.source_file, 0, "walls",
                        prefix + "the plan has no walls; a floor needs at least one wall"});

  std::map<std::int64_t, const Vertex*> vertices;
  for (const auto& v : plan.vertices) {
    auto [it, fresh] = vertices.emplace(v.id, &v);
    if (!fresh)
      sink.add(at(v.source, "id",
                  prefix + "vertex id " + std::to_string(v.id) + " is defined twice (first at " +
                      where(it->second->source) + ")"));
  }

  std::map<std::int64_t, const Wall*> walls;
  std::map<std::int64_t, double> wall_length;
  std::vector<WallGeometry> geometry;
  for (const auto& w : plan.walls) {
    auto [it, fresh] = walls.emplace(w.id, &w);
    if (!fresh) {
      sink.add(at(w.source, "id",
                  prefix + "wall id " + std::to_string(w.id) + " is defined twice (first at " +
                      where(it->second->source) + ")"));
      continue;
    }
    const auto a = vertices.find(w.start_vertex);
    const auto b = vertices.find(w.end_vertex);
    if (a == vertices.end())
      sink.add(at(w.source, "start",
                  prefix + "wall " + std::to_string(w.id) + ": start vertex " +
                      std::to_string(w.start_vertex) + " is not defined"));
    if (b == vertices.end())
      sink.add(at(w.source, "end",
                  prefix + "wall " + std::to_string(w.id) + ": end vertex " +
                      std::to_string(w.end_vertex) + " is not defined"));
    if (w.thickness_m && *w.thickness_m <= 0.0)
      sink.add(at(w.source, "thickness",
                  prefix + "wall " + std::to_string(w.id) + ": thickness must be positive, got " +
                      in_unit(*w.thickness_m)));
    if (a == vertices.end() || b == vertices.end()) continue;
    const Eigen::Vector2d pa = a->second->position_m, pb = b->second->position_m;
    const double length = (pb - pa).norm();
    if (length <= kLengthTolerance_m) {
      sink.add(at(w.source, "",
                  prefix + "wall " + std::to_string(w.id) + " has zero length (vertices " +
                      std::to_string(w.start_vertex) + " and " + std::to_string(w.end_vertex) +
                      " are at the same point)"));
      continue;
    }
    if (length <= limits::kMinWallLength_m) {
      sink.add(at(w.source, "",
                  prefix + "wall " + std::to_string(w.id) + " is " + exact(length) +
                      " long; walls must be longer than " + exact(limits::kMinWallLength_m) +
                      " (points closer than that are one point in a layer, so the wall would "
                      "vanish)"));
      continue;
    }
    if (!w.top_m.empty() && w.top_m.back().first > length + limits::kMinWallLength_m)
      sink.add(at(w.source, "top",
                  prefix + "wall " + std::to_string(w.id) + ": its top has a point at " +
                      in_unit(w.top_m.back().first) + " along it, past its end (it is " +
                      in_unit(length) + " long)"));
    wall_length[w.id] = length;
    geometry.push_back({&w, pa, pb, std::min(pa.x(), pb.x()), std::max(pa.x(), pb.x()),
                        std::min(pa.y(), pb.y()), std::max(pa.y(), pb.y())});
  }
  check_collinear_overlaps(geometry, plan.units, sink);

  std::vector<const Opening*> sound;  // openings whose own numbers are fine
  for (const auto& o : plan.openings) {
    const std::string name = prefix + describe_opening(o);
    bool ok = true;
    const auto wall = walls.find(o.wall_id);
    if (wall == walls.end()) {
      sink.add(
          at(o.source, "wall", name + ": wall " + std::to_string(o.wall_id) + " is not defined"));
      ok = false;
    }
    if (o.width_m <= 0.0) {
      sink.add(at(o.source, "width", name + ": width must be positive, got " + in_unit(o.width_m)));
      ok = false;
    }
    if (o.offset_m < 0.0) {
      sink.add(at(o.source, "offset",
                  name + ": offset must be zero or more, got " + in_unit(o.offset_m)));
      ok = false;
    }
    if (o.sill_m < 0.0) {
      sink.add(at(o.source, "sill",
                  name + ": sill height must be zero or more, got " + in_unit(o.sill_m)));
      ok = false;
    }
    if (o.head_m <= 0.0) {
      sink.add(
          at(o.source, "head", name + ": head height must be positive, got " + in_unit(o.head_m)));
      ok = false;
    } else if (o.sill_m >= o.head_m) {
      sink.add(at(o.source, "sill",
                  name + ": sill (" + in_unit(o.sill_m) + ") must be below head (" +
                      in_unit(o.head_m) + ")"));
      ok = false;
    }
    if (floor_height_m && o.head_m > *floor_height_m + kLengthTolerance_m) {
      sink.add(at(o.source, "head",
                  name + ": head (" + in_unit(o.head_m) + ") is above the floor height (" +
                      in_unit(*floor_height_m) + ")"));
      ok = false;
    }
    if (ok && wall_length.count(o.wall_id)) {
      const double length = wall_length[o.wall_id];
      if (o.offset_m + o.width_m > length + kLengthTolerance_m) {
        sink.add(at(o.source, "",
                    name + " does not fit on its wall: offset " + in_unit(o.offset_m) +
                        " + width " + in_unit(o.width_m) + " = " + in_unit(o.offset_m + o.width_m) +
                        ", but the wall is " + in_unit(length) + " long"));
      } else {
        sound.push_back(&o);
      }
    }
  }
  // Two openings clash when they share both a stretch of the wall and a height band.
  for (std::size_t i = 0; i < sound.size(); ++i) {
    for (std::size_t j = i + 1; j < sound.size(); ++j) {
      const Opening& p = *sound[i];
      const Opening& q = *sound[j];
      if (p.wall_id != q.wall_id) continue;
      const double along = std::min(p.offset_m + p.width_m, q.offset_m + q.width_m) -
                           std::max(p.offset_m, q.offset_m);
      const double up = std::min(p.head_m, q.head_m) - std::max(p.sill_m, q.sill_m);
      if (along > kLengthTolerance_m && up > kLengthTolerance_m)
        sink.add(at(q.source, "",
                    prefix + describe_opening(q) + " overlaps " + describe_opening(p) + " (" +
                        where(p.source) + ") by " + in_unit(along) + " along the wall"));
    }
  }
  sink.throw_if_any();
}

}  // namespace ccbuild::floors
