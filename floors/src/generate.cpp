#include "ccbuild/floors/generate.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "ccbuild/floors/slice.hpp"

namespace ccbuild::floors {
namespace {

// Coordinates are integers in decimetres, so junctions meet exactly.
struct Room {
  int x0, y0, x1, y1;
  long area() const { return static_cast<long>(x1 - x0) * (y1 - y0); }
};

using Intervals = std::vector<std::pair<int, int>>;

Intervals merged(Intervals v) {
  std::sort(v.begin(), v.end());
  Intervals out;
  for (const auto& [a, b] : v) {
    if (!out.empty() && a <= out.back().second)
      out.back().second = std::max(out.back().second, b);
    else
      out.emplace_back(a, b);
  }
  return out;
}

bool covers(const Intervals& v, int t) {
  return std::any_of(v.begin(), v.end(),
                     [&](const auto& iv) { return iv.first <= t && t <= iv.second; });
}

}  // namespace

FloorPlan generate_plan(const PlanGeneratorOptions& options) {
  std::mt19937_64 rng(options.seed);
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) / 9007199254740992.0);
  };
  const int min_side = static_cast<int>(std::lround(options.min_room_side_m * 10));
  // Footprint sized for rooms of about 14 m2, aspect between 1 and 2.
  const double area_dm2 = std::max(1, options.rooms) * 14.0 * 100.0 * uniform(0.8, 1.2);
  const double aspect = uniform(1.0, 2.0);
  const int width = std::max(min_side, static_cast<int>(std::sqrt(area_dm2 * aspect)));
  const int depth = std::max(min_side, static_cast<int>(area_dm2 / width));

  std::vector<Room> rooms{{0, 0, width, depth}};
  while (static_cast<int>(rooms.size()) < options.rooms) {
    // Split the largest room that can still be split, across its longer side.
    std::vector<std::size_t> order(rooms.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return rooms[a].area() > rooms[b].area();
    });
    bool split = false;
    for (std::size_t i : order) {
      Room r = rooms[i];
      const bool vertical =
          (r.x1 - r.x0) > (r.y1 - r.y0) || ((r.x1 - r.x0) == (r.y1 - r.y0) && rng() % 2);
      const int lo = vertical ? r.x0 : r.y0, hi = vertical ? r.x1 : r.y1;
      if (hi - lo < 2 * min_side) continue;
      const int at = std::clamp(static_cast<int>(std::lround(lo + (hi - lo) * uniform(0.35, 0.65))),
                                lo + min_side, hi - min_side);
      Room a = r, b = r;
      if (vertical) {
        a.x1 = at;
        b.x0 = at;
      } else {
        a.y1 = at;
        b.y0 = at;
      }
      rooms[i] = a;
      rooms.push_back(b);
      split = true;
      break;
    }
    if (!split) break;
  }

  // Room outlines, merged per line, split at every junction.
  std::map<int, Intervals> horizontal, vertical;
  for (const Room& r : rooms) {
    horizontal[r.y0].emplace_back(r.x0, r.x1);
    horizontal[r.y1].emplace_back(r.x0, r.x1);
    vertical[r.x0].emplace_back(r.y0, r.y1);
    vertical[r.x1].emplace_back(r.y0, r.y1);
  }
  for (auto& [k, v] : horizontal) v = merged(v);
  for (auto& [k, v] : vertical) v = merged(v);
  std::vector<std::pair<std::pair<int, int>, std::pair<int, int>>> pieces;
  for (const auto& [y, ivs] : horizontal) {
    for (const auto& [a, b] : ivs) {
      std::set<int> cuts{a, b};
      for (const auto& [x, vivs] : vertical)
        if (a <= x && x <= b && covers(vivs, y)) cuts.insert(x);
      for (auto it = cuts.begin(); std::next(it) != cuts.end(); ++it)
        pieces.push_back({{*it, y}, {*std::next(it), y}});
    }
  }
  for (const auto& [x, ivs] : vertical) {
    for (const auto& [a, b] : ivs) {
      std::set<int> cuts{a, b};
      for (const auto& [y, hivs] : horizontal)
        if (a <= y && y <= b && covers(hivs, x)) cuts.insert(y);
      for (auto it = cuts.begin(); std::next(it) != cuts.end(); ++it)
        pieces.push_back({{x, *it}, {x, *std::next(it)}});
    }
  }

  FloorPlan plan;
  plan.source_file = "generated(seed " + std::to_string(options.seed) + ")";
  std::map<std::pair<int, int>, std::int64_t> vertex_id;
  auto vertex = [&](std::pair<int, int> p) {
    auto [it, fresh] = vertex_id.emplace(p, static_cast<std::int64_t>(vertex_id.size()) + 1);
    if (fresh)
      plan.vertices.push_back({it->second, Eigen::Vector2d(p.first / 10.0, p.second / 10.0), {}});
    return it->second;
  };
  const int door = static_cast<int>(std::lround(options.door_width_m * 10));
  const int window = static_cast<int>(std::lround(options.window_width_m * 10));
  for (const auto& [a, b] : pieces) {
    Wall wall;
    wall.id = static_cast<std::int64_t>(plan.walls.size()) + 1;
    wall.start_vertex = vertex(a);
    wall.end_vertex = vertex(b);
    plan.walls.push_back(wall);
    const int length = std::abs(b.first - a.first) + std::abs(b.second - a.second);
    const bool exterior = (a.second == b.second && (a.second == 0 || a.second == depth)) ||
                          (a.first == b.first && (a.first == 0 || a.first == width));
    if (exterior && length >= window + 8 && uniform(0, 1) < options.window_probability) {
      plan.openings.push_back({"W" + std::to_string(wall.id),
                               wall.id,
                               (length - window) / 20.0,
                               window / 10.0,
                               0.9,
                               2.1,
                               {}});
    } else if (!exterior && length >= door + 4 && uniform(0, 1) < options.door_probability) {
      const int slack = length - door - 4;
      const int offset = 2 + static_cast<int>(rng() % (slack + 1));
      plan.openings.push_back(
          {"D" + std::to_string(wall.id), wall.id, offset / 10.0, door / 10.0, 0.0, 2.1, {}});
    }
  }
  return plan;
}

FloorPlan generate_plan_with_segments(int segments, std::uint64_t seed) {
  // Segments grow about linearly with rooms; search the room count.
  auto count = [&](int rooms) {
    PlanGeneratorOptions o;
    o.rooms = rooms;
    o.seed = seed;
    FloorPlan plan = generate_plan(o);
    const int n = static_cast<int>(slice_plan_at(plan, 1.0, 2.0).segments.size());
    return std::pair{n, std::move(plan)};
  };
  int lo = 1, hi = 2;
  while (count(hi).first < segments && hi < 1 << 16) hi *= 2;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (count(mid).first < segments ? lo : hi) = mid;
  }
  auto [n_lo, plan_lo] = count(lo);
  auto [n_hi, plan_hi] = count(hi);
  return std::abs(n_lo - segments) <= std::abs(n_hi - segments) ? plan_lo : plan_hi;
}

}  // namespace ccbuild::floors
