// Small plane geometry (plane.hpp).

#include "ccbuild/floors/plane.hpp"

#include <algorithm>

namespace ccbuild::floors {

std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  if (points.size() < 2) return points;
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) { return cross(a - o, b - o); };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // the lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // the upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point is the first again
  return hull;
}

double polygon_area(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k)
    twice += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  return 0.5 * std::abs(twice);
}

}  // namespace ccbuild::floors
