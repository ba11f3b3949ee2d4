#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::climb::detail {
namespace {

Eigen::Isometry3d wall_pose(const WallBox& w) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const Eigen::Vector2d mid = 0.5 * (w.a + w.b), d = w.b - w.a;
  pose.translation() = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (w.z_bottom_m + w.z_top_m));
  pose.linear() =
      Eigen::AngleAxisd(std::atan2(d.y(), d.x()), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

// What the broad-phase callback needs to know about the link it tests.
struct CollisionQuery {
  bool hit = false;
  int box = -1;
  std::function<bool(int box)> ignore;
};

bool on_pair(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto& query = *static_cast<CollisionQuery*>(data);
  if (query.hit) return true;
  fcl::CollisionObjectd* wall = a->getUserData() ? a : b;
  const int box = static_cast<int>(reinterpret_cast<std::intptr_t>(wall->getUserData())) - 1;
  if (query.ignore && query.ignore(box)) return false;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (fcl::collide(a, b, request, result) > 0) {
    query.hit = true;
    query.box = box;
  }
  return query.hit;
}

struct DistanceQuery {
  double best = std::numeric_limits<double>::infinity();
};

bool on_distance(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data, double& best) {
  auto& query = *static_cast<DistanceQuery*>(data);
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(a, b, request, result);
  query.best = std::min(query.best, std::max(0.0, result.min_distance));
  best = query.best;
  return best <= 0.0;
}

}  // namespace

std::vector<WallBox> walls_built(const floors::Building& building, LayerRef last,
                                 double default_thickness_m) {
  std::vector<WallBox> out;
  for (const auto& floor : building.floors) {
    if (floor.index > last.floor) break;
    const auto layers = floors::slice_floor(floor, building.layer_height_m);
    const int count = floor.index < last.floor ? static_cast<int>(layers.size())
                                               : std::min<int>(last.layer + 1, layers.size());
    int k = 0;
    while (k < count) {
      // A run of layers of one geometry makes one box per piece.
      const floors::GeometryKey key(layers[k]);
      int end = k;
      while (end + 1 < count && floors::GeometryKey(layers[end + 1]) == key) ++end;
      const floors::Layer& layer = layers[k];
      for (const auto& s : layer.segments) {
        WallBox box;
        box.a = layer.start_m(s);
        box.b = layer.end_m(s);
        const floors::Wall* wall = floor.plan.find_wall(s.wall_id);
        box.thickness_m = wall && wall->thickness_m ? *wall->thickness_m : default_thickness_m;
        box.z_bottom_m = layers[k].z_bottom_m;
        box.z_top_m = layers[end].z_top_m;
        box.wall_id = s.wall_id;
        box.floor = floor.index;
        out.push_back(box);
      }
      k = end + 1;
    }
  }
  return out;
}

Scene::Scene(const machine::ClimbingMachine& machine, std::vector<WallBox> walls,
             std::vector<Anchor> pipes)
    : machine_(machine),
      walls_(std::move(walls)),
      pipes_(std::move(pipes)),
      manager_(std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>()) {
  std::vector<fcl::CollisionObjectd*> objects;
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const WallBox& w = walls_[k];
    auto box =
        std::make_shared<fcl::Boxd>((w.b - w.a).norm(), w.thickness_m, w.z_top_m - w.z_bottom_m);
    auto object = std::make_unique<fcl::CollisionObjectd>(box, wall_pose(w));
    object->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(k + 1)));
    object->computeAABB();
    objects.push_back(object.get());
    wall_objects_.push_back(std::move(object));
  }
  if (!objects.empty()) manager_->registerObjects(objects);
  manager_->setup();

  const machine::Kinematics& robot = *machine_.robot;
  link_shapes_.resize(robot.link_count());
  for (int l = 0; l < robot.link_count(); ++l)
    for (const auto& shape : robot.link_info(l).collisions) {
      std::shared_ptr<fcl::CollisionGeometryd> geometry;
      switch (shape.kind) {
        case machine::CollisionShape::Kind::kBox:
          geometry = std::make_shared<fcl::Boxd>(shape.size.x(), shape.size.y(), shape.size.z());
          break;
        case machine::CollisionShape::Kind::kCylinder:
          geometry = std::make_shared<fcl::Cylinderd>(shape.size.x(), shape.size.y());
          break;
        case machine::CollisionShape::Kind::kSphere:
          geometry = std::make_shared<fcl::Sphered>(shape.size.x());
          break;
      }
      link_shapes_[l].push_back(
          {std::make_unique<fcl::CollisionObjectd>(geometry, shape.origin), shape.origin});
    }
  assembly_.assign(robot.link_count(), 0);
  for (int l : machine_.gantry_links) assembly_[l] = 1;
  pin_link_unit_.assign(robot.link_count(), -1);
  for (std::size_t u = 0; u < machine_.units.size(); ++u) {
    for (int l : machine_.units[u].links) assembly_[l] = 2 + static_cast<int>(u);
    pin_link_unit_[machine_.units[u].pin_link] = static_cast<int>(u);
  }
}

Scene::~Scene() = default;

std::string Scene::describe_wall(int box) const {
  if (box < 0) return "a wall";
  return "wall " + std::to_string(walls_[box].wall_id) + " of floor " +
         std::to_string(walls_[box].floor);
}

std::string Scene::describe_link(int link) const {
  const std::string name = machine_.robot->link_info(link).name;
  for (const auto& unit : machine_.units)
    for (int l : unit.links)
      if (l == link) return unit.name + "'s link " + name;
  return "link " + name;
}

bool Scene::pin_in_pipe(int link, const Eigen::Isometry3d& pose, int box) const {
  if (box < 0 || pin_link_unit_[link] < 0) return false;
  const Eigen::Vector3d tip = pose.translation();
  const Eigen::Vector3d axis = pose.linear() * Eigen::Vector3d::UnitX();
  const WallBox& wall = walls_[box];
  for (const auto& pipe : pipes_) {
    if (pipe.wall_id != wall.wall_id || pipe.floor != wall.floor) continue;
    const Eigen::Vector3d into(-pipe.outward.x(), -pipe.outward.y(), 0.0);
    if (axis.dot(into) < 1.0 - 1e-4) continue;
    // The pipe's axis and the pin's axis coincide within 5 mm.
    const Eigen::Vector3d off = pipe.centre_m - tip;
    if ((off - off.dot(into) * into).norm() < 5e-3) return true;
  }
  return false;
}

void Scene::place(int link, const Eigen::Isometry3d& pose) const {
  for (const auto& shape : link_shapes_[link]) {
    shape.object->setTransform(pose * shape.origin);
    shape.object->computeAABB();
  }
}

Verdict Scene::check(const std::vector<double>& q, const Eigen::Isometry3d& platform,
                     const std::vector<int>& moving, const std::vector<int>& self_moving,
                     const std::vector<Eigen::Vector2d>& support) const {
  const machine::Kinematics& robot = *machine_.robot;
  const auto poses = robot.link_poses(platform, q);
  for (int link : moving) {
    place(link, poses[link]);
    for (const auto& shape : link_shapes_[link]) {
      CollisionQuery query;
      if (pin_link_unit_[link] >= 0)
        query.ignore = [&](int box) { return pin_in_pipe(link, poses[link], box); };
      manager_->collide(shape.object.get(), &query, on_pair);
      if (query.hit) {
        const std::string wall = describe_wall(query.box);
        return Verdict::refused(describe_link(link) + " touches " + wall, wall);
      }
    }
  }
  // The machine itself: only links of other assemblies, and not a link's own parent.
  if (!self_moving.empty()) {
    for (int l = 0; l < robot.link_count(); ++l) place(l, poses[l]);
    for (int link : self_moving)
      for (int other = 0; other < robot.link_count(); ++other) {
        if (assembly_[other] == assembly_[link] || robot.parent_link(link) == other ||
            robot.parent_link(other) == link)
          continue;
        if (other < link &&
            std::find(self_moving.begin(), self_moving.end(), other) != self_moving.end())
          continue;  // that pair was tested from the other side
        for (const auto& a : link_shapes_[link])
          for (const auto& b : link_shapes_[other]) {
            if (!a.object->getAABB().overlap(b.object->getAABB())) continue;
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            if (fcl::collide(a.object.get(), b.object.get(), request, result) > 0) {
              const std::string part = "the machine's " + describe_link(other);
              return Verdict::refused(describe_link(link) + " touches " + part, part);
            }
          }
      }
  }
  if (!support.empty()) {
    const Eigen::Vector3d com = robot.centre_of_mass(poses);
    const double inside = inside_hull_m(com.head<2>(), support);
    if (!std::isfinite(inside))
      return Verdict::refused("unstable: the holding pins lie in a line, no polygon to stand on",
                              "the stability margin", true);
    if (inside < machine_.stability_margin_m)
      return Verdict::refused(
          "unstable: the centre of mass is " +
              (inside < 0 ? metres(-inside, 2) + " outside" : metres(inside, 2) + " inside") +
              " the holding pins' polygon (the margin is " +
              metres(machine_.stability_margin_m, 2) + ")",
          "the stability margin", true);
  }
  return {};
}

double Scene::clearance(const std::vector<double>& q, const Eigen::Isometry3d& platform,
                        const std::vector<int>& moving) const {
  const auto poses = machine_.robot->link_poses(platform, q);
  DistanceQuery query;
  for (int link : moving) {
    if (pin_link_unit_[link] >= 0) continue;  // a pin goes into its wall
    place(link, poses[link]);
    for (const auto& shape : link_shapes_[link])
      manager_->distance(shape.object.get(), &query, on_distance);
  }
  return query.best;
}

double inside_hull_m(const Eigen::Vector2d& p, std::vector<Eigen::Vector2d> points) {
  if (points.size() < 3) return -std::numeric_limits<double>::infinity();
  // Andrew's monotone chain, counter-clockwise.
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& pt : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pt) <= 0) --k;
    hull[k++] = pt;
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) return -std::numeric_limits<double>::infinity();
  double inside = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2d d = (b - a).normalized();
    // Counter-clockwise: the inside is to the left of each edge.
    inside = std::min(inside, d.x() * (p - a).y() - d.y() * (p - a).x());
  }
  return inside;
}

}  // namespace ccbuild::climb::detail
