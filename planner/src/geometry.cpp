#include "geometry.hpp"

namespace ccbuild::planner::detail {

bool leg_crosses(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, bool exclude_p,
                 bool exclude_q, double eps) {
  const Vec2 d = q - p;
  const double length = d.norm();
  if (length <= eps) return false;
  // Parameters along the leg within eps of an excluded end do not count.
  const double t_min = exclude_p ? eps / length : -eps / length;
  const double t_max = exclude_q ? 1.0 - eps / length : 1.0 + eps / length;
  const Vec2 e = b - a;
  const double e_length = e.norm();
  const double denominator = cross2(d, e);
  if (e_length <= eps) {  // a point-like segment
    const double t = (a - p).dot(d) / (length * length);
    return t > t_min && t < t_max && std::abs(cross2(d, a - p)) / length <= eps;
  }
  if (std::abs(denominator) <= 1e-12 * length * e_length) {
    // Parallel: crossing only when collinear and overlapping.
    if (std::abs(cross2(d, a - p)) / length > eps) return false;
    double t0 = (a - p).dot(d) / (length * length);
    double t1 = (b - p).dot(d) / (length * length);
    if (t0 > t1) std::swap(t0, t1);
    return std::min(t1, t_max) > std::max(t0, t_min);
  }
  const double t = cross2(a - p, e) / denominator;
  const double u = cross2(a - p, d) / denominator;
  const double u_eps = eps / e_length;
  return t > t_min && t < t_max && u >= -u_eps && u <= 1.0 + u_eps;
}

Legs travel_legs(const Vec2& from, const Vec2& to, bool rectilinear) {
  Legs legs;
  legs.points[0] = from;
  if ((to - from).norm() <= 1e-12) return legs;
  if (!rectilinear || std::abs(to.x() - from.x()) <= 1e-12 ||
      std::abs(to.y() - from.y()) <= 1e-12) {
    legs.points[1] = to;
    legs.count = 1;
    return legs;
  }
  legs.points[1] = Vec2(to.x(), from.y());
  legs.points[2] = to;
  legs.count = 2;
  return legs;
}

SegmentGrid::SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& segments) : segments_(segments) {
  seen_.assign(segments_.size(), 0);
  if (segments_.empty()) return;
  Vec2 lo = segments_[0].first, hi = lo;
  double total = 0.0;
  for (const auto& [a, b] : segments_) {
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
    total += (b - a).norm();
  }
  origin_ = lo;
  const Vec2 extent = (hi - lo).cwiseMax(Vec2(1e-3, 1e-3));
  // About one wall length per cell keeps both lists and scans short.
  cell_ = std::max(total / segments_.size(), 1e-3);
  cell_ = std::max(cell_, std::sqrt(extent.x() * extent.y() / (4.0 * segments_.size() + 1.0)));
  nx_ = std::max(1, static_cast<int>(extent.x() / cell_) + 1);
  ny_ = std::max(1, static_cast<int>(extent.y() / cell_) + 1);
  std::vector<int> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto cells = [&](const std::pair<Vec2, Vec2>& s, auto&& f) {
    const int x0 = cell_x(std::min(s.first.x(), s.second.x())),
              x1 = cell_x(std::max(s.first.x(), s.second.x()));
    const int y0 = cell_y(std::min(s.first.y(), s.second.y())),
              y1 = cell_y(std::max(s.first.y(), s.second.y()));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) f(y * nx_ + x);
  };
  for (const auto& s : segments_) cells(s, [&](int c) { ++count[c + 1]; });
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.assign(count.back(), 0);
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int i = 0; i < static_cast<int>(segments_.size()); ++i)
    cells(segments_[i], [&](int c) { items_[fill[c]++] = i; });
}

PointGrid::PointGrid(const std::vector<Vec2>& points, double points_per_cell) : points_(points) {
  if (points_.empty()) {
    start_.assign(2, 0);
    return;
  }
  Vec2 lo = points_[0], hi = lo;
  for (const auto& p : points_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  origin_ = lo;
  const Vec2 extent = (hi - lo).cwiseMax(Vec2(1e-3, 1e-3));
  cell_ = std::sqrt(extent.x() * extent.y() * points_per_cell / points_.size());
  cell_ = std::max(cell_, 1e-3);
  nx_ = std::max(1, std::min(4096, static_cast<int>(extent.x() / cell_) + 1));
  ny_ = std::max(1, std::min(4096, static_cast<int>(extent.y() / cell_) + 1));
  cell_ = std::max(extent.x() / nx_, extent.y() / ny_) * 1.000001;
  std::vector<int> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto cell_of = [&](const Vec2& p) {
    const int x = std::clamp(static_cast<int>((p.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int y = std::clamp(static_cast<int>((p.y() - origin_.y()) / cell_), 0, ny_ - 1);
    return y * nx_ + x;
  };
  for (const auto& p : points_) ++count[cell_of(p) + 1];
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.assign(points_.size(), 0);
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int i = 0; i < static_cast<int>(points_.size()); ++i)
    items_[fill[cell_of(points_[i])]++] = i;
}

}  // namespace ccbuild::planner::detail
