#pragma once
// Small plane geometry shared by slicing and the importers.

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace ccbuild::floors {

/// The z of the cross product of two plane vectors: positive when `b` turns
/// anticlockwise from `a`, 0 when they are parallel.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A length, m, rounded to the nanometre: what unit conversions and placements leave
/// beyond that is noise (0.9000000000000004), and imported plans are read by people.
inline double round_to_nanometre(double value_m) {
  return std::round(value_m * 1e9) / 1e9;
}

/// The convex hull of `points`, anticlockwise, without collinear corners (Andrew's
/// monotone chain); fewer than two points come back as they are.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points);

/// The area of a simple polygon (either way round), from its corners: the shoelace formula.
double polygon_area(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace ccbuild::floors
