// Cutting a layer into sections across the rail axis, and iterative dividing.

#include <algorithm>
#include <cmath>
#include <numeric>

#include "../search_internal.hpp"
#include "ccbuild/common/input_error.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner::detail {

std::vector<int> CutLayer::segments_in(int b) const {
  return segments_in(b, b);
}

std::vector<int> CutLayer::segments_in(int first_band, int last_band) const {
  std::vector<int> out;
  for (int s = 0; s < static_cast<int>(band.size()); ++s)
    if (band[s] >= first_band && band[s] <= last_band) out.push_back(s);
  return out;
}

CutLayer cut_layer(const floors::Layer& layer, RailAxis axis, const std::vector<double>& cuts) {
  constexpr double kEps = 1e-9;
  std::vector<floors::PieceSpec> pieces;
  for (const auto& seg : layer.segments) {
    const Eigen::Vector2d a = layer.start_m(seg), b = layer.end_m(seg);
    const double ca = rail_coordinate(a, axis), cb = rail_coordinate(b, axis);
    std::vector<double> at{0.0};
    for (double c : cuts) {
      if (c > std::min(ca, cb) + kEps && c < std::max(ca, cb) - kEps)
        at.push_back((c - ca) / (cb - ca));
    }
    at.push_back(1.0);
    std::sort(at.begin(), at.end());
    // Pieces keep their place along the wall: earlier pieces of the wall first.
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      const Eigen::Vector2d p = at[k] == 0.0 ? a : Eigen::Vector2d(a + at[k] * (b - a));
      const Eigen::Vector2d q = at[k + 1] == 1.0 ? b : Eigen::Vector2d(a + at[k + 1] * (b - a));
      pieces.push_back(
          {seg.wall_id, p, q, seg.piece * 1e7 + at[k] * seg.length_m, seg.width_m, seg.role});
    }
  }
  CutLayer out;
  out.layer = floors::layer_from_pieces(pieces);
  out.layer.floor_index = layer.floor_index;
  out.layer.index = layer.index;
  out.band.reserve(out.layer.segments.size());
  for (const auto& seg : out.layer.segments) {
    const double mid = rail_coordinate(0.5 * (out.layer.start_m(seg) + out.layer.end_m(seg)), axis);
    int b = 0;
    while (b < static_cast<int>(cuts.size()) && mid > cuts[b] + kEps) ++b;
    out.band.push_back(b);
  }
  return out;
}

Sequence closed_tour(const floors::Layer& layer, const std::vector<int>& segments,
                     const StageContext& ctx, std::optional<long> max_kicks, bool polish) {
  if (segments.empty()) return {};
  if (ctx.stop.should_stop()) {
    // Out of time: the walls in their given order, at once (the answer will say the
    // time limit came first).
    Sequence out;
    for (int s : segments) out.push_back({s, false});
    return out;
  }
  const floors::Layer part = floors::sub_layer(layer, segments);
  PlanOptions o = ctx.options.planning;
  o.algorithm = Algorithm::kCcTsp;
  o.path = PathSpec::closed_tour();
  o.waypoints = false;  // only the order is kept
  o.time_limit_s = std::max(0.05, std::min(o.time_limit_s, ctx.stop.remaining_s()));
  if (max_kicks) o.max_kicks = max_kicks;
  // Sections and zones are many and small: a short exact-time polish is plenty. A large
  // section gets the descent alone, as a layer of its size does: on the 40 x 40 rooms
  // benchmark's sections of 974-2,317 walls five kicks cost a third of each section's
  // plan and changed one layer time of 15, by 0.025% (bench/README.md, issue 50).
  if (!o.polish_kicks) o.polish_kicks = segments.size() > kExactPolishKicksMaxSegments ? 0 : 5;
  o.exact_polish = o.exact_polish && polish;
  const LayerPlan plan = plan_layer(part, ctx.machine, o);
  Sequence out;
  for (const Step& step : plan.sequence) out.push_back({segments[step.segment], step.reversed});
  return out;
}

namespace {
Division compute_division(const StageContext& ctx);
}  // namespace

const Division& divide(const StageContext& ctx) {
  if (!ctx.division) ctx.division = std::make_shared<const Division>(compute_division(ctx));
  return *ctx.division;
}

const Sections& sections_of(const StageContext& ctx) {
  if (ctx.sections) return *ctx.sections;
  auto s = std::make_shared<Sections>();
  s->division = divide(ctx);
  s->cut = cut_layer(ctx.layer, ctx.options.rail_axis, s->division.cuts);
  const int n = ctx.options.nozzles;
  for (int k = 0; k < n; ++k) {
    NozzleWork w;
    w.from_m = k == 0 ? ctx.from_m : s->division.cuts[k - 1];
    w.to_m = k == n - 1 ? ctx.to_m : s->division.cuts[k];
    w.section_segments = s->cut.segments_in(k);
    w.working = closed_tour(s->cut.layer, w.section_segments, ctx);
    s->works.push_back(std::move(w));
  }
  ctx.sections = s;
  return *ctx.sections;
}

namespace {
Division compute_division(const StageContext& ctx) {
  const int n = ctx.options.nozzles;
  const double length = std::max(ctx.to_m - ctx.from_m, 1e-6);
  std::vector<double> widths(n, length / n);
  Division best;
  double best_max = std::numeric_limits<double>::infinity();
  auto cuts_of = [&](const std::vector<double>& w) {
    std::vector<double> cuts;
    double at = ctx.from_m;
    for (int k = 0; k + 1 < n; ++k) cuts.push_back(at += w[k]);
    return cuts;
  };
  const long kicks = 100 + 2 * static_cast<long>(ctx.layer.segments.size()) / n;
  for (int iteration = 1; iteration <= ctx.options.max_dividing_iterations; ++iteration) {
    Division d;
    d.cuts = cuts_of(widths);
    d.iterations = iteration;
    const CutLayer cut = cut_layer(ctx.layer, ctx.options.rail_axis, d.cuts);
    for (int k = 0; k < n; ++k) {
      const std::vector<int> segments = cut.segments_in(k);
      if (segments.empty()) {
        d.section_time_s.push_back(0.0);
        continue;
      }
      const floors::Layer part = floors::sub_layer(cut.layer, segments);
      const Sequence tour =
          closed_tour(cut.layer, segments, ctx, kicks, false);  // balancing: no polish
      Sequence local;
      for (std::size_t i = 0; i < tour.size(); ++i)
        local.push_back(
            {static_cast<int>(std::find(segments.begin(), segments.end(), tour[i].segment) -
                              segments.begin()),
             tour[i].reversed});
      const CostModel model(part, ctx.machine, ctx.options.planning.metric);
      d.section_time_s.push_back(model.evaluate(local, PathSpec::closed_tour()).layer_time_s);
    }
    const double slowest = *std::max_element(d.section_time_s.begin(), d.section_time_s.end());
    const double fastest = *std::min_element(d.section_time_s.begin(), d.section_time_s.end());
    const double mean = std::accumulate(d.section_time_s.begin(), d.section_time_s.end(), 0.0) / n;
    if (slowest < best_max) {
      best_max = slowest;
      best = d;
    }
    if (mean <= 0.0 || (slowest - fastest) / mean < ctx.options.balance_tolerance ||
        ctx.stop.should_stop())
      break;
    // Move the cuts in proportion to each section's deviation from the mean: a section
    // slower than the mean shrinks, a faster one grows (damped to avoid oscillation).
    for (int k = 0; k < n; ++k) {
      const double ratio = mean / std::max(d.section_time_s[k], 0.05 * mean);
      widths[k] *= std::pow(ratio, 0.7);
    }
    const double total = std::accumulate(widths.begin(), widths.end(), 0.0);
    for (double& w : widths) w = std::max(w * length / total, 1e-3 * length);
  }
  return best;
}
}  // namespace

}  // namespace ccbuild::planner::detail
