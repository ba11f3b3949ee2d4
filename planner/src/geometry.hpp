#pragma once
// Small 2-D geometry for the planner: crossing tests and a grid index of segments.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace ccbuild::planner::detail {

using Vec2 = Eigen::Vector2d;

inline double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Does the travel leg p -> q meet segment [a, b] anywhere except within `eps` of an
/// excluded end of the leg? Touching [a, b]'s own ends counts; running along it counts.
bool leg_crosses(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, bool exclude_p,
                 bool exclude_q, double eps = 1e-6);

/// The legs an air move travels: one straight leg, or x first then y for rectilinear.
struct Legs {
  Vec2 points[3];
  int count = 0;  ///< number of legs, 1 or 2 (0 when the move has no length)
};
Legs travel_legs(const Vec2& from, const Vec2& to, bool rectilinear);

/// Uniform grid over segments; each segment is listed in every cell its bounding box
/// touches. Queries return each segment once.
class SegmentGrid {
 public:
  SegmentGrid() = default;
  SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& segments);

  /// Calls f(index) for every segment whose cells overlap the bounding box of a and b.
  template <class F>
  void for_each_near(const Vec2& a, const Vec2& b, F&& f) const {
    if (segments_.empty()) return;
    const int x0 = cell_x(std::min(a.x(), b.x())), x1 = cell_x(std::max(a.x(), b.x()));
    const int y0 = cell_y(std::min(a.y(), b.y())), y1 = cell_y(std::max(a.y(), b.y()));
    ++stamp_;
    for (int cy = y0; cy <= y1; ++cy) {
      for (int cx = x0; cx <= x1; ++cx) {
        const int cell = cy * nx_ + cx;
        for (int k = start_[cell]; k < start_[cell + 1]; ++k) {
          const int s = items_[k];
          if (seen_[s] == stamp_) continue;
          seen_[s] = stamp_;
          f(s);
        }
      }
    }
  }

  const std::pair<Vec2, Vec2>& segment(int index) const { return segments_[index]; }
  std::size_t size() const { return segments_.size(); }

 private:
  int cell_x(double x) const {
    return std::clamp(static_cast<int>((x - origin_.x()) / cell_), 0, nx_ - 1);
  }
  int cell_y(double y) const {
    return std::clamp(static_cast<int>((y - origin_.y()) / cell_), 0, ny_ - 1);
  }

  std::vector<std::pair<Vec2, Vec2>> segments_;
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;  // CSR: cell -> items
  std::vector<int> items_;
  mutable std::vector<std::uint32_t> seen_;
  mutable std::uint32_t stamp_ = 0;
};

/// Points on a grid for k-nearest-neighbour queries.
class PointGrid {
 public:
  explicit PointGrid(const std::vector<Vec2>& points, double points_per_cell = 2.0);
  /// Indices of up to k points nearest to points[index] by Euclidean distance (not
  /// itself, nor those `skip` rejects), nearest first, ties by index.
  template <class Skip>
  std::vector<int> nearest(int index, int k, Skip&& skip) const;

 private:
  const std::vector<Vec2>& points_;
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;
  std::vector<int> items_;
};

template <class Skip>
std::vector<int> PointGrid::nearest(int index, int k, Skip&& skip) const {
  const Vec2& p = points_[index];
  const int cx = std::clamp(static_cast<int>((p.x() - origin_.x()) / cell_), 0, nx_ - 1);
  const int cy = std::clamp(static_cast<int>((p.y() - origin_.y()) / cell_), 0, ny_ - 1);
  std::vector<std::pair<double, int>> found;
  const int max_ring = std::max(nx_, ny_);
  for (int ring = 0; ring <= max_ring; ++ring) {
    for (int y = cy - ring; y <= cy + ring; ++y) {
      if (y < 0 || y >= ny_) continue;
      for (int x = cx - ring; x <= cx + ring; ++x) {
        if (x < 0 || x >= nx_) continue;
        if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
        const int cell = y * nx_ + x;
        for (int i = start_[cell]; i < start_[cell + 1]; ++i) {
          const int q = items_[i];
          if (q == index || skip(q)) continue;
          found.emplace_back((points_[q] - p).squaredNorm(), q);
        }
      }
    }
    // Points beyond this ring are at least ring * cell away.
    if (static_cast<int>(found.size()) >= k) {
      std::nth_element(found.begin(), found.begin() + (k - 1), found.end());
      const double kth = found[k - 1].first;
      const double reach = ring * cell_;
      if (kth <= reach * reach) break;
    }
  }
  std::sort(found.begin(), found.end());
  if (static_cast<int>(found.size()) > k) found.resize(k);
  std::vector<int> out;
  out.reserve(found.size());
  for (const auto& f : found) out.push_back(f.second);
  return out;
}

/// Signed angle wrapped into (-pi, pi].
inline double wrap_angle(double a) {
  // fmod returns a itself when |a| < 2 pi (it is exact): skipped there, the searches' usual
  // case (fmod was 2% of a large layer's planning time).
  if (!(std::abs(a) < 2.0 * M_PI)) a = std::fmod(a, 2.0 * M_PI);
  if (a <= -M_PI) a += 2.0 * M_PI;
  if (a > M_PI) a -= 2.0 * M_PI;
  return a;
}

}  // namespace ccbuild::planner::detail
