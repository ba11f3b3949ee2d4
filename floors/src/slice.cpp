#include "ccbuild/floors/slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_map>

#include "beads_internal.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::floors {
namespace {

// Merges points closer than the tolerance, keeping the first one seen; a grid of
// tolerance-sized cells makes each lookup constant time.
class PointMerger {
 public:
  PointMerger(double tolerance_m, std::vector<Eigen::Vector2d>& points)
      : tolerance_m_(tolerance_m), points_(points) {}

  int add(const Eigen::Vector2d& p) {
    const std::int64_t cx = cell(p.x()), cy = cell(p.y());
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid_.find(key(cx + dx, cy + dy));
        if (it == grid_.end()) continue;
        for (int index : it->second)
          if ((points_[index] - p).norm() <= tolerance_m_) return index;
      }
    }
    const int index = static_cast<int>(points_.size());
    points_.push_back(p);
    grid_[key(cx, cy)].push_back(index);
    return index;
  }

 private:
  std::int64_t cell(double v) const {
    return static_cast<std::int64_t>(std::floor(v / tolerance_m_));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(y);
  }

  double tolerance_m_;
  std::vector<Eigen::Vector2d>& points_;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
};

// Cuts every wall at the openings active at height `mid_m` (nullopt: none).
Layer cut_walls(const FloorPlan& plan, std::optional<double> mid_m, const SliceOptions& options) {
  std::vector<PieceSpec> pieces;
  for (const auto& wall : plan.walls) {
    const Eigen::Vector2d a = plan.wall_start_m(wall);
    const Eigen::Vector2d b = plan.wall_end_m(wall);
    const double length = (b - a).norm();
    std::vector<std::pair<double, double>> gaps;
    if (mid_m) {
      gaps = wall_gaps_above(wall, length, *mid_m);  // above where the wall stops
      for (const auto& o : plan.openings) {
        if (o.wall_id != wall.id) continue;
        const OpeningState state = opening_state(o, plan.lintel, *mid_m);
        if (state != OpeningState::kWall)
          gaps.push_back(opening_gap_m(o, plan.lintel, state, length));
      }
    }
    std::sort(gaps.begin(), gaps.end());
    double from = 0.0;
    const Eigen::Vector2d dir = (b - a) / length;
    auto add = [&](double s0, double s1) {
      const Eigen::Vector2d p = s0 == 0.0 ? a : Eigen::Vector2d(a + dir * s0);
      const Eigen::Vector2d q = s1 == length ? b : Eigen::Vector2d(a + dir * s1);
      pieces.push_back({wall.id, p, q, s0});
    };
    for (const auto& [g0, g1] : gaps) {
      if (g0 > from) add(from, g0);
      from = std::max(from, g1);
    }
    if (from < length) add(from, length);
  }
  if (plan.beads.bead_width_m > 0.0) pieces = bead_pieces(plan, pieces, options);
  return layer_from_pieces(pieces, options);
}

}  // namespace

Layer layer_from_pieces(const std::vector<PieceSpec>& pieces, const SliceOptions& options) {
  CCBUILD_CHECK(options.merge_tolerance_m > 0.0, "merge tolerance is positive");
  // Pieces grouped by wall, walls in order of first appearance, pieces along the wall.
  std::vector<std::int64_t> wall_order;
  std::unordered_map<std::int64_t, std::vector<const PieceSpec*>> by_wall;
  for (const auto& p : pieces) {
    if ((p.end_m - p.start_m).norm() <= options.merge_tolerance_m) continue;
    auto [it, fresh] = by_wall.try_emplace(p.wall_id);
    if (fresh) wall_order.push_back(p.wall_id);
    it->second.push_back(&p);
  }
  Layer layer;
  PointMerger merger(options.merge_tolerance_m, layer.points);
  for (std::int64_t id : wall_order) {
    auto& list = by_wall[id];
    std::stable_sort(list.begin(), list.end(), [](const PieceSpec* a, const PieceSpec* b) {
      return a->along_m < b->along_m;
    });
    const std::size_t first = layer.segments.size();
    for (const PieceSpec* p : list) {
      LayerSegment seg;
      seg.wall_id = id;
      seg.start_point = merger.add(p->start_m);
      seg.end_point = merger.add(p->end_m);
      if (seg.start_point == seg.end_point) continue;
      seg.length_m = (layer.points[seg.end_point] - layer.points[seg.start_point]).norm();
      seg.width_m = p->width_m;
      seg.role = p->role;
      layer.segments.push_back(seg);
    }
    const int count = static_cast<int>(layer.segments.size() - first);
    for (int k = 0; k < count; ++k) {
      layer.segments[first + k].piece = k;
      layer.segments[first + k].piece_count = count;
    }
  }
  layer.geometry_hash = geometry_hash(layer);
  return layer;
}

Layer sub_layer(const Layer& layer, const std::vector<int>& segments) {
  Layer out;
  out.floor_index = layer.floor_index;
  out.index = layer.index;
  out.z_bottom_m = layer.z_bottom_m;
  out.z_top_m = layer.z_top_m;
  std::unordered_map<int, int> point_map;
  auto point = [&](int p) {
    auto [it, fresh] = point_map.try_emplace(p, static_cast<int>(out.points.size()));
    if (fresh) out.points.push_back(layer.points[p]);
    return it->second;
  };
  for (int s : segments) {
    LayerSegment seg = layer.segments[s];
    seg.start_point = point(seg.start_point);
    seg.end_point = point(seg.end_point);
    out.segments.push_back(seg);
  }
  out.geometry_hash = geometry_hash(out);
  return out;
}

double Layer::total_length_m() const {
  double total = 0.0;
  for (const auto& s : segments) total += s.length_m;
  return total;
}

int layer_count(double floor_height_m, double layer_height_m) {
  CCBUILD_CHECK(std::isfinite(floor_height_m) && std::isfinite(layer_height_m) &&
                    floor_height_m > 0.0 && layer_height_m > 0.0,
                "heights are positive and finite");
  const double ratio = floor_height_m / layer_height_m;
  CCBUILD_CHECK(ratio <= 1e7, "a floor has a plausible number of layers (heights checked?)");
  return std::max(1, static_cast<int>(std::ceil(ratio - 1e-9 * std::max(1.0, ratio))));
}

std::vector<Layer> slice_floor(const Floor& floor, double layer_height_m,
                               const SliceOptions& options) {
  const int count = layer_count(floor.height_m, layer_height_m);
  std::vector<Layer> layers;
  layers.reserve(count);
  // A layer's pieces depend only on which openings are open at its mid-height and where
  // the walls that stop lower leave off: layers alike in that are cut (and offset into
  // beads, the costly part) once.
  std::map<std::pair<std::vector<OpeningState>, std::vector<double>>, std::size_t> first_with;
  for (int k = 0; k < count; ++k) {
    const double z0 = k * layer_height_m;
    const double mid_m = layer_mid_m(floor.height_m, layer_height_m, k);
    std::vector<OpeningState> open;
    open.reserve(floor.plan.openings.size());
    for (const auto& o : floor.plan.openings)
      open.push_back(opening_state(o, floor.plan.lintel, mid_m));
    std::vector<double> tops;  // each topped wall's gap count, then their ends
    for (const auto& w : floor.plan.walls) {
      if (w.top_m.empty()) continue;
      const auto gaps = wall_gaps_above(w, floor.plan.wall_length_m(w), mid_m);
      tops.push_back(static_cast<double>(gaps.size()));
      for (const auto& [g0, g1] : gaps) tops.insert(tops.end(), {g0, g1});
    }
    const auto [it, fresh] =
        first_with.try_emplace({std::move(open), std::move(tops)}, layers.size());
    if (fresh) {
      layers.push_back(slice_floor_layer(floor, layer_height_m, k, options));
      continue;
    }
    Layer layer = layers[it->second];
    layer.index = k;
    layer.z_bottom_m = floor.base_elevation_m + z0;
    layer.z_top_m = floor.base_elevation_m + std::min((k + 1) * layer_height_m, floor.height_m);
    layers.push_back(std::move(layer));
  }
  return layers;
}

double layer_mid_m(double floor_height_m, double layer_height_m, int k) {
  return 0.5 * (k * layer_height_m + std::min((k + 1) * layer_height_m, floor_height_m));
}

Layer slice_floor_layer(const Floor& floor, double layer_height_m, int k,
                        const SliceOptions& options) {
  const double z0 = k * layer_height_m;
  const double z1 = std::min((k + 1) * layer_height_m, floor.height_m);
  Layer layer = cut_walls(floor.plan, layer_mid_m(floor.height_m, layer_height_m, k), options);
  layer.z_bottom_m = z0;
  layer.z_top_m = z1;
  layer.floor_index = floor.index;
  layer.index = k;
  layer.z_bottom_m = floor.base_elevation_m + z0;
  layer.z_top_m = floor.base_elevation_m + z1;
  return layer;
}

Layer slice_plan_at(const FloorPlan& plan, double z_bottom_m, double z_top_m,
                    const SliceOptions& options) {
  Layer layer = cut_walls(plan, 0.5 * (z_bottom_m + z_top_m), options);
  layer.z_bottom_m = z_bottom_m;
  layer.z_top_m = z_top_m;
  return layer;
}

Layer plan_as_layer(const FloorPlan& plan, const SliceOptions& options) {
  return cut_walls(plan, std::nullopt, options);
}

namespace {

std::array<std::int64_t, 2> quantised(const Eigen::Vector2d& p) {
  return {std::llround(p.x() * 1e6), std::llround(p.y() * 1e6)};
}

GeometryKey::QuantisedSegment quantised(const Layer& layer, const LayerSegment& s, bool& swapped) {
  auto a = quantised(layer.points[s.start_point]), b = quantised(layer.points[s.end_point]);
  swapped = b < a;
  if (swapped) std::swap(a, b);
  return {a[0], a[1], b[0], b[1]};
}

}  // namespace

GeometryKey::GeometryKey(const Layer& layer) {
  segments_.reserve(layer.segments.size());
  bool swapped = false;
  for (const auto& s : layer.segments) segments_.push_back(quantised(layer, s, swapped));
  std::sort(segments_.begin(), segments_.end());
  // FNV-1a over the values' bytes, least significant first: stable across platforms.
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  auto mix = [&](std::int64_t value) {
    auto bits = static_cast<std::uint64_t>(value);
    for (int i = 0; i < 8; ++i) {
      hash ^= (bits >> (8 * i)) & 0xFF;
      hash *= 0x100000001b3ULL;
    }
  };
  mix(static_cast<std::int64_t>(segments_.size()));
  for (const auto& q : segments_)
    for (std::int64_t v : q) mix(v);
  hash_ = hash;
}

int GeometryNumbering::number(const Layer& layer, bool* fresh) {
  if (fresh) *fresh = false;
  if (layer.segments.empty()) return 0;
  const auto [it, added] = numbers_.try_emplace(GeometryKey(layer), count() + 1);
  if (fresh) *fresh = added;
  return it->second;
}

std::optional<std::vector<SegmentMatch>> match_segments(const Layer& from, const Layer& to) {
  if (from.segments.size() != to.segments.size()) return std::nullopt;
  // Each quantised segment of `to`, sorted, with where it is and which way it runs.
  struct Entry {
    GeometryKey::QuantisedSegment key;
    int segment;
    bool swapped;
  };
  std::vector<Entry> entries;
  entries.reserve(to.segments.size());
  for (std::size_t i = 0; i < to.segments.size(); ++i) {
    bool swapped = false;
    const auto key = quantised(to, to.segments[i], swapped);
    entries.push_back({key, static_cast<int>(i), swapped});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.key < b.key || (a.key == b.key && a.segment < b.segment);
  });
  std::vector<char> used(entries.size(), 0);
  std::vector<SegmentMatch> out;
  out.reserve(from.segments.size());
  for (const auto& s : from.segments) {
    bool swapped = false;
    const auto key = quantised(from, s, swapped);
    auto it = std::lower_bound(entries.begin(), entries.end(), key,
                               [](const Entry& e, const auto& k) { return e.key < k; });
    // Equal segments (none in a valid plan) are matched in order, each once.
    while (it != entries.end() && it->key == key && used[it - entries.begin()]) ++it;
    if (it == entries.end() || it->key != key) return std::nullopt;
    used[it - entries.begin()] = 1;
    out.push_back({it->segment, it->swapped != swapped});
  }
  return out;
}

std::uint64_t geometry_hash(const Layer& layer) {
  return GeometryKey(layer).hash();
}

std::string hash_to_hex(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace ccbuild::floors
