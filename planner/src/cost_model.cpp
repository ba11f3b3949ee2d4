#include "ccbuild/planner/cost_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <deque>
#include <limits>
#include <unordered_map>

#include "ccbuild/common/input_error.hpp"
#include "geometry.hpp"
#include "pair_slots.hpp"

namespace ccbuild::planner {

using detail::Vec2;

std::string to_string(Metric metric) {
  return metric == Metric::kEuclidean ? "euclidean" : "rectilinear";
}
std::string to_string(Objective objective) {
  return objective == Objective::kDistance ? "distance" : "time";
}

std::optional<Metric> parse_metric(const std::string& text) {
  if (text == "euclidean" || text == "D") return Metric::kEuclidean;
  if (text == "rectilinear" || text == "R") return Metric::kRectilinear;
  return std::nullopt;
}

std::optional<Objective> parse_objective(const std::string& text) {
  if (text == "distance") return Objective::kDistance;
  if (text == "time") return Objective::kTime;
  return std::nullopt;
}

namespace {
using MoveKey = std::array<double, 4>;
struct MoveKeyHash {
  std::size_t operator()(const MoveKey& k) const {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (double v : k) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 0x100000001b3ULL;
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h);
  }
};
}  // namespace

struct CostModel::Index {
  detail::SegmentGrid grid;
  std::unordered_map<MoveKey, std::vector<int>, MoveKeyHash> crossings;  // by the move's end points
  // By layer point pair: a dense table of slots for small layers, a hash table otherwise.
  int point_count = 0;
  std::vector<int> dense_slot;  // point pair -> 1 + index into pair_lists, 0 when unknown
  detail::PairSlots sparse_slot;
  std::deque<std::vector<int>> pair_lists;  // deque: references stay valid as it grows
};

namespace {

void require_positive(double value, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw InputError("", 0, field, "must be positive and finite for planning");
}
}  // namespace

CostModel::CostModel(std::shared_ptr<const floors::Layer> shared,
                     const machine::MachineModel& machine, Metric metric)
    : layer_(std::move(shared)),
      machine_(machine),
      metric_(metric),
      index_(std::make_unique<Index>()) {
  CCBUILD_CHECK(layer_ != nullptr, "a cost model has a layer");
  const floors::Layer& layer = *layer_;
  require_positive(machine_.deposition_speed_m_s, "MachineModel::deposition_speed_m_s");
  require_positive(machine_.travel_speed_m_s, "MachineModel::travel_speed_m_s");
  require_positive(machine_.x.speed_m_s, "MachineModel::x.speed_m_s");
  require_positive(machine_.y.speed_m_s, "MachineModel::y.speed_m_s");
  require_positive(machine_.rotation_speed_rad_s, "MachineModel::rotation_speed_rad_s");
  std::vector<std::pair<Vec2, Vec2>> segments;
  segments.reserve(layer.segments.size());
  for (const auto& s : layer.segments) segments.emplace_back(layer.start_m(s), layer.end_m(s));
  index_->grid = detail::SegmentGrid(segments);
  index_->point_count = static_cast<int>(layer.points.size());
  if (index_->point_count <= 1500)
    index_->dense_slot.assign(static_cast<std::size_t>(index_->point_count) * index_->point_count,
                              0);
  deposition_s_ = deposition_time_s(layer, machine_);
  segment_heading_rad_.reserve(layer.segments.size());
  for (const auto& seg : layer.segments) {
    const Vec2 d = layer.end_m(seg) - layer.start_m(seg);
    segment_heading_rad_.push_back(std::atan2(d.y(), d.x()));
  }
}

CostModel::CostModel(const floors::Layer& layer, const machine::MachineModel& machine,
                     Metric metric)
    : CostModel(std::make_shared<const floors::Layer>(layer), machine, metric) {}

CostModel::~CostModel() = default;
CostModel::CostModel(CostModel&&) noexcept = default;

bool CostModel::path_crosses(const Vec2& a, const Vec2& b, int segment) const {
  const auto legs = detail::travel_legs(a, b, metric_ == Metric::kRectilinear);
  const auto& [s0, s1] = index_->grid.segment(segment);
  for (int k = 0; k < legs.count; ++k) {
    if (detail::leg_crosses(legs.points[k], legs.points[k + 1], s0, s1, k == 0,
                            k == legs.count - 1))
      return true;
  }
  return false;
}

const std::vector<int>& CostModel::crossed_segments(const Vec2& a, const Vec2& b) const {
  auto [it, fresh] = index_->crossings.try_emplace(MoveKey{a.x(), a.y(), b.x(), b.y()});
  if (!fresh) return it->second;
  std::vector<int>& out = it->second;
  const auto legs = detail::travel_legs(a, b, metric_ == Metric::kRectilinear);
  for (int k = 0; k < legs.count; ++k) {
    index_->grid.for_each_near(legs.points[k], legs.points[k + 1], [&](int s) {
      const auto& [s0, s1] = index_->grid.segment(s);
      if (detail::leg_crosses(legs.points[k], legs.points[k + 1], s0, s1, k == 0,
                              k == legs.count - 1))
        out.push_back(s);
    });
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const std::vector<int>& CostModel::crossed_between_points(int from_point, int to_point) const {
  Index& index = *index_;
  int* slot;
  if (!index.dense_slot.empty()) {
    slot = &index.dense_slot[static_cast<std::size_t>(from_point) * index.point_count + to_point];
  } else {
    slot = &index.sparse_slot[(static_cast<std::uint64_t>(from_point) << 32) |
                              static_cast<std::uint32_t>(to_point)];
  }
  // Slots: 0 not yet known, -1 crosses nothing (most moves: no list to fetch), k the k-th
  // list.
  static const std::vector<int> kNone;
  if (*slot == 0) {
    std::vector<int> crossed =
        crossed_segments(layer_->points[from_point], layer_->points[to_point]);
    if (crossed.empty()) {
      *slot = -1;
    } else {
      index.pair_lists.push_back(std::move(crossed));
      *slot = static_cast<int>(index.pair_lists.size());
    }
  }
  return *slot < 0 ? kNone : index.pair_lists[*slot - 1];
}

double CostModel::stopper_turn_rad(double from_rad, double target_rad) const {
  const double short_way = detail::wrap_angle(target_rad - from_rad);
  if (std::abs(short_way) <= 1e-12) return 0.0;
  const double long_way = short_way > 0 ? short_way - 2.0 * M_PI : short_way + 2.0 * M_PI;
  const double lo = machine_.stopper_min_rad - 1e-9, hi = machine_.stopper_max_rad + 1e-9;
  auto inside = [&](double turn) { return from_rad + turn >= lo && from_rad + turn <= hi; };
  const bool short_ok = inside(short_way), long_ok = inside(long_way);
  if (short_ok && long_ok) {
    if (std::abs(std::abs(short_way) - M_PI) <= 1e-12)  // half a turn: unwind
      return std::abs(from_rad + short_way) <= std::abs(from_rad + long_way) ? short_way : long_way;
    return short_way;
  }
  if (short_ok) return short_way;
  if (long_ok) return long_way;
  // A stopper narrower than a full turn cannot always reach the heading; take the way
  // that ends nearer the range (MachineModel loading rejects such stoppers).
  auto overshoot = [&](double turn) {
    return std::max(lo - (from_rad + turn), (from_rad + turn) - hi);
  };
  return overshoot(short_way) <= overshoot(long_way) ? short_way : long_way;
}

double deposition_time_s(const floors::Layer& layer, const machine::MachineModel& machine) {
  return layer.total_length_m() / machine.deposition_speed_m_s;
}

bool covers_every_segment_once(const Sequence& sequence, std::size_t segment_count) {
  if (sequence.size() != segment_count) return false;
  std::vector<char> seen(segment_count, 0);
  for (const auto& step : sequence) {
    if (step.segment < 0 || step.segment >= static_cast<int>(segment_count) || seen[step.segment])
      return false;
    seen[step.segment] = 1;
  }
  return true;
}

PathState CostModel::begin(const PathSpec& path) const {
  PathState state;
  state.position_m = path.start_m;
  return state;
}

Evaluation CostModel::evaluate(const Sequence& sequence, const PathSpec& path) const {
  Evaluation out;
  const int segment_count = static_cast<int>(layer_->segments.size());
  std::vector<char> deposited(segment_count, 0);
  auto is_deposited = [&](int s) { return deposited[s] != 0; };
  double deposited_length = 0.0;
  auto record = [&](const Move& m) {
    out.airtime_distance_m += m.distance_m;
    out.airtime_s += m.time_s;
    out.max_idle_s = std::max(out.max_idle_s, m.time_s);
    out.lift_count += m.lifted ? 1 : 0;
    out.idle_limit_violations += m.time_s > machine_.nozzle_idle_limit_s ? 1 : 0;
    out.total_rotation_rad += std::abs(m.rotation_rad);
    out.moves.push_back(m);
  };
  PathState state = begin(path);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const Step& step = sequence[i];
    CCBUILD_CHECK(step.segment >= 0 && step.segment < segment_count,
                  "step names a segment of the layer");
    CCBUILD_CHECK(!deposited[step.segment], "a sequence deposits each segment at most once");
    const Move move = advance(state, step, path, is_deposited);
    if (i > 0 || !path.closed) record(move);  // a closed tour's first move is its closing move
    deposited[step.segment] = 1;
    deposited_length += layer_->segments[step.segment].length_m;
  }
  if (path.closed && !sequence.empty()) record(close(state, sequence.front(), is_deposited));
  out.final_heading_rad = state.heading_rad;
  out.deposition_s = deposited_length / machine_.deposition_speed_m_s;
  out.layer_time_s = out.deposition_s + out.airtime_s;
  return out;
}

}  // namespace ccbuild::planner
