#pragma once
// The IFC importer's reader of IFC++ models (ifc_model.cpp: units, storeys, materials;
// ifc_geometry.cpp: axes, bodies, walls and openings). Internal: only these two files see
// IFC++.

#include <ifcpp/IFC4/include/IfcAxis2Placement.h>
#include <ifcpp/IFC4/include/IfcCartesianPoint.h>
#include <ifcpp/IFC4/include/IfcCurve.h>
#include <ifcpp/IFC4/include/IfcDirection.h>
#include <ifcpp/IFC4/include/IfcElement.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcObjectDefinition.h>
#include <ifcpp/IFC4/include/IfcObjectPlacement.h>
#include <ifcpp/IFC4/include/IfcPolygonalBoundedHalfSpace.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcReal.h>
#include <ifcpp/IFC4/include/IfcRepresentationItem.h>
#include <ifcpp/IFC4/include/IfcRoot.h>
#include <ifcpp/IFC4/include/IfcSlab.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/model/BuildingModel.h>

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "ifc_internal.hpp"

namespace ccbuild::import::ifc::detail {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

template <class T, class U>
std::shared_ptr<T> as(const std::shared_ptr<U>& p) {
  return std::dynamic_pointer_cast<T>(p);
}

std::string utf8(const std::wstring& w);
/// A STEP string's text as IFC++ read it, in UTF-8, its doubled quotes made one.
std::string step_string(const std::wstring& w);
std::string lower(std::string s);
std::string label(const std::shared_ptr<IfcLabel>& l);
Element element_of(const IfcRoot& e);

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
  /// The element's NetVolume in its quantity sets (IfcRelDefinesByProperties to an
  /// IfcElementQuantity: Qto_WallBaseQuantities in IFC4, BaseQuantities as IFC2X3 tools
  /// write it), m³; nullopt when it states none, or none that is a finite positive volume
  /// (said in a note).
  std::optional<double> net_volume_m3(const IfcObject& object, const Element& who,
                                      ModelContents& out) const;
  std::optional<std::tuple<double, double>> layer_set(const IfcObjectDefinition& object) const;
  void read_wall(const std::shared_ptr<IfcWall>& wall, const Element& parent, double z_shift_m,
                 FoundStorey& storey, ModelContents& out, int depth);
  void read_slab(const std::shared_ptr<IfcSlab>& slab, bool in_roof, double z_shift_m,
                 const std::string& storey, ModelContents& out);
  void read_openings(const IfcElement& wall, const Isometry3d& wall_world, double z_shift_m,
                     FoundWall& into, ModelContents& out);

  struct Solid {
    std::vector<Vector2d> profile;  ///< closed polygon in the solid's Position frame
    bool curved = false;            ///< the profile approximated from a curve
    Isometry3d position = Isometry3d::Identity();
    Vector3d extrusion = Vector3d::UnitZ();  ///< in the Position frame, as long as the depth
    bool clipped = false;
    /// Half-spaces taken away from it (IfcBooleanClippingResult: a roof's planes over a
    /// gable), in the wall's frame: `point` on the plane, `removed` the unit normal towards
    /// the side taken away. A polygonal bounded half-space takes away only inside its
    /// prism, held as convex prisms that do not overlap (`prisms`, each its side faces: a
    /// point on each and its outward unit normal); `bounded` says its boundary could not be
    /// read (curved, say), so the whole half-space is taken away.
    struct Face {
      Vector3d point, outward;
    };
    using Prism = std::vector<Face>;
    struct Cut {
      Vector3d point, removed;
      std::vector<Prism> prisms;
      bool bounded = false;
    };
    std::vector<Cut> cuts;
    bool cut_unread = false;  ///< cut by something else: a solid, a curved surface
  };
  std::optional<Solid> solid_of(const std::shared_ptr<IfcRepresentationItem>& item,
                                int depth) const;
  /// A polygonal bounded half-space's prism (its boundary, a polygon in its Position's xy
  /// plane, swept along that Position's z) as convex prisms (the boundary cut into
  /// triangles where it is not convex), in the frame the half-space is placed in; empty
  /// when the boundary is curved, crosses itself or cannot be read.
  std::vector<Solid::Prism> prisms_of(const IfcPolygonalBoundedHalfSpace& half) const;
  /// The upper outline of a wall's solids along its piece from `a` to `b` (the wall's
  /// frame), as FoundWall::piece_tops holds it; `z0_m` the wall's frame's z in the model's.
  static std::vector<std::pair<double, double>> top_outline(const std::vector<Solid>& bodies,
                                                            const Vector2d& a, const Vector2d& b,
                                                            double z0_m);
  std::vector<Vector2d> curve_points(const std::shared_ptr<IfcCurve>& curve, bool& curved,
                                     int depth) const;

  std::string file_;
  const IfcOptions& options_;
  double unit_ = 1.0;
  double volume_unit_ = 1.0;  ///< m³ per volume unit of the model
};

}  // namespace ccbuild::import::ifc::detail
