// The volume of a wall's body between two heights (ifc_internal.hpp): how a wall's
// NetVolume is shared between the floors, and between a floor and the slab over it.

#include <algorithm>
#include <cmath>

#include "ccbuild/floors/plane.hpp"
#include "ifc_internal.hpp"

namespace ccbuild::import::ifc {

namespace {

using Eigen::Vector2d;

/// The part of a polygon (h, z) on the side of z = `cut` where `keep_above` says
/// (Sutherland-Hodgman against one line).
std::vector<Vector2d> clip_at(const std::vector<Vector2d>& polygon, double cut, bool keep_above) {
  const auto inside = [&](const Vector2d& p) { return keep_above ? p.y() >= cut : p.y() <= cut; };
  std::vector<Vector2d> out;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vector2d& p = polygon[k];
    const Vector2d& q = polygon[(k + 1) % polygon.size()];
    if (inside(p)) out.push_back(p);
    if (inside(p) != inside(q)) {
      const double t = (cut - p.y()) / (q.y() - p.y());
      out.push_back(p + t * (q - p));
    }
  }
  return out;
}

}  // namespace

double body_volume_between_m3(const FoundWall& wall, double lo_m, double hi_m) {
  if (!(hi_m > lo_m)) return 0.0;
  double m3 = 0.0;
  for (const FoundWall::UprightPiece& piece : wall.body_volume)
    m3 += floors::polygon_area(clip_at(clip_at(piece.hz, lo_m, true), hi_m, false)) * piece.depth_m;
  return m3;
}

}  // namespace ccbuild::import::ifc
