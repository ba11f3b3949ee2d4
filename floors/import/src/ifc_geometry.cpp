// The geometry of walls and openings read through IFC++: axes, extruded bodies, the
// centreline, thickness and height of a wall, the corners of an opening (ifc.hpp).

#include <ifcpp/IFC4/include/IfcArbitraryClosedProfileDef.h>
#include <ifcpp/IFC4/include/IfcArcIndex.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement2D.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement3D.h>
#include <ifcpp/IFC4/include/IfcBoolean.h>
#include <ifcpp/IFC4/include/IfcBooleanOperator.h>
#include <ifcpp/IFC4/include/IfcBooleanResult.h>
#include <ifcpp/IFC4/include/IfcBuilding.h>
#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcCartesianPoint.h>
#include <ifcpp/IFC4/include/IfcCartesianPointList2D.h>
#include <ifcpp/IFC4/include/IfcCartesianPointList3D.h>
#include <ifcpp/IFC4/include/IfcCircle.h>
#include <ifcpp/IFC4/include/IfcCircleProfileDef.h>
#include <ifcpp/IFC4/include/IfcCompositeCurve.h>
#include <ifcpp/IFC4/include/IfcCompositeCurveSegment.h>
#include <ifcpp/IFC4/include/IfcConic.h>
#include <ifcpp/IFC4/include/IfcConversionBasedUnit.h>
#include <ifcpp/IFC4/include/IfcCurtainWall.h>
#include <ifcpp/IFC4/include/IfcDirection.h>
#include <ifcpp/IFC4/include/IfcDirectionSenseEnum.h>
#include <ifcpp/IFC4/include/IfcExtrudedAreaSolid.h>
#include <ifcpp/IFC4/include/IfcGeometricRepresentationContext.h>
#include <ifcpp/IFC4/include/IfcGloballyUniqueId.h>
#include <ifcpp/IFC4/include/IfcHalfSpaceSolid.h>
#include <ifcpp/IFC4/include/IfcIndexedPolyCurve.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcLayerSetDirectionEnum.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcLine.h>
#include <ifcpp/IFC4/include/IfcLocalPlacement.h>
#include <ifcpp/IFC4/include/IfcMapConversion.h>
#include <ifcpp/IFC4/include/IfcMaterial.h>
#include <ifcpp/IFC4/include/IfcMaterialLayer.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSet.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSetUsage.h>
#include <ifcpp/IFC4/include/IfcMaterialList.h>
#include <ifcpp/IFC4/include/IfcMeasureWithUnit.h>
#include <ifcpp/IFC4/include/IfcNonNegativeLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcOpeningElement.h>
#include <ifcpp/IFC4/include/IfcOpeningElementTypeEnum.h>
#include <ifcpp/IFC4/include/IfcPlane.h>
#include <ifcpp/IFC4/include/IfcPolygonalBoundedHalfSpace.h>
#include <ifcpp/IFC4/include/IfcPolyline.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProductDefinitionShape.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcRatioMeasure.h>
#include <ifcpp/IFC4/include/IfcReal.h>
#include <ifcpp/IFC4/include/IfcRectangleProfileDef.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelAssociatesMaterial.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelDefinesByType.h>
#include <ifcpp/IFC4/include/IfcRelFillsElement.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcRepresentation.h>
#include <ifcpp/IFC4/include/IfcSIPrefix.h>
#include <ifcpp/IFC4/include/IfcSIUnit.h>
#include <ifcpp/IFC4/include/IfcSIUnitName.h>
#include <ifcpp/IFC4/include/IfcSite.h>
#include <ifcpp/IFC4/include/IfcSlab.h>
#include <ifcpp/IFC4/include/IfcSlabTypeEnum.h>
#include <ifcpp/IFC4/include/IfcTrimmedCurve.h>
#include <ifcpp/IFC4/include/IfcTypeObject.h>
#include <ifcpp/IFC4/include/IfcUnitAssignment.h>
#include <ifcpp/IFC4/include/IfcUnitEnum.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/model/BuildingException.h>
#include <ifcpp/model/BuildingModel.h>
#include <ifcpp/reader/ReaderSTEP.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plane.hpp"
#include "ifc_reader.hpp"

namespace ccbuild::import::ifc::detail {

std::vector<Vector2d> Reader::curve_points(const std::shared_ptr<IfcCurve>& curve, bool& curved,
                                           int depth) const {
  std::vector<Vector2d> out;
  if (depth > 8) throw Unusable{"its curves nest too deep"};
  if (auto poly = as<IfcPolyline>(curve)) {
    for (const auto& p : poly->m_Points) out.push_back(point(p).head<2>());
  } else if (auto indexed = as<IfcIndexedPolyCurve>(curve)) {
    for (const auto& s : indexed->m_Segments)
      if (as<IfcArcIndex>(s)) curved = true;
    if (auto list = as<IfcCartesianPointList2D>(indexed->m_Points)) {
      for (const auto& c : list->m_CoordList)
        if (c.size() >= 2 && c[0] && c[1])
          out.emplace_back(c[0]->m_value * unit_, c[1]->m_value * unit_);
    } else if (auto list3 = as<IfcCartesianPointList3D>(indexed->m_Points)) {
      for (const auto& c : list3->m_CoordList)
        if (c.size() >= 2 && c[0] && c[1])
          out.emplace_back(c[0]->m_value * unit_, c[1]->m_value * unit_);
    }
  } else if (auto composite = as<IfcCompositeCurve>(curve)) {
    for (const auto& segment : composite->m_Segments) {
      if (!segment) continue;
      auto pts = curve_points(segment->m_ParentCurve, curved, depth + 1);
      if (segment->m_SameSense && !segment->m_SameSense->m_value)
        std::reverse(pts.begin(), pts.end());
      for (const auto& p : pts)
        if (out.empty() || (out.back() - p).norm() > 1e-9) out.push_back(p);
    }
  } else if (auto trimmed = as<IfcTrimmedCurve>(curve)) {
    if (as<IfcConic>(trimmed->m_BasisCurve)) {
      curved = true;
      return out;
    }
    if (as<IfcLine>(trimmed->m_BasisCurve)) {
      for (const auto* trim : {&trimmed->m_Trim1, &trimmed->m_Trim2})
        for (const auto& t : *trim)
          if (auto p = as<IfcCartesianPoint>(t)) {
            out.push_back(point(p).head<2>());
            break;
          }
      if (out.size() != 2) throw Unusable{"its axis is a line trimmed by parameters, not points"};
      return out;
    }
    throw Unusable{std::string("its axis is a trimmed ") +
                   (trimmed->m_BasisCurve ? trimmed->m_BasisCurve->className() : "nothing")};
  } else if (as<IfcConic>(curve)) {
    curved = true;
  } else if (curve) {
    throw Unusable{std::string("a curve ccbuild does not read (") + curve->className() + ")"};
  }
  return out;
}

std::optional<Reader::Solid> Reader::solid_of(const std::shared_ptr<IfcRepresentationItem>& item,
                                              int depth) const {
  if (depth > 16) return std::nullopt;
  if (auto boolean = as<IfcBooleanResult>(item)) {
    auto first = solid_of(as<IfcRepresentationItem>(boolean->m_FirstOperand), depth + 1);
    if (!first) return first;
    first->clipped = true;
    // A plane's half-space taken away (how exporters cut a gable under its roof).
    const auto half = as<IfcHalfSpaceSolid>(boolean->m_SecondOperand);
    const auto plane = half ? as<IfcPlane>(half->m_BaseSurface) : nullptr;
    if (boolean->m_Operator && boolean->m_Operator->m_enum == IfcBooleanOperator::ENUM_DIFFERENCE &&
        plane && plane->m_Position) {
      const Isometry3d at = axis_placement(plane->m_Position);
      // AgreementFlag true: the plane's normal points away from the half-space's material.
      const bool away = half->m_AgreementFlag && half->m_AgreementFlag->m_value;
      const Vector3d normal = at.linear().col(2).normalized();
      Solid::Cut cut{at.translation(), away ? Vector3d(-normal) : normal, {}, false};
      if (const auto bounded = as<IfcPolygonalBoundedHalfSpace>(half)) {
        cut.prisms = prisms_of(*bounded);
        cut.bounded = cut.prisms.empty();
      }
      first->cuts.push_back(std::move(cut));
    } else {
      first->cut_unread = true;
    }
    return first;
  }
  auto extruded = as<IfcExtrudedAreaSolid>(item);
  if (!extruded || !extruded->m_SweptArea) return std::nullopt;
  Solid s;
  if (extruded->m_Position) s.position = axis_placement(extruded->m_Position);
  if (!extruded->m_Depth) return std::nullopt;
  s.extrusion = direction(extruded->m_ExtrudedDirection, Vector3d::UnitZ()) *
                extruded->m_Depth->m_value * unit_;
  const auto& area = extruded->m_SweptArea;
  if (auto rect = as<IfcRectangleProfileDef>(area)) {
    if (!rect->m_XDim || !rect->m_YDim) return std::nullopt;
    const double hx = 0.5 * rect->m_XDim->m_value * unit_, hy = 0.5 * rect->m_YDim->m_value * unit_;
    Isometry3d p = Isometry3d::Identity();
    if (rect->m_Position) p = axis_placement(rect->m_Position);
    for (const Vector2d& c :
         {Vector2d(-hx, -hy), Vector2d(hx, -hy), Vector2d(hx, hy), Vector2d(-hx, hy)})
      s.profile.push_back((p * Vector3d(c.x(), c.y(), 0.0)).head<2>());
  } else if (auto circle = as<IfcCircleProfileDef>(area)) {
    if (!circle->m_Radius) return std::nullopt;
    const double r = circle->m_Radius->m_value * unit_;
    Isometry3d p = Isometry3d::Identity();
    if (circle->m_Position) p = axis_placement(circle->m_Position);
    for (int k = 0; k < 16; ++k) {
      const double a = 2.0 * M_PI * k / 16.0;
      s.profile.push_back((p * Vector3d(r * std::cos(a), r * std::sin(a), 0.0)).head<2>());
    }
    s.curved = true;
  } else if (auto arbitrary = as<IfcArbitraryClosedProfileDef>(area)) {
    s.profile = curve_points(arbitrary->m_OuterCurve, s.curved, 0);
    if (s.profile.size() > 1 && (s.profile.front() - s.profile.back()).norm() < 1e-9)
      s.profile.pop_back();
  } else {
    return std::nullopt;
  }
  if (s.profile.size() < 3) return std::nullopt;
  return s;
}

void Reader::read_openings(const IfcElement& wall, const Isometry3d& /*wall_world*/,
                           double z_shift_m, FoundWall& into, ModelContents& out) {
  for (const auto& weak : wall.m_HasOpenings_inverse) {
    auto rel = weak.lock();
    if (!rel || !rel->m_RelatedOpeningElement) continue;
    const auto& opening = rel->m_RelatedOpeningElement;
    FoundOpening found;
    found.what = element_of(*opening);
    found.label = found.what.name;
    if (auto o = as<IfcOpeningElement>(opening)) {
      if (o->m_PredefinedType &&
          o->m_PredefinedType->m_enum == IfcOpeningElementTypeEnum::ENUM_RECESS) {
        out.notes.left_out("recesses left out", found.what.describe() + " in " +
                                                    into.what.describe() +
                                                    ": a recess, not through the wall; left out");
        ++out.left_out;
        continue;
      }
      for (const auto& fills : o->m_HasFillings_inverse)
        if (auto f = fills.lock(); f && f->m_RelatedBuildingElement) {
          const Element filler = element_of(*f->m_RelatedBuildingElement);
          found.filled_by = filler.describe();
          if (!filler.name.empty()) found.label = filler.name;
          break;
        }
    }
    try {
      const Isometry3d place = world(opening->m_ObjectPlacement, found.what);
      if (opening->m_Representation)
        for (const auto& rep : opening->m_Representation->m_Representations) {
          if (!rep) continue;
          for (const auto& item : rep->m_Items) {
            const auto solid = solid_of(item, 0);
            if (!solid) continue;
            for (const Vector2d& p : solid->profile) {
              const Vector3d base = place * (solid->position * Vector3d(p.x(), p.y(), 0.0));
              const Vector3d top =
                  base + place.linear() * (solid->position.linear() * solid->extrusion);
              for (Vector3d c : {base, top}) {
                c.z() += z_shift_m;
                found.corners_m.push_back(c);
              }
            }
          }
        }
    } catch (const Unusable& u) {
      found.corners_m.clear();
      out.notes.left_out(
          "openings that cannot be read left out",
          found.what.describe() + " in " + into.what.describe() + ": " + u.why + "; left out");
      ++out.left_out;
      continue;
    }
    if (found.corners_m.empty()) {
      out.notes.left_out("openings without an extruded body left out",
                         found.what.describe() + " in " + into.what.describe() +
                             ": no extruded body to measure it by; left out");
      ++out.left_out;
      continue;
    }
    into.openings.push_back(std::move(found));
  }
}

namespace {

/// Twice the signed area of the corner p, q, r: > 0 when it turns counter-clockwise.
double turn(const Vector2d& p, const Vector2d& q, const Vector2d& r) {
  const Vector2d e = q - p, f = r - q;
  return e.x() * f.y() - e.y() * f.x();
}

/// A simple polygon, counter-clockwise, as convex pieces: itself when convex, else the
/// triangles of its ears clipped one by one; empty when no ear is found (it crosses itself).
std::vector<std::vector<Vector2d>> convex_pieces(std::vector<Vector2d> polygon) {
  const auto convex = [](const std::vector<Vector2d>& p) {
    for (std::size_t k = 0; k < p.size(); ++k)
      if (turn(p[k], p[(k + 1) % p.size()], p[(k + 2) % p.size()]) < -1e-12) return false;
    return true;
  };
  std::vector<std::vector<Vector2d>> out;
  while (polygon.size() > 3 && !convex(polygon)) {
    const std::size_t n = polygon.size();
    bool clipped = false;
    for (std::size_t k = 0; k < n && !clipped; ++k) {
      const Vector2d &p = polygon[(k + n - 1) % n], &q = polygon[k], &r = polygon[(k + 1) % n];
      if (turn(p, q, r) <= 1e-12) continue;  // a reflex or straight corner is no ear
      bool empty = true;
      for (std::size_t j = 0; j < n && empty; ++j) {
        const Vector2d& x = polygon[j];
        if (j == k || j == (k + 1) % n || j == (k + n - 1) % n) continue;
        empty = !(turn(p, q, x) >= 0.0 && turn(q, r, x) >= 0.0 && turn(r, p, x) >= 0.0);
      }
      if (!empty) continue;
      out.push_back({p, q, r});
      polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped) return {};
  }
  out.push_back(std::move(polygon));
  return out;
}

}  // namespace

std::vector<Reader::Solid::Prism> Reader::prisms_of(
    const IfcPolygonalBoundedHalfSpace& half) const {
  // A boundary of more corners than this is read as the whole half-space (and said).
  constexpr std::size_t kMostCorners = 1000;
  if (!half.m_PolygonalBoundary) return {};
  const Isometry3d at = half.m_Position ? axis_placement(half.m_Position) : Isometry3d::Identity();
  std::vector<Vector2d> polygon;
  bool curved = false;
  try {
    polygon = curve_points(half.m_PolygonalBoundary, curved, 0);
  } catch (const Unusable&) {
    return {};
  }
  if (polygon.size() > 1 && (polygon.front() - polygon.back()).norm() < 1e-9) polygon.pop_back();
  if (curved || polygon.size() < 3 || polygon.size() > kMostCorners) return {};
  double area2 = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vector2d &p = polygon[k], &q = polygon[(k + 1) % polygon.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
  }
  if (std::abs(area2) < 1e-12) return {};
  if (area2 < 0.0) std::reverse(polygon.begin(), polygon.end());
  std::vector<Solid::Prism> prisms;
  for (const auto& piece : convex_pieces(std::move(polygon))) {
    Solid::Prism prism;
    for (std::size_t k = 0; k < piece.size(); ++k) {
      const Vector2d e = piece[(k + 1) % piece.size()] - piece[k];
      if (e.norm() < 1e-12) continue;
      const Vector2d out = Vector2d(e.y(), -e.x()).normalized();  // counter-clockwise: right
      prism.push_back({at * Vector3d(piece[k].x(), piece[k].y(), 0.0),
                       at.linear() * Vector3d(out.x(), out.y(), 0.0)});
    }
    prisms.push_back(std::move(prism));
  }
  return prisms;
}

std::vector<std::pair<double, double>> Reader::top_outline(const std::vector<Solid>& bodies,
                                                           const Vector2d& a, const Vector2d& b,
                                                           double z0_m) {
  // Each solid's outline in the wall's elevation, (along the piece, z): a solid extruded
  // through the wall is its profile; one extruded upwards the box over its footprint.
  const double length_m = (b - a).norm();
  const Vector2d d = (b - a) / length_m;
  std::vector<std::vector<Vector2d>> outlines;
  for (const Solid& body : bodies) {
    const Vector3d along = body.position.linear() * body.extrusion;
    std::vector<Vector2d> outline;
    if (std::abs(along.normalized().z()) <= 1e-6) {
      if (std::abs(along.head<2>().normalized().dot(d)) > 1e-6) continue;  // along the wall
      for (const Vector2d& p : body.profile) {
        const Vector3d q = body.position * Vector3d(p.x(), p.y(), 0.0);
        outline.emplace_back(d.dot(q.head<2>() - a), q.z());
      }
    } else {
      double s0 = std::numeric_limits<double>::infinity(), s1 = -s0;
      double z_lo = s0, z_hi = -s0;
      for (const Vector2d& p : body.profile) {
        const Vector3d q = body.position * Vector3d(p.x(), p.y(), 0.0);
        s0 = std::min(s0, d.dot(q.head<2>() - a));
        s1 = std::max(s1, d.dot(q.head<2>() - a));
        z_lo = std::min({z_lo, q.z(), q.z() + along.z()});
        z_hi = std::max({z_hi, q.z(), q.z() + along.z()});
      }
      outline = {{s0, z_lo}, {s1, z_lo}, {s1, z_hi}, {s0, z_hi}};
    }
    // A plane through `point` with unit normal `n`, along the piece: alpha s + beta z +
    // gamma, positive on the side `n` points to.
    struct Side {
      double alpha, beta, gamma;
      double operator()(const Vector2d& p) const { return alpha * p.x() + beta * p.y() + gamma; }
      Side flipped() const { return {-alpha, -beta, -gamma}; }
    };
    const auto side_of = [&](const Vector3d& point, const Vector3d& n) {
      return Side{n.x() * d.x() + n.y() * d.y(), n.z(),
                  n.x() * (a.x() - point.x()) + n.y() * (a.y() - point.y()) - n.z() * point.z()};
    };
    // The part of `polygon` where every side is <= 0 (Sutherland-Hodgman).
    const auto clip = [](std::vector<Vector2d> polygon, const std::vector<Side>& sides) {
      for (const Side& side : sides) {
        std::vector<Vector2d> kept;
        for (std::size_t k = 0; k < polygon.size(); ++k) {
          const Vector2d& p = polygon[k];
          const Vector2d& q = polygon[(k + 1) % polygon.size()];
          const double sp = side(p), sq = side(q);
          if (sp <= 0.0) kept.push_back(p);
          if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))
            kept.push_back(p + (q - p) * (sp / (sp - sq)));
        }
        polygon = std::move(kept);
      }
      return polygon;
    };
    // Each half-space taken away, along the piece. Unbounded: the outline clipped to the
    // other side. Bounded by a prism: what is outside the half-space, and inside it what is
    // outside the prism, face by face (outside face k, inside the faces before it), so that
    // the pieces cover what is kept once.
    // Prisms that do not overlap are taken away one after the other.
    std::vector<std::vector<Vector2d>> pieces = {outline};
    for (const Solid::Cut& cut : body.cuts) {
      const Side removed = side_of(cut.point, cut.removed);
      const std::vector<Solid::Prism> prisms =
          cut.prisms.empty() ? std::vector<Solid::Prism>{{}} : cut.prisms;
      for (const Solid::Prism& prism : prisms) {
        std::vector<std::vector<Vector2d>> kept;
        for (const auto& piece : pieces) {
          kept.push_back(clip(piece, {removed}));
          std::vector<Side> inside = {removed.flipped()};
          for (const Solid::Face& face : prism) {
            const Side out = side_of(face.point, face.outward);
            inside.push_back(out.flipped());
            kept.push_back(clip(piece, inside));
            inside.back() = out;
          }
        }
        pieces.clear();
        for (auto& piece : kept)
          if (piece.size() >= 3) pieces.push_back(std::move(piece));
      }
    }
    for (auto& piece : pieces) outlines.push_back(std::move(piece));
  }
  // The highest point of any outline over `s` (its edges over s, either end included when
  // `right` says which side of a vertical step counts); nullopt where none is.
  const auto top_at = [&](double s, bool right) -> std::optional<double> {
    std::optional<double> z;
    for (const auto& o : outlines)
      for (std::size_t k = 0; k < o.size(); ++k) {
        const Vector2d& p = o[k];
        const Vector2d& q = o[(k + 1) % o.size()];
        const double lo = std::min(p.x(), q.x()), hi = std::max(p.x(), q.x());
        if (hi - lo < 1e-9 || s < lo || s > hi || (right ? s >= hi : s <= lo)) continue;
        const double at = p.y() + (q.y() - p.y()) * (s - p.x()) / (q.x() - p.x());
        z = std::max(z.value_or(at), at);
      }
    return z;
  };
  // Sampled just either side of every corner along the piece: linear in between.
  std::vector<double> at = {0.0, length_m};
  for (const auto& o : outlines)
    for (const Vector2d& p : o)
      if (p.x() > 0.0 && p.x() < length_m) at.push_back(p.x());
  std::sort(at.begin(), at.end());
  // Pieces of one body share their corners: each place once.
  at.erase(std::unique(at.begin(), at.end(), [](double x, double y) { return y - x < 1e-9; }),
           at.end());
  std::vector<std::pair<double, double>> top;
  for (const double s : at)
    for (const bool right : {false, true}) {
      if ((s == 0.0 && !right) || (s == length_m && right)) continue;
      const auto z = top_at(s, right);
      if (!z) continue;
      const double z_m = z0_m + *z;
      if (!top.empty() && std::abs(top.back().first - s) < 1e-9 &&
          std::abs(top.back().second - z_m) < 1e-9)
        continue;
      // A vertical step: the two sides a micrometre apart, so the offsets increase.
      const double s_m = !top.empty() && s <= top.back().first ? top.back().first + 1e-6 : s;
      top.emplace_back(s_m, z_m);
    }
  // Points on a straight line between their neighbours say nothing.
  std::vector<std::pair<double, double>> kept;
  for (std::size_t k = 0; k < top.size(); ++k) {
    if (!kept.empty() && k + 1 < top.size()) {
      const auto& [s0, t0] = kept.back();
      const auto& [s1, t1] = top[k + 1];
      const auto& [s, t] = top[k];
      if (s1 > s0 && std::abs(t0 + (t1 - t0) * (s - s0) / (s1 - s0) - t) < 1e-6) continue;
    }
    kept.push_back(top[k]);
  }
  return kept;
}

void Reader::read_wall(const std::shared_ptr<IfcWall>& wall, const Element& parent,
                       double z_shift_m, FoundStorey& storey, ModelContents& out, int depth) {
  FoundWall found;
  found.what = element_of(*wall);
  found.net_volume_m3 = net_volume_m3(*wall, found.what, out);
  const std::string who =
      found.what.describe() + (parent.guid.empty() ? "" : " (part of " + parent.describe() + ")");
  // Each reason a kind of its own (a reason with a number in it: `kind` says which).
  const auto skip = [&](const std::string& why, const std::string& kind = std::string()) {
    out.notes.left_out("walls left out: " + (kind.empty() ? why : kind),
                       who + ": " + why + "; left out");
    ++out.left_out;
  };
  // A wall made of parts (IfcRelAggregates) without geometry of its own: its parts.
  if (!wall->m_Representation && depth < 4) {
    bool parts = false;
    for (const auto& weak : wall->m_IsDecomposedBy_inverse)
      if (auto rel = weak.lock())
        for (const auto& part : rel->m_RelatedObjects)
          if (auto w = as<IfcWall>(part)) {
            parts = true;
            read_wall(w, found.what, z_shift_m, storey, out, depth + 1);
          }
    if (parts) return;
  }
  try {
    const Isometry3d place = world(wall->m_ObjectPlacement, found.what);
    if (std::abs(place.linear().col(2).z()) < 1.0 - 1e-6)
      return skip(
          "its placement is tilted (its z axis is not vertical): a sloped wall ccbuild "
          "cannot print");
    std::vector<Vector2d> axis;
    bool curved = false;
    // Every solid of the body: Revit, for one, exports a layered wall as one extrusion per
    // layer, side by side; the wall is all of them.
    std::vector<Solid> bodies;
    if (wall->m_Representation)
      for (const auto& rep : wall->m_Representation->m_Representations) {
        if (!rep) continue;
        const std::string id = lower(label(rep->m_RepresentationIdentifier));
        if (id == "axis") {
          for (const auto& item : rep->m_Items)
            if (auto c = as<IfcCurve>(item); c && axis.empty() && !curved)
              axis = curve_points(c, curved, 0);
        } else if (bodies.empty()) {
          for (const auto& item : rep->m_Items)
            if (auto solid = solid_of(item, 0)) bodies.push_back(std::move(*solid));
        }
      }
    if (curved)
      return skip(
          "its axis is curved (an arc); ccbuild prints straight walls: model it as "
          "straight pieces to print it");
    for (const Solid& body : bodies)
      if (body.curved) return skip("its body's footprint is curved; ccbuild prints straight walls");
    // The body in the wall's frame: its footprint corners, its extent in z. A solid is
    // extruded upwards from a horizontal profile, or through the wall from a profile in the
    // wall's elevation (a wall with a gable or a notch, as Revit exports it): both stand
    // upright; the second only when extruded across the axis (checked below).
    std::vector<Vector2d> footprint;
    std::vector<std::size_t> owner;  // the solid each footprint corner is of
    // The horizontal direction of each solid extruded sideways.
    std::vector<std::optional<Vector2d>> across(bodies.size());
    if (!bodies.empty()) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Solid& body = bodies[i];
        const Vector3d along = body.position.linear() * body.extrusion;
        const Vector3d normal = body.position.linear().col(2);
        const bool upwards = std::abs(along.normalized().z()) >= 1.0 - 1e-6;
        const bool sideways = std::abs(along.normalized().z()) <= 1e-6;
        if (!upwards && !sideways)
          return skip(
              "its body is extruded at a slant: a sloped wall ccbuild cannot "
              "print");
        if (upwards && std::abs(normal.z()) < 1.0 - 1e-6)
          return skip(
              "its body's profile is not horizontal: ccbuild reads walls extruded "
              "upwards or through their thickness");
        if (sideways && std::abs(normal.z()) > 1e-6)
          return skip(
              "its body's profile is not upright: ccbuild reads walls extruded "
              "upwards or through their thickness");
        if (sideways) across[i] = along.head<2>().normalized();
        for (const Vector2d& p : body.profile) {
          const Vector3d base = body.position * Vector3d(p.x(), p.y(), 0.0);
          footprint.push_back(base.head<2>());
          owner.push_back(i);
          if (sideways) {
            footprint.push_back((base + along).head<2>());
            owner.push_back(i);
          }
          lo = std::min({lo, base.z(), base.z() + along.z()});
          hi = std::max({hi, base.z(), base.z() + along.z()});
        }
      }
      const double z0 = (place * Vector3d(0, 0, 0)).z() + z_shift_m;
      found.bottom_m = z0 + lo;
      found.top_m = z0 + hi;
      found.clipped =
          std::any_of(bodies.begin(), bodies.end(), [](const Solid& b) { return b.cut_unread; });
      found.bounded_cut = std::any_of(bodies.begin(), bodies.end(), [](const Solid& b) {
        return std::any_of(b.cuts.begin(), b.cuts.end(), [](const auto& c) { return c.bounded; });
      });
      // Its volume by height, to share its NetVolume between floors where the body is not
      // of one section all the way up (a leaf stopping under a ring beam).
      if (std::none_of(bodies.begin(), bodies.end(), [](const Solid& b) { return b.clipped; }))
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          const Solid& body = bodies[i];
          const Vector3d along = body.position.linear() * body.extrusion;
          const double base_z = z0 + body.position.translation().z();
          FoundWall::UprightPiece piece;
          if (!across[i]) {
            const double area_m2 = floors::polygon_area(body.profile);
            const double za = std::min(base_z, base_z + along.z());
            const double zb = std::max(base_z, base_z + along.z());
            piece.hz = {{0.0, za}, {area_m2, za}, {area_m2, zb}, {0.0, zb}};
            piece.depth_m = 1.0;
          } else {
            // The profile stands upright: its frame's rows give z (and, across that, the
            // horizontal) of each profile point, a rotation, so areas are kept.
            const Vector2d up = body.position.linear().row(2).head<2>().transpose();
            if (!(up.norm() > 0.5)) continue;
            const Vector2d u = up.normalized();
            for (const Vector2d& p : body.profile)
              piece.hz.emplace_back(u.x() * p.y() - u.y() * p.x(), base_z + up.dot(p));
            piece.depth_m = std::abs(along.dot(body.position.linear().col(2)));
          }
          found.body_volume.push_back(std::move(piece));
        }
    }
    const auto layers = layer_set(*wall);
    // The centreline in the wall's frame.
    std::vector<std::pair<Vector2d, Vector2d>> local;
    if (axis.size() >= 2) {
      // Straight runs of the polyline.
      std::vector<Vector2d> corners{axis.front()};
      for (std::size_t k = 1; k + 1 < axis.size(); ++k) {
        const Vector2d a = corners.back(), b = axis[k], c = axis[k + 1];
        const Vector2d d = (c - a).normalized();
        if (std::abs(d.x() * (b - a).y() - d.y() * (b - a).x()) > options_.straightness_tolerance_m)
          corners.push_back(b);
      }
      corners.push_back(axis.back());
      if (corners.size() - 1 > ifc_limits::kMaxPiecesPerWall)
        throw InputError(file_, 0, found.what.describe(),
                         printf_string("its axis turns into %zu straight pieces; ccbuild reads "
                                       "walls of at most %zu",
                                       corners.size() - 1, ifc_limits::kMaxPiecesPerWall));
      bool said = false;
      for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
        const Vector2d a = corners[k], b = corners[k + 1];
        if ((b - a).norm() < 1e-9) continue;
        const Vector2d d = (b - a).normalized(), left(-d.y(), d.x());
        // A solid extruded sideways along the wall (a sweep, a cornice) is not a part of
        // its thickness.
        std::vector<bool> along_it(bodies.size(), false);
        for (std::size_t i = 0; i < bodies.size(); ++i)
          along_it[i] = across[i] && std::abs(across[i]->dot(d)) > 1e-6;
        const auto kept =
            static_cast<std::size_t>(std::count(along_it.begin(), along_it.end(), false));
        if (kept < bodies.size() && !std::exchange(said, true))
          out.notes.add(
              "solids extruded sideways along walls not printed",
              printf_string(
                  "%s: %zu of its body's %zu solids extruded sideways along it (a sweep or a "
                  "cornice?) are not printed",
                  who.c_str(), bodies.size() - kept, bodies.size()));
        double thickness = 0.0, offset = 0.0;
        if (layers) {
          std::tie(thickness, offset) = *layers;
        } else if (kept > 0) {
          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (std::size_t j = 0; j < footprint.size(); ++j) {
            if (along_it[owner[j]]) continue;
            lo = std::min(lo, left.dot(footprint[j] - a));
            hi = std::max(hi, left.dot(footprint[j] - a));
          }
          thickness = hi - lo;
          offset = 0.5 * (lo + hi);
        } else {
          return skip("neither a material layer set nor a body gives its thickness");
        }
        found.thickness_m = thickness;
        local.emplace_back(a + offset * left, b + offset * left);
      }
    } else if (!footprint.empty()) {
      if (bodies.size() != 1 || across[0])
        return skip(
            "it has no axis, and its body is not one solid extruded upwards (ccbuild "
            "finds the axis of such a body only)");
      // The footprint's longest edge gives the direction; its faces are the two lines
      // every corner lies on.
      std::size_t longest = 0;
      for (std::size_t k = 0; k < footprint.size(); ++k)
        if ((footprint[(k + 1) % footprint.size()] - footprint[k]).norm() >
            (footprint[(longest + 1) % footprint.size()] - footprint[longest]).norm())
          longest = k;
      const Vector2d o = footprint[longest];
      const Vector2d d = (footprint[(longest + 1) % footprint.size()] - o).normalized();
      const Vector2d left(-d.y(), d.x());
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vector2d& p : footprint) {
        lo = std::min(lo, left.dot(p - o));
        hi = std::max(hi, left.dot(p - o));
      }
      const double tol = std::max(options_.straightness_tolerance_m, 0.01 * (hi - lo));
      double a_min[2] = {std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::infinity()};
      double a_max[2] = {-a_min[0], -a_min[0]};
      for (const Vector2d& p : footprint) {
        const double y = left.dot(p - o), x = d.dot(p - o);
        const int face = std::abs(y - lo) <= tol ? 0 : std::abs(y - hi) <= tol ? 1 : -1;
        if (face < 0)
          return skip(printf_string("its body's footprint (%zu corners, no axis) is not one "
                                    "straight wall",
                                    footprint.size()),
                      "its body's footprint is not one straight wall");
        a_min[face] = std::min(a_min[face], x);
        a_max[face] = std::max(a_max[face], x);
      }
      if (!std::isfinite(a_min[0]) || !std::isfinite(a_min[1]))
        return skip("its body's footprint has no width");
      const double mid = 0.5 * (lo + hi);
      const double x0 = 0.5 * (a_min[0] + a_min[1]), x1 = 0.5 * (a_max[0] + a_max[1]);
      found.thickness_m = layers ? std::get<0>(*layers) : hi - lo;
      local.emplace_back(o + x0 * d + mid * left, o + x1 * d + mid * left);
    } else {
      return skip("no usable geometry: neither an axis nor an extruded body ccbuild reads");
    }
    if (!floors::limits::kWallThickness_m.contains(found.thickness_m))
      return skip(
          printf_string("its thickness %.4f m is not one ccbuild takes (%s)", found.thickness_m,
                        floors::limits::kWallThickness_m.describe("m").c_str()),
          "a thickness ccbuild does not take");
    const double z0 = (place * Vector3d(0, 0, 0)).z() + z_shift_m;
    for (const auto& [a, b] : local) found.piece_tops.push_back(top_outline(bodies, a, b, z0));
    for (const auto& [a, b] : local) {
      const Vector3d wa = place * Vector3d(a.x(), a.y(), 0.0),
                     wb = place * Vector3d(b.x(), b.y(), 0.0);
      for (const Vector3d& p : {wa, wb})
        if (!p.allFinite() || !floors::limits::kCoordinate_m.contains(p.x()) ||
            !floors::limits::kCoordinate_m.contains(p.y()))
          throw InputError(
              file_, 0, found.what.describe(),
              printf_string("a point (%g, %g) m that is not a coordinate ccbuild "
                            "takes (%s)",
                            p.x(), p.y(), floors::limits::kCoordinate_m.describe("m").c_str()));
      found.pieces.emplace_back(wa.head<2>(), wb.head<2>());
    }
    read_openings(*wall, place, z_shift_m, found, out);
  } catch (const Unusable& u) {
    return skip(u.why);
  }
  storey.walls.push_back(std::move(found));
}

void Reader::read_slab(const std::shared_ptr<IfcSlab>& slab, bool in_roof, double z_shift_m,
                       const std::string& storey, ModelContents& out) {
  FoundSlab found;
  found.what = element_of(*slab);
  found.storey = storey;
  const auto type =
      slab->m_PredefinedType ? slab->m_PredefinedType->m_enum : IfcSlabTypeEnum::ENUM_NOTDEFINED;
  switch (type) {
    case IfcSlabTypeEnum::ENUM_FLOOR:
      found.kind = "FLOOR";
      break;
    case IfcSlabTypeEnum::ENUM_BASESLAB:
      found.kind = "BASESLAB";
      break;
    case IfcSlabTypeEnum::ENUM_ROOF:
      found.kind = "ROOF";
      break;
    default:
      break;
  }
  if (in_roof && found.kind.empty()) found.kind = "ROOF";
  found.roof = in_roof || found.kind == "ROOF";
  const auto skip = [&](const std::string& why) {
    out.notes.add("slabs not used: " + why,
                  found.what.describe() + ": " + why + "; not used for the floors' heights");
  };
  if (found.kind.empty())
    return skip("a slab neither FLOOR, BASESLAB nor ROOF (a landing, say) and not part of a roof");
  try {
    const Isometry3d place = world(slab->m_ObjectPlacement, found.what);
    const double z0 = place.translation().z() + z_shift_m;
    // The body: every extruded solid of it, its extent in z (a sloped roof's lowest point).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, depth = 0.0;
    if (slab->m_Representation)
      for (const auto& rep : slab->m_Representation->m_Representations) {
        if (!rep || lower(label(rep->m_RepresentationIdentifier)) != "body") continue;
        for (const auto& item : rep->m_Items) {
          const auto solid = solid_of(item, 0);
          if (!solid) continue;
          const Vector3d along = place.linear() * solid->position.linear() * solid->extrusion;
          depth = std::max(depth, std::abs(along.z()));
          for (const Vector2d& p : solid->profile) {
            const Vector3d base = place * (solid->position * Vector3d(p.x(), p.y(), 0.0));
            lo = std::min({lo, base.z(), base.z() + along.z()});
            hi = std::max({hi, base.z(), base.z() + along.z()});
          }
        }
      }
    // Its layer set (IfcMaterialLayerSetUsage along AXIS3: up from the placement's plane
    // and its offset, or down with a NEGATIVE sense, as Revit exports floors).
    std::optional<double> layers;
    double layers_bottom = z0, layers_top = z0;
    for (const auto& weak : slab->m_HasAssociations_inverse) {
      auto rel = as<IfcRelAssociatesMaterial>(weak.lock());
      auto usage = rel ? as<IfcMaterialLayerSetUsage>(rel->m_RelatingMaterial) : nullptr;
      if (!usage || !usage->m_ForLayerSet) continue;
      double total = 0.0;
      for (const auto& layer : usage->m_ForLayerSet->m_MaterialLayers)
        if (layer && layer->m_LayerThickness) total += layer->m_LayerThickness->m_value * unit_;
      if (!(total > 0.0) || !std::isfinite(total)) continue;
      layers = total;
      const double ref =
          z0 + (usage->m_OffsetFromReferenceLine ? usage->m_OffsetFromReferenceLine->m_value * unit_
                                                 : 0.0);
      const bool down = usage->m_DirectionSense &&
                        usage->m_DirectionSense->m_enum == IfcDirectionSenseEnum::ENUM_NEGATIVE;
      layers_bottom = down ? ref - total : ref;
      layers_top = down ? ref : ref + total;
      break;
    }
    if (std::isfinite(lo) && hi > lo) {
      found.bottom_m = lo;
      found.top_m = hi;
      found.thickness_m = layers ? *layers : depth;
    } else if (layers) {
      found.bottom_m = layers_bottom;
      found.top_m = layers_top;
      found.thickness_m = *layers;
    } else {
      return skip("neither an extruded body nor a material layer set gives its level");
    }
    if (!std::isfinite(found.bottom_m) || !std::isfinite(found.top_m))
      return skip("its level is not a finite number");
  } catch (const Unusable& u) {
    return skip(u.why);
  }
  out.slabs.push_back(std::move(found));
}

}  // namespace ccbuild::import::ifc::detail
