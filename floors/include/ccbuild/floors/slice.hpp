#pragma once
// Slicing a floor into layers. A floor of height H with layer height h has ceil(H/h)
// layers (the last may be thinner); the part of a wall inside an opening is absent from
// every layer whose mid-height lies in [sill, head). Each layer is a list of wall
// segments that remember their origin; endpoints closer than a tolerance are merged.

#include <Eigen/Core>
#include <array>
#include <compare>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plan.hpp"

namespace ccbuild::floors {

/// One straight piece of a wall at one height, in the wall's own direction.
struct LayerSegment {
  std::int64_t wall_id = 0;
  int piece = 0;        ///< 0-based, counted from the wall's start vertex
  int piece_count = 1;  ///< pieces this wall has in this layer (1 when not cut)
  int start_point = 0;  ///< index into Layer::points
  int end_point = 0;
  double length_m = 0.0;
  double width_m = 0.0;  ///< the bead's width; 0 when the plan was sliced without beads
  BeadRole role = BeadRole::kPass;
};

struct Layer {
  int floor_index = 0;
  int index = 0;            ///< within its floor, 0 = bottom
  double z_bottom_m = 0.0;  ///< building elevation
  double z_top_m = 0.0;
  std::vector<Eigen::Vector2d> points;
  std::vector<LayerSegment> segments;
  /// Same value for layers with the same geometry (segments as point pairs, quantised
  /// to 1 micrometre, order-independent); wall ids do not enter it. For display and
  /// quick lookups only: equal hashes are not proof, equal GeometryKeys are.
  std::uint64_t geometry_hash = 0;

  double total_length_m() const;
  Eigen::Vector2d start_m(const LayerSegment& s) const { return points[s.start_point]; }
  Eigen::Vector2d end_m(const LayerSegment& s) const { return points[s.end_point]; }
};

struct SliceOptions {
  /// Endpoints closer than this are one point; pieces shorter than it are dropped.
  double merge_tolerance_m = limits::kMinWallLength_m;
};

/// A straight piece of a wall, before endpoints are merged into a layer.
struct PieceSpec {
  std::int64_t wall_id = 0;
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();  ///< in the wall's own direction
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();
  double along_m = 0.0;  ///< where the piece starts along its wall: orders the pieces
  double width_m = 0.0;  ///< as LayerSegment
  BeadRole role = BeadRole::kPass;
};

/// Builds a layer from pieces: merges endpoints closer than the tolerance, drops pieces
/// shorter than it, numbers each wall's pieces along the wall, sorts segments by wall
/// (in first-appearance order) then piece, and computes the geometry hash.
Layer layer_from_pieces(const std::vector<PieceSpec>& pieces, const SliceOptions& options = {});

/// The layer made of some of `layer`'s segments (indices), keeping their wall ids and
/// piece numbers; points are renumbered and the hash recomputed.
Layer sub_layer(const Layer& layer, const std::vector<int>& segments);

/// Number of layers of a floor: ceil(height / layer height), with a relative tolerance
/// so that 3.0 / 0.1 is 30 and not 31, and 2.7 / 0.03 is 90. Throws InternalError when
/// the count would not be plausible (loaders check heights against limits.hpp first).
int layer_count(double floor_height_m, double layer_height_m);

/// All layers of one floor of a building.
std::vector<Layer> slice_floor(const Floor& floor, double layer_height_m,
                               const SliceOptions& options = {});
/// The mid-height of layer `k` of a floor of height `floor_height_m` above its base, m:
/// what decides whether an opening cuts the layer (the one computation of it).
double layer_mid_m(double floor_height_m, double layer_height_m, int k);
/// Layer `k` (0 to layer_count - 1) of one floor of a building, as slice_floor gives it.
Layer slice_floor_layer(const Floor& floor, double layer_height_m, int k,
                        const SliceOptions& options = {});

/// One layer at a given height above the plan's floor base (for single-plan tools).
Layer slice_plan_at(const FloorPlan& plan, double z_bottom_m, double z_top_m,
                    const SliceOptions& options = {});

/// Turns a plan into one layer with every wall whole (openings ignored).
Layer plan_as_layer(const FloorPlan& plan, const SliceOptions& options = {});

/// The canonical form of a layer's geometry: every segment as its two end points
/// quantised to 1 micrometre, the pair in order, the list sorted. Layers with equal keys
/// deposit the same pieces at the same places, whatever their wall ids, directions and
/// order; unlike the 64-bit hash, equality of keys is proof of that.
class GeometryKey {
 public:
  using QuantisedSegment = std::array<std::int64_t, 4>;  ///< x0, y0, x1, y1 in micrometres

  GeometryKey() = default;
  explicit GeometryKey(const Layer& layer);

  std::uint64_t hash() const { return hash_; }  ///< the same as Layer::geometry_hash
  std::size_t size() const { return segments_.size(); }
  const std::vector<QuantisedSegment>& segments() const { return segments_; }

  friend bool operator==(const GeometryKey& a, const GeometryKey& b) {
    return a.hash_ == b.hash_ && a.segments_ == b.segments_;
  }
  friend std::strong_ordering operator<=>(const GeometryKey& a, const GeometryKey& b) {
    return a.segments_ <=> b.segments_;
  }

 private:
  std::vector<QuantisedSegment> segments_;
  std::uint64_t hash_ = 0;
};

/// The distinct geometries of a building's layers, numbered from 1 in the order they first
/// appear (bottom to top); a layer with no walls has none. The one numbering of "distinct
/// layers": the schedule's plan keys g<number>n<nozzles>, `ccbuild layers`, `sweep` and
/// `plan-layer` name geometries by it.
class GeometryNumbering {
 public:
  /// The number of `layer`'s geometry, a new one if it is the first of its kind; 0 (and
  /// nothing counted) for a layer with no walls. `fresh` says whether it was new.
  int number(const Layer& layer, bool* fresh = nullptr);
  /// How many distinct geometries were numbered.
  int count() const { return static_cast<int>(numbers_.size()); }

 private:
  std::map<GeometryKey, int> numbers_;
};

/// For std::unordered_map keyed by geometry.
struct GeometryKeyHash {
  std::size_t operator()(const GeometryKey& key) const { return key.hash(); }
};

/// Where a segment of one layer is in another layer of the same geometry.
struct SegmentMatch {
  int segment = 0;        ///< index into the other layer's segments
  bool reversed = false;  ///< the other layer's segment runs the opposite way
};

/// For each segment of `from`, the segment of `to` at the same place (1 micrometre),
/// so that a plan of one can be replayed on the other; nullopt when their geometries
/// differ.
std::optional<std::vector<SegmentMatch>> match_segments(const Layer& from, const Layer& to);

/// Computes the geometry hash of a layer's segments (see Layer::geometry_hash).
std::uint64_t geometry_hash(const Layer& layer);

/// 16 hex digits.
std::string hash_to_hex(std::uint64_t hash);

}  // namespace ccbuild::floors
