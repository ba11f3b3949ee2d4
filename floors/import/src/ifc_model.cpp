// The IFC model read through IFC++: units, true north and map conversion, storeys and the
// walls contained in them, their materials and layer sets (the walls' and openings'
// geometry: ifc_geometry.cpp).

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
#include <ifcpp/IFC4/include/IfcElementQuantity.h>
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
#include <ifcpp/IFC4/include/IfcObjectPlacement.h>
#include <ifcpp/IFC4/include/IfcOpeningElement.h>
#include <ifcpp/IFC4/include/IfcOpeningElementTypeEnum.h>
#include <ifcpp/IFC4/include/IfcPolyline.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProductDefinitionShape.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcQuantityVolume.h>
#include <ifcpp/IFC4/include/IfcRatioMeasure.h>
#include <ifcpp/IFC4/include/IfcReal.h>
#include <ifcpp/IFC4/include/IfcRectangleProfileDef.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelAssociatesMaterial.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelDefinesByProperties.h>
#include <ifcpp/IFC4/include/IfcRelDefinesByType.h>
#include <ifcpp/IFC4/include/IfcRelFillsElement.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcRepresentation.h>
#include <ifcpp/IFC4/include/IfcRepresentationContext.h>
#include <ifcpp/IFC4/include/IfcRoof.h>
#include <ifcpp/IFC4/include/IfcSIPrefix.h>
#include <ifcpp/IFC4/include/IfcSIUnit.h>
#include <ifcpp/IFC4/include/IfcSIUnitName.h>
#include <ifcpp/IFC4/include/IfcSite.h>
#include <ifcpp/IFC4/include/IfcSlab.h>
#include <ifcpp/IFC4/include/IfcTrimmedCurve.h>
#include <ifcpp/IFC4/include/IfcTypeObject.h>
#include <ifcpp/IFC4/include/IfcUnitAssignment.h>
#include <ifcpp/IFC4/include/IfcUnitEnum.h>
#include <ifcpp/IFC4/include/IfcVolumeMeasure.h>
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
#include "ifc_reader.hpp"

namespace ccbuild::import::ifc {
namespace detail {

namespace {

void append_utf8(std::string& out, std::uint32_t c) {
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

/// The length of the UTF-8 sequence at `at` (shortest forms, no surrogates), 0 if none.
std::size_t utf8_sequence(const std::string& s, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(at);
  const std::size_t n = b < 0x80           ? 1
                        : (b >> 5) == 0x6  ? 2
                        : (b >> 4) == 0xE  ? 3
                        : (b >> 3) == 0x1E ? 4
                                           : 0;
  if (n == 0 || at + n > s.size()) return 0;
  std::uint32_t c = n == 1 ? b : n == 2 ? (b & 0x1F) : n == 3 ? (b & 0x0F) : (b & 0x07);
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(at + k) & 0xC0) != 0x80) return 0;
    c = (c << 6) | (byte(at + k) & 0x3F);
  }
  static const std::uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (c < kMin[n] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

std::string utf8(const std::wstring& w) {
  std::string out;
  for (std::size_t k = 0; k < w.size();) {
    auto c = static_cast<std::uint32_t>(w[k]);
    // Bytes of 0x80 and more written as they are (not as STEP's \X2\ escapes) reach here as
    // negative characters: UTF-8 where they are, else each a Latin-1 character.
    if (c >= 0xFFFFFF80u) {
      std::string raw;
      for (; k < w.size() && static_cast<std::uint32_t>(w[k]) >= 0xFFFFFF80u; ++k)
        raw += static_cast<char>(static_cast<std::uint32_t>(w[k]) & 0xFF);
      for (std::size_t r = 0; r < raw.size();) {
        const std::size_t n = utf8_sequence(raw, r);
        if (n > 0) {
          out.append(raw, r, n);
          r += n;
        } else {
          append_utf8(out, static_cast<unsigned char>(raw[r]));
          ++r;
        }
      }
      continue;
    }
    ++k;
    // IFC++ decodes \X2\ text 16 bits at a time: a surrogate pair is one character, and a
    // lone surrogate (or a number past Unicode) is none: U+FFFD, so that names stay UTF-8.
    if (c >= 0xD800 && c <= 0xDBFF && k < w.size() && static_cast<std::uint32_t>(w[k]) >= 0xDC00 &&
        static_cast<std::uint32_t>(w[k]) <= 0xDFFF) {
      c = 0x10000 + ((c - 0xD800) << 10) + (static_cast<std::uint32_t>(w[k]) - 0xDC00);
      ++k;
    } else if ((c >= 0xD800 && c <= 0xDFFF) || c > 0x10FFFF) {
      c = 0xFFFD;
    }
    append_utf8(out, c);
  }
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string step_string(const std::wstring& w) {
  // IFC++ keeps STEP's doubled quote ('') inside strings as two quotes: one is meant.
  std::string text = utf8(w);
  for (std::size_t at = text.find("''"); at != std::string::npos; at = text.find("''", at + 1))
    text.erase(at, 1);
  return text;
}

std::string label(const std::shared_ptr<IfcLabel>& l) {
  return l ? step_string(l->m_value) : std::string();
}

Element element_of(const IfcRoot& e) {
  return {e.className(),
          e.m_GlobalId ? step_string(e.m_GlobalId->m_value) : std::string("(no GlobalId)"),
          label(e.m_Name)};
}

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

namespace {

/// An SI prefix as a factor (IfcSIPrefix's order: EXA to ATTO); 1 without one.
double prefix_factor(const std::shared_ptr<IfcSIPrefix>& prefix) {
  static const double kPrefix[] = {1e18, 1e15, 1e12, 1e9,  1e6,  1e3,   1e2,   1e1,
                                   1e-1, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 1e-18};
  return prefix ? kPrefix[static_cast<int>(prefix->m_enum)] : 1.0;
}

}  // namespace

void Reader::read_units(const std::shared_ptr<IfcProject>& project, ModelContents& out) {
  unit_ = 1.0;
  bool found = false;
  std::optional<double> volume;
  // A unit of the kind `power` (1: length, 3: volume) in SI units (its prefix applies to
  // the metre, so a cubic millimetre is 1e-9 m³); a conversion-based one by its factor.
  const auto unit_of = [&](const std::shared_ptr<IfcUnit>& u, IfcUnitEnum::IfcUnitEnumEnum kind,
                           int power, const char* what) -> std::optional<double> {
    if (auto si = as<IfcSIUnit>(u)) {
      if (!si->m_UnitType || si->m_UnitType->m_enum != kind) return std::nullopt;
      return std::pow(prefix_factor(si->m_Prefix), power);
    }
    auto cb = as<IfcConversionBasedUnit>(u);
    if (!cb || !cb->m_UnitType || cb->m_UnitType->m_enum != kind) return std::nullopt;
    double value = 0.0, base = 1.0;
    if (cb->m_ConversionFactor) {
      const auto& v = cb->m_ConversionFactor->m_ValueComponent;
      if (auto l = as<IfcLengthMeasure>(v)) value = l->m_value;
      if (auto r = as<IfcRatioMeasure>(v)) value = r->m_value;
      if (auto r = as<IfcReal>(v)) value = r->m_value;
      if (auto r = as<IfcVolumeMeasure>(v)) value = r->m_value;
      if (auto si = as<IfcSIUnit>(cb->m_ConversionFactor->m_UnitComponent))
        base = std::pow(prefix_factor(si->m_Prefix), power);
    }
    if (!(value > 0.0) || !std::isfinite(value))
      throw InputError(file_, 0, "IfcConversionBasedUnit #" + std::to_string(cb->m_entity_id),
                       std::string("the ") + what + " unit '" + label(cb->m_Name) +
                           "' has no usable conversion factor to SI units");
    return value * base;
  };
  if (project && project->m_UnitsInContext)
    for (const auto& u : project->m_UnitsInContext->m_Units) {
      if (auto length = unit_of(u, IfcUnitEnum::ENUM_LENGTHUNIT, 1, "length")) {
        unit_ = *length;
        found = true;
      }
      if (auto v = unit_of(u, IfcUnitEnum::ENUM_VOLUMEUNIT, 3, "volume")) volume = *v;
    }
  if (!found)
    out.notes.add("the project's length unit",
                  "the project names no length unit (IfcUnitAssignment); lengths are "
                  "taken as metres");
  out.metres_per_unit = unit_;
  // Without a volume unit of its own the model's volumes are in its length unit cubed.
  volume_unit_ = volume ? *volume : unit_ * unit_ * unit_;
}

std::optional<double> Reader::net_volume_m3(const IfcObject& object, const Element& who,
                                            ModelContents& out) const {
  for (const auto& weak : object.m_IsDefinedBy_inverse) {
    auto rel = weak.lock();
    if (!rel) continue;
    auto set = as<IfcElementQuantity>(rel->m_RelatingPropertyDefinition);
    if (!set) continue;
    for (const auto& q : set->m_Quantities) {
      auto volume = as<IfcQuantityVolume>(q);
      if (!volume || label(volume->m_Name) != "NetVolume") continue;
      const double value = volume->m_VolumeValue ? volume->m_VolumeValue->m_value : 0.0;
      const double m3 = value * volume_unit_;
      if (!std::isfinite(m3) || !floors::limits::kWallVolume_m3.contains(m3)) {
        out.notes.add(
            "model quantities not used",
            who.describe() + printf_string(": its NetVolume (%s) is %g m³, not a wall's "
                                           "volume (%s); not compared",
                                           label(set->m_Name).c_str(), m3,
                                           floors::limits::kWallVolume_m3.describe("m³").c_str()));
        return std::nullopt;
      }
      return m3;
    }
  }
  return std::nullopt;
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
      out.notes.add(
          "true norths ignored",
          printf_string(
              "the model's true north (IfcGeometricRepresentationContext #%d) is turned %.2f "
              "degrees from its y axis; ignored: the plan keeps the model's axes",
              id, angle_deg));
    } else if (auto map = as<IfcMapConversion>(entity)) {
      const auto v = [](const std::shared_ptr<IfcLengthMeasure>& m) {
        return m ? m->m_value : 0.0;
      };
      out.notes.add(
          "map conversions ignored",
          printf_string(
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
    out.notes.add("buildings read together",
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
      out.notes.left_out("storeys whose placement cannot be read, their elements left out",
                         s.what.describe() + ": " + u.why + "; its elements left out");
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
            out.notes.left_out(
                "walls of a type not read left out", e.describe() + ": an " + type +
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
            out.notes.left_out(
                "walls of a material not printable left out",
                e.describe() + ": its material '" + excluded_by + " is not printable; left out");
            ++out.left_out;
            continue;
          }
          read_wall(wall, Element{}, z_shift_m, s, out, 0);
        } else if (auto slab = as<IfcSlab>(product)) {
          read_slab(slab, false, z_shift_m, s.what.name, out);
        } else if (auto roof = as<IfcRoof>(product)) {
          // A roof is made of slabs (IfcRelAggregates), or is one itself in IFC2X3's way.
          bool parts = false;
          for (const auto& weak : roof->m_IsDecomposedBy_inverse)
            if (auto agg = weak.lock())
              for (const auto& part : agg->m_RelatedObjects)
                if (auto roof_slab = as<IfcSlab>(part)) {
                  parts = true;
                  read_slab(roof_slab, true, z_shift_m, s.what.name, out);
                }
          if (!parts)
            out.notes.add("roofs made of no slab",
                          element_of(*roof).describe() +
                              ": a roof made of no slab (IfcRelAggregates); not used for "
                              "the floors' heights");
        } else if (as<IfcCurtainWall>(product)) {
          out.notes.left_out(
              "curtain walls left out",
              element_of(*product).describe() + ": a curtain wall, not printable; left out");
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

}  // namespace detail

namespace {

void on_message(void* sink, shared_ptr<StatusCallback::Message> m) {
  if (!m) return;
  if (m->m_message_type == StatusCallback::MESSAGE_TYPE_ERROR ||
      m->m_message_type == StatusCallback::MESSAGE_TYPE_WARNING) {
    std::string text = detail::utf8(m->m_message_text);
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
    detail::Reader r(file, options);
    out = r.read(model);
  } catch (const detail::Broken& b) {
    throw InputError(file, 0, "", b.why);
  }
  // What IFC++ said while reading (a reference to an entity the file does not have, say):
  // the elements it concerns are read as far as they can be, and it is said.
  std::size_t said = 0;
  for (const auto& [error, message] : messages)
    if (++said <= 10)
      out.notes.add("IFC++'s messages",
                    std::string(error ? "IFC++ error: " : "IFC++ warning: ") + message);
  if (said > 10)
    out.notes.add("IFC++'s messages", printf_string("IFC++: and %zu more messages", said - 10));
  // IFC++ models hold references in both directions; let them go. Each entity unlinks
  // itself from the inverse lists of what it refers to, one linear search per entity: the
  // lists every representation and placement joins (their context's, the storey's
  // placement's) are emptied first, or that is quadratic (2.0 of 4.8 s importing the
  // 40 x 40 rooms benchmark, bench/README.md).
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    if (const auto context = std::dynamic_pointer_cast<IfcRepresentationContext>(entity))
      context->m_RepresentationsInContext_inverse.clear();
    if (const auto placement = std::dynamic_pointer_cast<IfcObjectPlacement>(entity)) {
      placement->m_PlacesObject_inverse.clear();
      placement->m_ReferencedByPlacements_inverse.clear();
    }
  }
  model->unsetInverseAttributes();
  model->clearIfcModel();
  return out;
}

}  // namespace ccbuild::import::ifc
