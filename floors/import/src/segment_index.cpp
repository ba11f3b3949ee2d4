#include "segment_index.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ccbuild::import::detail {
namespace {

/// Coordinates beyond this (or not finite) are indexed here: the grid's edge.
constexpr double kEdge_m = 1e15;
/// Cell numbers are clamped to this, so that they pack into 32 bits each.
constexpr double kMaxCell = 1e9;
constexpr int kMaxLevel = 62;

double clamped(double v) {
  if (std::isnan(v)) return kEdge_m;
  return std::clamp(v, -kEdge_m, kEdge_m);
}

std::uint64_t key(std::int64_t cx, std::int64_t cy) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cx + (1ll << 31))) << 32) |
         static_cast<std::uint32_t>(cy + (1ll << 31));
}

}  // namespace

std::int64_t SegmentIndex::cell_of(double v, double cell_m) const {
  return static_cast<std::int64_t>(std::floor(std::clamp(v / cell_m, -kMaxCell, kMaxCell)));
}

template <class Visit>
void SegmentIndex::visit_cells(const Level& level, const Box& box, Visit visit) const {
  if (level.cells.empty()) return;
  const std::int64_t cx0 = cell_of(box.x0, level.cell_m), cx1 = cell_of(box.x1, level.cell_m);
  const std::int64_t cy0 = cell_of(box.y0, level.cell_m), cy1 = cell_of(box.y1, level.cell_m);
  for (std::int64_t cx = cx0; cx <= cx1; ++cx)
    for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
      const auto it = level.cells.find(key(cx, cy));
      if (it == level.cells.end()) continue;
      for (std::uint32_t k = it->second.first; k < it->second.second; ++k) visit(level.ids[k]);
    }
}

SegmentIndex::SegmentIndex(const std::vector<Segment>& segments, double reach_m)
    : base_m_(std::max(2.0 * reach_m, 1e-4)), stamp_(segments.size(), 0) {
  boxes_.reserve(segments.size());
  level_of_.reserve(segments.size());
  // (level, cell key, id), sorted: each cell's ids ascending, in one run.
  std::vector<std::tuple<int, std::uint64_t, std::uint32_t>> entries;
  entries.reserve(segments.size() * 2);
  int top = -1;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const auto& [a, b] = segments[k];
    const Box box{clamped(std::min(a.x(), b.x())), clamped(std::min(a.y(), b.y())),
                  clamped(std::max(a.x(), b.x())), clamped(std::max(a.y(), b.y()))};
    boxes_.push_back(box);
    const double extent = std::max(box.x1 - box.x0, box.y1 - box.y0);
    int level = 0;
    while (level < kMaxLevel && std::ldexp(base_m_, level) < extent) ++level;
    level_of_.push_back(level);
    top = std::max(top, level);
    const double cell = std::ldexp(base_m_, level);
    for (std::int64_t cx = cell_of(box.x0, cell); cx <= cell_of(box.x1, cell); ++cx)
      for (std::int64_t cy = cell_of(box.y0, cell); cy <= cell_of(box.y1, cell); ++cy)
        entries.emplace_back(level, key(cx, cy), static_cast<std::uint32_t>(k));
  }
  std::sort(entries.begin(), entries.end());
  levels_.resize(static_cast<std::size_t>(top + 1));
  for (int level = 0; level <= top; ++level)
    levels_[static_cast<std::size_t>(level)].cell_m = std::ldexp(base_m_, level);
  for (std::size_t e = 0; e < entries.size();) {
    const auto& [level, cell, id] = entries[e];
    Level& l = levels_[static_cast<std::size_t>(level)];
    const auto first = static_cast<std::uint32_t>(l.ids.size());
    std::size_t f = e;
    for (;
         f < entries.size() && std::get<0>(entries[f]) == level && std::get<1>(entries[f]) == cell;
         ++f)
      l.ids.push_back(std::get<2>(entries[f]));
    l.cells.emplace(cell, std::pair{first, static_cast<std::uint32_t>(l.ids.size())});
    e = f;
  }
}

const std::vector<std::size_t>& SegmentIndex::near_point(const Eigen::Vector2d& p,
                                                         double r_m) const {
  found_.clear();
  if (++epoch_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
  const Box query{clamped(p.x()) - r_m, clamped(p.y()) - r_m, clamped(p.x()) + r_m,
                  clamped(p.y()) + r_m};
  for (const Level& level : levels_)
    visit_cells(level, query, [&](std::uint32_t id) {
      if (stamp_[id] == epoch_) return;
      stamp_[id] = epoch_;
      if (within(boxes_[id], query, 0.0)) found_.push_back(id);
    });
  std::sort(found_.begin(), found_.end());
  return found_;
}

std::optional<std::size_t> SegmentIndex::near_pairs(
    double r_m, std::size_t max_pairs,
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) const {
  pairs.clear();
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (++epoch_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      epoch_ = 1;
    }
    const Box& own = boxes_[i];
    const Box query{own.x0 - r_m, own.y0 - r_m, own.x1 + r_m, own.y1 + r_m};
    const int level_i = level_of_[i];
    for (std::size_t level = static_cast<std::size_t>(level_i); level < levels_.size(); ++level)
      visit_cells(levels_[level], query, [&](std::uint32_t j) {
        // Each pair once: from the one of the two on the finer level (the lower id on one).
        if (level_of_[j] == level_i && j <= i) return;
        if (stamp_[j] == epoch_) return;
        stamp_[j] = epoch_;
        const auto me = static_cast<std::uint32_t>(i);
        if (within(own, boxes_[j], r_m)) pairs.emplace_back(std::min(me, j), std::max(me, j));
      });
    if (pairs.size() > max_pairs) return i;
  }
  std::sort(pairs.begin(), pairs.end());
  return std::nullopt;
}

}  // namespace ccbuild::import::detail
