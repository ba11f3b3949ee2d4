// The IFC model read through IFC++: units, storeys, the walls contained in them with their
// axes, thicknesses and heights, and the openings voiding them. The only file that sees
// IFC++.

#include <ifcpp/IFC4/include/IfcArbitraryClosedProfileDef.h>
#include <ifcpp/IFC4/include/IfcArcIndex.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement2D.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement3D.h>
#include <ifcpp/IFC4/include/IfcBoolean.h>
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
#include <ifcpp/IFC4/include/IfcTrimmedCurve.h>
#include <ifcpp/IFC4/include/IfcTypeObject.h>
#include <ifcpp/IFC4/include/IfcUnitAssignment.h>
#include <ifcpp/IFC4/include/IfcUnitEnum.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/model/BuildingException.h>
#include <ifcpp/model/BuildingModel.h>
#include <ifcpp/reader/ReaderSTEP.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <set>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ifc_internal.hpp"

namespace ccbuild::import::ifc {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;
template <class T, class U>
std::shared_ptr<T> as(const std::shared_ptr<U>& p) {
  return std::dynamic_pointer_cast<T>(p);
}

std::string utf8(const std::wstring& w) {
  std::string out;
  for (wchar_t wc : w) {
    const auto c = static_cast<std::uint32_t>(wc);
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string label(const std::shared_ptr<IfcLabel>& l) {
  return l ? utf8(l->m_value) : std::string();
}

Element element_of(const IfcRoot& e) {
  return {e.className(), e.m_GlobalId ? utf8(e.m_GlobalId->m_value) : std::string("(no GlobalId)"),
          label(e.m_Name)};
}

/// An element that cannot be read for a reason the model is to blame for (thrown inside,
/// caught per element: the element is left out and said).
struct Unusable {
  std::string why;
};

/// The model is broken (a placement cycle): an input error for the whole file.
struct Broken {
  std::string why;
};

class Reader {
 public:
  Reader(const std::string& file, const IfcOptions& options) : file_(file), options_(options) {}

  ModelContents read(const std::shared_ptr<BuildingModel>& model);

 private:
  double length(const std::shared_ptr<IfcLengthMeasure>& m) const {
    if (!m) throw Unusable{"a length is missing"};
    return m->m_value * unit_;
  }
  Vector3d point(const std::shared_ptr<IfcCartesianPoint>& p) const {
    if (!p) throw Unusable{"a point is missing"};
    Vector3d out = Vector3d::Zero();
    for (std::size_t k = 0; k < p->m_Coordinates.size() && k < 3; ++k)
      out[static_cast<int>(k)] = length(p->m_Coordinates[k]);
    return out;
  }
  static Vector3d direction(const std::shared_ptr<IfcDirection>& d, const Vector3d& fallback) {
    if (!d) return fallback;
    Vector3d out = Vector3d::Zero();
    for (std::size_t k = 0; k < d->m_DirectionRatios.size() && k < 3; ++k)
      if (d->m_DirectionRatios[k]) out[static_cast<int>(k)] = d->m_DirectionRatios[k]->m_value;
    if (out.norm() < 1e-12) throw Unusable{"a direction of length zero"};
    return out.normalized();
  }
  Isometry3d axis_placement(const std::shared_ptr<IfcAxis2Placement>& p) const;
  Isometry3d world(const std::shared_ptr<IfcObjectPlacement>& placement, const Element& who) const;
  void read_units(const std::shared_ptr<IfcProject>& project, ModelContents& out);
  void report_georeferencing(const std::shared_ptr<BuildingModel>& model, ModelContents& out);
  std::vector<std::string> material_names(const IfcObjectDefinition& object) const;
  std::optional<std::tuple<double, double>> layer_set(const IfcObjectDefinition& object) const;
  void read_wall(const std::shared_ptr<IfcWall>& wall, const Element& parent, double z_shift_m,
                 FoundStorey& storey, ModelContents& out, int depth);
  void read_openings(const IfcElement& wall, const Isometry3d& wall_world, double z_shift_m,
                     FoundWall& into, ModelContents& out);

  struct Solid {
    std::vector<Vector2d> profile;  ///< closed polygon in the solid's Position frame
    bool curved = false;            ///< the profile approximated from a curve
    Isometry3d position = Isometry3d::Identity();
    Vector3d extrusion = Vector3d::UnitZ();  ///< in the Position frame, as long as the depth
    bool clipped = false;
  };
  std::optional<Solid> solid_of(const std::shared_ptr<IfcRepresentationItem>& item,
                                int depth) const;
  std::vector<Vector2d> curve_points(const std::shared_ptr<IfcCurve>& curve, bool& curved,
                                     int depth) const;

  std::string file_;
  const IfcOptions& options_;
  double unit_ = 1.0;
};

Isometry3d Reader::axis_placement(const std::shared_ptr<IfcAxis2Placement>& p) const {
  Isometry3d t = Isometry3d::Identity();
  if (auto p3 = as<IfcAxis2Placement3D>(p)) {
    const Vector3d z = direction(p3->m_Axis, Vector3d::UnitZ());
    Vector3d x = direction(p3->m_RefDirection, Vector3d::UnitX());
    x = x - x.dot(z) * z;  // IFC's rule: the reference direction projected off the axis
    if (x.norm() < 1e-9) x = std::abs(z.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
    x = (x - x.dot(z) * z).normalized();
    Matrix3d r;
    r.col(0) = x;
    r.col(1) = z.cross(x);
    r.col(2) = z;
    t.linear() = r;
    t.translation() = point(p3->m_Location);
  } else if (auto p2 = as<IfcAxis2Placement2D>(p)) {
    Vector3d x = direction(p2->m_RefDirection, Vector3d::UnitX());
    x.z() = 0.0;
    if (x.norm() < 1e-9) throw Unusable{"a 2-D placement with a vertical direction"};
    x.normalize();
    Matrix3d r = Matrix3d::Identity();
    r.col(0) = x;
    r.col(1) = Vector3d(-x.y(), x.x(), 0.0);
    t.linear() = r;
    t.translation() = point(p2->m_Location);
  }
  return t;
}

Isometry3d Reader::world(const std::shared_ptr<IfcObjectPlacement>& placement,
                         const Element& who) const {
  Isometry3d t = Isometry3d::Identity();
  std::set<const IfcObjectPlacement*> seen;
  std::shared_ptr<IfcObjectPlacement> at = placement;
  int depth = 0;
  while (at) {
    if (!seen.insert(at.get()).second)
      throw Broken{who.describe() + ": its placement chain loops (IfcLocalPlacement #" +
                   std::to_string(at->m_entity_id) +
                   " is placed relative to itself, or to a placement relative to it)"};
    if (++depth > ifc_limits::kMaxPlacementDepth)
      throw Broken{who.describe() + printf_string(": its placement chain is more than %d "
                                                  "placements deep",
                                                  ifc_limits::kMaxPlacementDepth)};
    auto local = as<IfcLocalPlacement>(at);
    if (!local)
      throw Unusable{std::string("placed by an ") + at->className() +
                     ", which ccbuild does not read (only IfcLocalPlacement)"};
    t = axis_placement(local->m_RelativePlacement) * t;
    at = local->m_PlacementRelTo;
  }
  if (!t.matrix().allFinite()) throw Unusable{"its placement is not finite"};
  return t;
}

void Reader::read_units(const std::shared_ptr<IfcProject>& project, ModelContents& out) {
  unit_ = 1.0;
  bool found = false;
  if (project && project->m_UnitsInContext)
    for (const auto& u : project->m_UnitsInContext->m_Units) {
      if (auto si = as<IfcSIUnit>(u)) {
        if (!si->m_UnitType || si->m_UnitType->m_enum != IfcUnitEnum::ENUM_LENGTHUNIT) continue;
        double factor = 1.0;
        if (si->m_Prefix) {
          static const double kPrefix[] = {1e18, 1e15, 1e12, 1e9,  1e6,  1e3,   1e2,   1e1,
                                           1e-1, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 1e-18};
          factor = kPrefix[static_cast<int>(si->m_Prefix->m_enum)];
        }
        unit_ = factor;
        found = true;
      } else if (auto cb = as<IfcConversionBasedUnit>(u)) {
        if (!cb->m_UnitType || cb->m_UnitType->m_enum != IfcUnitEnum::ENUM_LENGTHUNIT) continue;
        double value = 0.0, base = 1.0;
        if (cb->m_ConversionFactor) {
          const auto& v = cb->m_ConversionFactor->m_ValueComponent;
          if (auto l = as<IfcLengthMeasure>(v)) value = l->m_value;
          if (auto r = as<IfcRatioMeasure>(v)) value = r->m_value;
          if (auto r = as<IfcReal>(v)) value = r->m_value;
          if (auto si = as<IfcSIUnit>(cb->m_ConversionFactor->m_UnitComponent))
            if (si->m_Prefix) {
              static const double kPrefix[] = {1e18, 1e15, 1e12, 1e9,  1e6,  1e3,   1e2,   1e1,
                                               1e-1, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 1e-18};
              base = kPrefix[static_cast<int>(si->m_Prefix->m_enum)];
            }
        }
        if (!(value > 0.0) || !std::isfinite(value))
          throw InputError(file_, 0, "IfcConversionBasedUnit #" + std::to_string(cb->m_entity_id),
                           "the length unit '" + label(cb->m_Name) +
                               "' has no usable conversion factor to metres");
        unit_ = value * base;
        found = true;
      }
    }
  if (!found)
    out.notes.push_back(
        "the project names no length unit (IfcUnitAssignment); lengths are "
        "taken as metres");
  out.metres_per_unit = unit_;
}

void Reader::report_georeferencing(const std::shared_ptr<BuildingModel>& model,
                                   ModelContents& out) {
  std::set<long long> norths;  // each angle said once (a model has several contexts)
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    if (auto context = as<IfcGeometricRepresentationContext>(entity)) {
      if (!context->m_TrueNorth) continue;
      Vector3d north;
      try {
        north = direction(context->m_TrueNorth, Vector3d::UnitY());
      } catch (const Unusable&) {
        continue;
      }
      const double angle_deg = std::atan2(-north.x(), north.y()) * 180.0 / M_PI;
      if (std::abs(angle_deg) < 1e-6 || !norths.insert(std::llround(angle_deg * 1e3)).second)
        continue;
      out.notes.push_back(printf_string(
          "the model's true north (IfcGeometricRepresentationContext #%d) is turned %.2f "
          "degrees from its y axis; ignored: the plan keeps the model's axes",
          id, angle_deg));
    } else if (auto map = as<IfcMapConversion>(entity)) {
      const auto v = [](const std::shared_ptr<IfcLengthMeasure>& m) {
        return m ? m->m_value : 0.0;
      };
      out.notes.push_back(printf_string(
          "the model's map conversion (IfcMapConversion #%d: eastings %g, northings %g, "
          "height %g) is ignored: the plan keeps the model's own coordinates",
          id, v(map->m_Eastings), v(map->m_Northings), v(map->m_OrthogonalHeight)));
    }
  }
}

std::vector<std::string> Reader::material_names(const IfcObjectDefinition& object) const {
  std::vector<std::string> names;
  const auto from = [&](const IfcObjectDefinition& o) {
    for (const auto& weak : o.m_HasAssociations_inverse) {
      auto rel = as<IfcRelAssociatesMaterial>(weak.lock());
      if (!rel) continue;
      const auto& m = rel->m_RelatingMaterial;
      std::shared_ptr<IfcMaterialLayerSet> set;
      if (auto usage = as<IfcMaterialLayerSetUsage>(m)) set = usage->m_ForLayerSet;
      if (auto s = as<IfcMaterialLayerSet>(m)) set = s;
      if (set)
        for (const auto& layer : set->m_MaterialLayers)
          if (layer && layer->m_Material) names.push_back(label(layer->m_Material->m_Name));
      if (auto material = as<IfcMaterial>(m)) names.push_back(label(material->m_Name));
      if (auto list = as<IfcMaterialList>(m))
        for (const auto& material : list->m_Materials)
          if (material) names.push_back(label(material->m_Name));
    }
  };
  from(object);
  if (names.empty())
    if (auto typed = dynamic_cast<const IfcObject*>(&object))
      for (const auto& weak : typed->m_IsTypedBy_inverse)
        if (auto rel = weak.lock(); rel && rel->m_RelatingType) from(*rel->m_RelatingType);
  return names;
}

// The layer set's total thickness and the offset of its middle from the wall's axis,
// along the wall's local y (from IfcMaterialLayerSetUsage), m.
std::optional<std::tuple<double, double>> Reader::layer_set(
    const IfcObjectDefinition& object) const {
  for (const auto& weak : object.m_HasAssociations_inverse) {
    auto rel = as<IfcRelAssociatesMaterial>(weak.lock());
    if (!rel) continue;
    auto usage = as<IfcMaterialLayerSetUsage>(rel->m_RelatingMaterial);
    if (!usage || !usage->m_ForLayerSet) continue;
    if (usage->m_LayerSetDirection &&
        usage->m_LayerSetDirection->m_enum != IfcLayerSetDirectionEnum::ENUM_AXIS2)
      continue;
    double total = 0.0;
    for (const auto& layer : usage->m_ForLayerSet->m_MaterialLayers)
      if (layer && layer->m_LayerThickness) total += layer->m_LayerThickness->m_value * unit_;
    if (!(total > 0.0)) continue;
    const double sense = usage->m_DirectionSense && usage->m_DirectionSense->m_enum ==
                                                        IfcDirectionSenseEnum::ENUM_NEGATIVE
                             ? -1.0
                             : 1.0;
    const double offset =
        usage->m_OffsetFromReferenceLine ? usage->m_OffsetFromReferenceLine->m_value * unit_ : 0.0;
    return std::tuple{total, offset + sense * 0.5 * total};
  }
  return std::nullopt;
}

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
    if (first) first->clipped = true;
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
        out.notes.push_back(found.what.describe() + " in " + into.what.describe() +
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
      out.notes.push_back(found.what.describe() + " in " + into.what.describe() + ": " + u.why +
                          "; left out");
      ++out.left_out;
      continue;
    }
    if (found.corners_m.empty()) {
      out.notes.push_back(found.what.describe() + " in " + into.what.describe() +
                          ": no extruded body to measure it by; left out");
      ++out.left_out;
      continue;
    }
    into.openings.push_back(std::move(found));
  }
}

void Reader::read_wall(const std::shared_ptr<IfcWall>& wall, const Element& parent,
                       double z_shift_m, FoundStorey& storey, ModelContents& out, int depth) {
  FoundWall found;
  found.what = element_of(*wall);
  const std::string who =
      found.what.describe() + (parent.guid.empty() ? "" : " (part of " + parent.describe() + ")");
  const auto skip = [&](const std::string& why) {
    out.notes.push_back(who + ": " + why + "; left out");
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
    std::optional<Solid> body;
    if (wall->m_Representation)
      for (const auto& rep : wall->m_Representation->m_Representations) {
        if (!rep) continue;
        const std::string id = lower(label(rep->m_RepresentationIdentifier));
        for (const auto& item : rep->m_Items) {
          if (id == "axis" && axis.empty() && !curved) {
            if (auto c = as<IfcCurve>(item)) axis = curve_points(c, curved, 0);
          } else if (id != "axis" && !body) {
            body = solid_of(item, 0);
          }
        }
      }
    if (curved)
      return skip(
          "its axis is curved (an arc); ccbuild prints straight walls: model it as "
          "straight pieces to print it");
    if (body && body->curved)
      return skip("its body's footprint is curved; ccbuild prints straight walls");
    // The body in the wall's frame: its footprint corners, its extent in z.
    std::vector<Vector2d> footprint;
    if (body) {
      const Vector3d along = body->position.linear() * body->extrusion;
      if (std::abs(along.normalized().z()) < 1.0 - 1e-6)
        return skip(
            "its body is extruded at a slant or sideways: a sloped wall ccbuild cannot "
            "print");
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vector2d& p : body->profile) {
        const Vector3d base = body->position * Vector3d(p.x(), p.y(), 0.0);
        if (std::abs(body->position.linear().col(2).z()) < 1.0 - 1e-6)
          return skip(
              "its body's profile is not horizontal: ccbuild reads walls extruded "
              "upwards");
        footprint.push_back(base.head<2>());
        lo = std::min({lo, base.z(), base.z() + along.z()});
        hi = std::max({hi, base.z(), base.z() + along.z()});
      }
      const double z0 = (place * Vector3d(0, 0, 0)).z() + z_shift_m;
      found.bottom_m = z0 + lo;
      found.top_m = z0 + hi;
      found.clipped = body->clipped;
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
      for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
        const Vector2d a = corners[k], b = corners[k + 1];
        if ((b - a).norm() < 1e-9) continue;
        const Vector2d d = (b - a).normalized(), left(-d.y(), d.x());
        double thickness = 0.0, offset = 0.0;
        if (layers) {
          std::tie(thickness, offset) = *layers;
        } else if (!footprint.empty()) {
          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (const Vector2d& p : footprint) {
            lo = std::min(lo, left.dot(p - a));
            hi = std::max(hi, left.dot(p - a));
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
          return skip(
              printf_string("its body's footprint (%zu corners, no axis) is not one "
                            "straight wall",
                            footprint.size()));
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
      return skip(printf_string("its thickness %.4f m is not one ccbuild takes (%s)",
                                found.thickness_m,
                                floors::limits::kWallThickness_m.describe("m").c_str()));
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

ModelContents Reader::read(const std::shared_ptr<BuildingModel>& model) {
  ModelContents out;
  std::shared_ptr<IfcProject> project;
  for (const auto& [id, entity] : model->getMapIfcEntities())
    if ((project = as<IfcProject>(entity))) break;
  if (!project) throw InputError(file_, 0, "", "the model has no IfcProject: not a building model");
  read_units(project, out);
  report_georeferencing(model, out);
  // Buildings: their name, and a word when there are several.
  std::vector<std::string> buildings;
  for (const auto& [id, entity] : model->getMapIfcEntities())
    if (auto b = as<::IfcBuilding>(entity)) buildings.push_back(label(b->m_Name));
  if (!buildings.empty()) out.building_name = buildings.front();
  if (buildings.size() > 1)
    out.notes.push_back(
        printf_string("the model holds %zu buildings (IfcBuilding); their "
                      "storeys are read together, by elevation",
                      buildings.size()));
  if (out.building_name.empty()) out.building_name = label(project->m_Name);
  // Storeys and what they contain.
  std::set<std::string> wall_types;
  for (const auto& t : options_.wall_types) wall_types.insert(lower(t));
  int order = 0;
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    auto storey = as<IfcBuildingStorey>(entity);
    if (!storey) continue;
    FoundStorey s;
    s.what = element_of(*storey);
    s.order = order++;
    double placed_z = 0.0;
    try {
      placed_z = storey->m_ObjectPlacement
                     ? world(storey->m_ObjectPlacement, s.what).translation().z()
                     : 0.0;
    } catch (const Unusable& u) {
      out.notes.push_back(s.what.describe() + ": " + u.why + "; its elements left out");
      ++out.left_out;
      continue;
    }
    s.elevation_m = storey->m_Elevation ? storey->m_Elevation->m_value * unit_ : placed_z;
    // Elements are placed relative to the storey's placement; its Elevation attribute is
    // the storey's level: elements' heights are taken relative to both agreeing.
    const double z_shift_m = s.elevation_m - placed_z;
    for (const auto& weak : storey->m_ContainsElements_inverse) {
      auto rel = weak.lock();
      if (!rel) continue;
      for (const auto& product : rel->m_RelatedElements) {
        if (!product) continue;
        const std::string type = product->className();
        if (auto wall = as<IfcWall>(product)) {
          const Element e = element_of(*wall);
          if (!wall_types.count(lower(type))) {
            out.notes.push_back(e.describe() + ": an " + type +
                                " is not among the wall types read (" +
                                [&] {
                                  std::string list;
                                  for (const auto& t : options_.wall_types)
                                    list += (list.empty() ? "" : ", ") + t;
                                  return list;
                                }() +
                                "); left out");
            ++out.left_out;
            continue;
          }
          const auto names = material_names(*wall);
          bool printable = names.empty();
          std::string excluded_by;
          for (const auto& name : names) {
            bool excluded = false;
            for (const auto& pattern : options_.excluded_materials)
              if (!pattern.empty() && lower(name).find(lower(pattern)) != std::string::npos) {
                excluded = true;
                if (excluded_by.empty()) excluded_by = name + "' (matches '" + pattern + "')";
              }
            printable = printable || !excluded;
          }
          if (!printable) {
            out.notes.push_back(e.describe() + ": its material '" + excluded_by +
                                " is not printable; left out");
            ++out.left_out;
            continue;
          }
          read_wall(wall, Element{}, z_shift_m, s, out, 0);
        } else if (as<IfcCurtainWall>(product)) {
          out.notes.push_back(element_of(*product).describe() +
                              ": a curtain wall, not printable; left out");
          ++out.left_out;
        }
      }
    }
    out.storeys.push_back(std::move(s));
  }
  if (out.storeys.empty())
    throw InputError(file_, 0, "", "the model has no building storeys (IfcBuildingStorey)");
  return out;
}

void on_message(void* sink, shared_ptr<StatusCallback::Message> m) {
  if (!m) return;
  if (m->m_message_type == StatusCallback::MESSAGE_TYPE_ERROR ||
      m->m_message_type == StatusCallback::MESSAGE_TYPE_WARNING) {
    std::string text = utf8(m->m_message_text);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    static_cast<std::vector<std::pair<bool, std::string>>*>(sink)->emplace_back(
        m->m_message_type == StatusCallback::MESSAGE_TYPE_ERROR, text);
  }
}

}  // namespace

std::string Element::describe() const {
  return type + " " + guid + (name.empty() ? std::string() : " '" + name + "'");
}

ModelContents read_model(std::string text, const std::string& file, const IfcOptions& options) {
  std::vector<std::pair<bool, std::string>> messages;  // (error?, text)
  auto model = std::make_shared<BuildingModel>();
  ReaderSTEP reader;
  reader.setMessageCallBack(&messages, &on_message);
  model->setMessageCallBack(&messages, &on_message);
  try {
    reader.loadModelFromString(text, model);
  } catch (const OutOfMemoryException&) {
    throw InputError(file, 0, "", "IFC++ ran out of memory reading it: the model is too large");
  } catch (const std::exception& e) {
    throw InputError(file, 0, "", std::string("IFC++ could not read it: ") + e.what());
  }
  ModelContents out;
  try {
    Reader r(file, options);
    out = r.read(model);
  } catch (const Broken& b) {
    throw InputError(file, 0, "", b.why);
  }
  // What IFC++ said while reading (a reference to an entity the file does not have, say):
  // the elements it concerns are read as far as they can be, and it is said.
  std::size_t said = 0;
  for (const auto& [error, message] : messages)
    if (++said <= 10)
      out.notes.push_back(std::string(error ? "IFC++ error: " : "IFC++ warning: ") + message);
  if (said > 10) out.notes.push_back(printf_string("IFC++: and %zu more messages", said - 10));
  // IFC++ models hold references in both directions; let them go.
  model->unsetInverseAttributes();
  model->clearIfcModel();
  return out;
}

}  // namespace ccbuild::import::ifc
