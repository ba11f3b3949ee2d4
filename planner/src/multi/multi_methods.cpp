// The papers' multi-nozzle methods: path cycling (individual and global), buffer zone
// path cycling and the auxiliary buffer zone.

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <tuple>

#include "ccbuild/common/format.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

// Splits sections into zones at given offsets from each section's left border, then
// plans each zone. `zone_widths[k]` lists the widths of section k's leading zones.
struct Zoned {
  CutLayer cut;
  std::vector<NozzleWork> works;
  std::vector<std::vector<double>> zone_time_s;  // per section, per leading zone
};

Zoned zoned_sections(const StageContext& ctx, const Division& division,
                     const std::vector<std::vector<double>>& zone_widths,
                     const std::vector<std::string>& names) {
  const int n = ctx.options.nozzles;
  std::vector<double> borders{ctx.from_m};
  borders.insert(borders.end(), division.cuts.begin(), division.cuts.end());
  borders.push_back(ctx.to_m);
  std::vector<double> cuts = division.cuts;
  for (int k = 0; k < n; ++k) {
    double at = borders[k];
    for (double w : zone_widths[k]) cuts.push_back(at += w);
  }
  std::sort(cuts.begin(), cuts.end());
  Zoned z;
  z.cut = cut_layer(ctx.layer, ctx.options.rail_axis, cuts);
  for (int k = 0; k < n; ++k) {
    NozzleWork w;
    w.from_m = borders[k];
    w.to_m = borders[k + 1];
    std::vector<std::vector<int>> zone_segments(zone_widths[k].size());
    std::vector<int> working;
    for (int s = 0; s < static_cast<int>(z.cut.layer.segments.size()); ++s) {
      const auto& seg = z.cut.layer.segments[s];
      const double mid = rail_coordinate(0.5 * (z.cut.layer.start_m(seg) + z.cut.layer.end_m(seg)),
                                         ctx.options.rail_axis);
      const bool inside = k == 0 ? mid <= borders[1] + 1e-9
                                 : (mid > borders[k] + 1e-9 && mid <= borders[k + 1] + 1e-9);
      if (!inside) continue;
      w.section_segments.push_back(s);
      double edge = borders[k];
      std::size_t zone = 0;
      for (; zone < zone_widths[k].size(); ++zone) {
        edge += zone_widths[k][zone];
        if (mid <= edge + 1e-9) break;
      }
      if (zone < zone_widths[k].size())
        zone_segments[zone].push_back(s);
      else
        working.push_back(s);
    }
    std::vector<double> times;
    for (std::size_t zone = 0; zone < zone_segments.size(); ++zone) {
      const Sequence tour = closed_tour(z.cut.layer, zone_segments[zone], ctx);
      double time = 0.0;
      if (!tour.empty()) {
        SectionModel part(ctx, z.cut, zone_segments[zone]);
        time = part.model->evaluate(part.local(tour), PathSpec::closed_tour()).layer_time_s;
        w.fixed_blocks.push_back(tour);
        w.fixed_names.push_back(names[zone]);
      }
      times.push_back(time);
    }
    w.working = closed_tour(z.cut.layer, working, ctx);
    z.zone_time_s.push_back(times);
    z.works.push_back(std::move(w));
  }
  return z;
}

}  // namespace

namespace {

// Path cycling proper: compatible start points for the works' tours, then the exact check.
MethodResult cycled(const StageContext& ctx, const CutLayer& cut,
                    const std::vector<NozzleWork>& works) {
  CycleSearch search = compatible_cycles(ctx, cut, works);
  MethodResult result;
  if (!search.status)
    result.status = std::move(search.status);
  else
    result = checked(ctx, build_paths(ctx, cut, works, search.cycles));
  result.vertices = static_cast<int>(cut.layer.points.size());
  return result;
}

}  // namespace

MethodResult path_cycling(const StageContext& ctx) {
  const Sections& s = sections_of(ctx);
  if (PlanStatus late = stop_status(ctx, "iterative dividing"); !late) {
    MethodResult out;
    out.status = std::move(late);
    out.vertices = static_cast<int>(s.cut.layer.points.size());
    return out;
  }
  return cycled(ctx, s.cut, s.works);
}

namespace {

// The ways to cut one closed tour into contiguous pieces, each of which becomes a closed
// path of its own: the moves between pieces are dropped and each piece returns to its
// start. Steps are indexed around the tour twice over (t and t + m are the same step), so
// a piece is a start and a length.
class TourPieces {
 public:
  TourPieces(const Sequence& tour, const CostModel& model, RailAxis axis)
      : tour_(tour), model_(model), m_(static_cast<int>(tour.size())) {
    const Evaluation e = model.evaluate(tour, PathSpec::closed_tour());
    const double speed = model.machine().deposition_speed_m_s;
    deposition_.assign(2 * m_ + 1, 0.0);
    moves_.assign(2 * m_ + 1, 0.0);
    std::vector<double> lo(2 * m_), hi(2 * m_);
    for (int t = 0; t < 2 * m_; ++t) {
      const Step& step = tour[t % m_];
      deposition_[t + 1] = deposition_[t] + model.layer().segments[step.segment].length_m / speed;
      // e.moves[k] leads to step k + 1; the last one (the closing move) to step 0.
      moves_[t + 1] = moves_[t] + e.moves[(t % m_ + m_ - 1) % m_].time_s;
      const double a = rail_coordinate(model.step_start_m(step), axis),
                   b = rail_coordinate(model.step_end_m(step), axis);
      lo[t] = std::min(a, b);
      hi[t] = std::max(a, b);
    }
    // Sparse tables for the rail extent of any run of steps.
    lo_.push_back(lo);
    hi_.push_back(hi);
    for (int span = 1; 2 * span <= 2 * m_; span *= 2) {
      std::vector<double> l(2 * m_ - 2 * span + 1), h(l.size());
      for (std::size_t t = 0; t < l.size(); ++t) {
        l[t] = std::min(lo_.back()[t], lo_.back()[t + span]);
        h[t] = std::max(hi_.back()[t], hi_.back()[t + span]);
      }
      lo_.push_back(std::move(l));
      hi_.push_back(std::move(h));
    }
    // The largest moves, for bounding what the moves dropped between pieces can take.
    largest_moves_s_.reserve(e.moves.size());
    for (const Move& move : e.moves) largest_moves_s_.push_back(move.time_s);
    std::sort(largest_moves_s_.rbegin(), largest_moves_s_.rend());
  }

  int size() const { return m_; }
  /// Deposition and inner moves of steps [a, a + len), as timed in the whole tour.
  double inner_s(int a, int len) const {
    return deposition_[a + len] - deposition_[a] + moves_[a + len] - moves_[a + 1];
  }
  /// inner_s plus the move from the piece's last wall back to its first.
  double time_s(int a, int len) const {
    const Step& first = tour_[a % m_];
    const Step& last = tour_[(a + len - 1) % m_];
    const double turn =
        std::remainder(model_.heading_rad(first) - model_.heading_rad(last), 2.0 * M_PI);
    return inner_s(a, len) +
           model_.move_time_s(model_.step_end_m(last), model_.step_start_m(first), turn, false);
  }
  /// Smallest and largest rail coordinate of the walls of steps [a, a + len).
  std::pair<double, double> extent(int a, int len) const {
    int level = 0;
    while ((2 << level) <= len) ++level;
    const int b = a + len - (1 << level);
    return {std::min(lo_[level][a], lo_[level][b]), std::max(hi_[level][a], hi_[level][b])};
  }
  /// An upper bound of the moves dropped when a run is cut into `pieces` pieces.
  double dropped_bound_s(int pieces) const {
    double sum = 0.0;
    for (int k = 0; k + 1 < pieces && k < static_cast<int>(largest_moves_s_.size()); ++k)
      sum += largest_moves_s_[k];
    return sum;
  }

  /// Calls visit(cuts, longest) for every way to cut the tour into `n` pieces that each
  /// take at most `limit` s (which visit may lower as it goes); cuts are ascending step
  /// indices where pieces begin, the last piece running on round the end of the tour to
  /// cuts[0]. Returns false when `budget` ran out first.
  template <class Visit>
  bool each_split(int n, double& limit, long& budget, Visit&& visit) const {
    std::vector<int> cuts(n);
    std::function<bool(int, double)> place = [&](int k, double longest) -> bool {
      const int from = cuts[k - 1], end = cuts[0] + m_;
      if (k == n) {
        const double t = time_s(from, end - from);
        if (t <= limit) visit(cuts, std::max(longest, t));
        return true;
      }
      // Piece k - 1 is [from, c). What follows, [c, end), must still fit n - k pieces:
      // its inner time shrinks as c grows, so start at the first c where it can.
      const int left = n - k;
      const double room = left * limit + dropped_bound_s(left);
      int lo = from + 1, hi = m_ - left;  // cuts stay below m: cuts[0] is the smallest
      if (lo > hi) return true;
      {
        int a = lo, b = hi + 1;
        while (a < b) {
          const int mid = (a + b) / 2;
          if (inner_s(mid, end - mid) <= room)
            b = mid;
          else
            a = mid + 1;
        }
        lo = a;
      }
      for (int c = lo; c <= hi; ++c) {
        if (inner_s(from, c - from) > limit) break;
        const double t = time_s(from, c - from);
        if (t > limit) continue;
        if (--budget < 0) return false;
        cuts[k] = c;
        if (!place(k + 1, std::max(longest, t))) return false;
      }
      return true;
    };
    for (int c0 = 0; c0 < m_; ++c0) {
      cuts[0] = c0;
      if (!place(1, 0.0)) return false;
    }
    return true;
  }

 private:
  const Sequence& tour_;
  const CostModel& model_;
  int m_;
  std::vector<double> deposition_, moves_;  // prefix sums over the doubled tour
  std::vector<std::vector<double>> lo_, hi_;
  std::vector<double> largest_moves_s_;
};

// A way to cut the tour, with its pieces in rail order.
struct TourSplit {
  std::vector<std::pair<int, int>> pieces;  // (start, length), ascending rail position
  std::vector<std::pair<double, double>> extents;
  double longest_s = 0.0;
  double shortfall_m = 0.0;  // summed over adjacent pieces: how much less than a gantry
                             // width apart their rail extents are
};

TourSplit make_split(const TourPieces& tp, const std::vector<int>& cuts, double longest,
                     double gantry_width_m) {
  const int n = static_cast<int>(cuts.size());
  std::vector<std::pair<int, int>> pieces;
  for (int k = 0; k < n; ++k) {
    const int end = k + 1 < n ? cuts[k + 1] : cuts[0] + tp.size();
    pieces.emplace_back(cuts[k], end - cuts[k]);
  }
  std::vector<std::pair<double, double>> extents;
  for (const auto& [a, len] : pieces) extents.push_back(tp.extent(a, len));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return extents[a].first + extents[a].second < extents[b].first + extents[b].second;
  });
  TourSplit out;
  out.longest_s = longest;
  for (int k : order) {
    out.pieces.push_back(pieces[k]);
    out.extents.push_back(extents[k]);
  }
  for (int k = 0; k + 1 < n; ++k)
    out.shortfall_m +=
        std::max(0.0, gantry_width_m - (out.extents[k + 1].first - out.extents[k].second));
  return out;
}

// Splits ranked for cycling: less shortfall first (to the centimetre), then faster.
bool better_split(const TourSplit& a, const TourSplit& b) {
  const long sa = std::lround(a.shortfall_m * 100.0), sb = std::lround(b.shortfall_m * 100.0);
  return sa != sb ? sa < sb : a.longest_s < b.longest_s;
}

constexpr int kSplitsToCycle = 6;         // best-ranked splits handed to path cycling in turn
constexpr long kSplitBudget = 4'000'000;  // pieces timed per enumeration

}  // namespace

MethodResult global_path_cycling(const StageContext& ctx) {
  const int n = ctx.options.nozzles;
  const double w = ctx.options.gantry_width_m;
  const CutLayer cut = cut_layer(ctx.layer, ctx.options.rail_axis, {});
  MethodResult out;
  out.vertices = static_cast<int>(cut.layer.points.size());
  std::vector<int> all(cut.layer.segments.size());
  std::iota(all.begin(), all.end(), 0);
  const Sequence tour = closed_tour(cut.layer, all, ctx);
  if (static_cast<int>(tour.size()) < n) {
    out.status = {PlanStatus::Code::kNotApplicable,
                  "the layer has fewer walls (" + std::to_string(tour.size()) + ") than nozzles"};
    return out;
  }
  if (PlanStatus late = stop_status(ctx, "the layer's tour"); !late) {
    out.status = std::move(late);
    return out;
  }
  const CostModel model(cut.layer, ctx.machine, ctx.options.planning.metric);
  const TourPieces tp(tour, model, ctx.options.rail_axis);
  // 1. The most balanced split: its longest piece as short as possible. Start from the
  //    layer time (any split is shorter) and tighten as splits are found.
  double limit = model.evaluate(tour, PathSpec::closed_tour()).layer_time_s + 1.0;
  double best = std::numeric_limits<double>::infinity();
  long budget = kSplitBudget;
  tp.each_split(n, limit, budget, [&](const std::vector<int>&, double longest) {
    best = std::min(best, longest);
    limit = best * (1.0 - 1e-12);
  });
  // 2. Among the splits balanced within the tolerance (longest piece at most that much
  //    longer than the best one's), those whose pieces lie furthest apart along the rails.
  limit = best * (1.0 + ctx.options.balance_tolerance) + 1e-9;
  budget = kSplitBudget;
  std::vector<TourSplit> ranked;
  tp.each_split(n, limit, budget, [&](const std::vector<int>& cuts, double longest) {
    TourSplit split = make_split(tp, cuts, longest, w);
    if (static_cast<int>(ranked.size()) == kSplitsToCycle && !better_split(split, ranked.back()))
      return;
    ranked.insert(std::upper_bound(ranked.begin(), ranked.end(), split, better_split),
                  std::move(split));
    if (static_cast<int>(ranked.size()) > kSplitsToCycle) ranked.pop_back();
  });
  if (ranked.empty()) {  // only when the enumeration ran out of budget first
    out.status = {PlanStatus::Code::kSearchExhausted,
                  "no cut of the tour into " + std::to_string(n) + " balanced pieces was found"};
    return out;
  }
  // 3. Path cycling on the pieces, the best-ranked split first.
  PlanStatus first_failure;
  for (const TourSplit& split : ranked) {
    std::vector<NozzleWork> works;
    for (std::size_t k = 0; k < split.pieces.size(); ++k) {
      const auto [a, len] = split.pieces[k];
      NozzleWork work;
      for (int t = a; t < a + len; ++t) {
        work.working.push_back(tour[t % tour.size()]);
        work.section_segments.push_back(work.working.back().segment);
      }
      std::tie(work.from_m, work.to_m) = split.extents[k];
      works.push_back(std::move(work));
    }
    CycleSearch search = compatible_cycles(ctx, cut, works);
    PlanStatus status = std::move(search.status);
    if (status) {
      MethodResult result = checked(ctx, build_paths(ctx, cut, works, search.cycles));
      if (result.status) {
        result.vertices = out.vertices;
        return result;
      }
      status = std::move(result.status);
    }
    if (first_failure) {
      std::string reason = status.reason();
      if (split.shortfall_m > 1e-9)
        reason += "; the best split's pieces are " + length(ctx.options, split.shortfall_m) +
                  " short of a gantry width apart along the rails";
      first_failure = {status.code(), reason};
    }
    if (PlanStatus late = stop_status(ctx, "global path cycling"); !late) {
      out.status = std::move(late);
      return out;
    }
  }
  out.status = {first_failure.code(), first_failure.reason() + " (" +
                                          std::to_string(ranked.size()) +
                                          " balanced splits of the tour tried)"};
  return out;
}

MethodResult buffer_zone_path_cycling(const StageContext& ctx) {
  const int n = ctx.options.nozzles;
  const double buffer = ctx.options.buffer_width_factor * ctx.options.gantry_width_m;
  const Division& division = divide(ctx);
  MethodResult out;
  // A buffer zone at every inner border, on the right-hand section's side.
  std::vector<std::vector<double>> widths(n);
  for (int k = 1; k < n; ++k) {
    const double section = (k == n - 1 ? ctx.to_m : division.cuts[k]) - division.cuts[k - 1];
    if (section <= buffer) {
      out.status = {PlanStatus::Code::kNotApplicable, "section " + std::to_string(k + 1) + " (" +
                                                          length(ctx.options, section) +
                                                          ") is not wider than its buffer zone (" +
                                                          length(ctx.options, buffer) + ")"};
      return out;
    }
    widths[k] = {buffer};
  }
  const Zoned z = zoned_sections(ctx, division, widths, {"buffer"});
  out.vertices = static_cast<int>(z.cut.layer.points.size());
  if (PlanStatus late = stop_status(ctx, "the zones' tours"); !late) {
    out.status = std::move(late);
    return out;
  }
  // The buffer must hold less than half the section's work.
  for (int k = 1; k < n; ++k) {
    const double b = z.zone_time_s[k][0];
    SectionModel section(ctx, z.cut, z.works[k].section_segments);
    const double whole = section.model ? section.model
                                             ->evaluate(section.local(concatenated(z.works[k], 0)),
                                                        PathSpec::closed_tour())
                                             .layer_time_s
                                       : 0.0;
    if (b >= 0.5 * whole && whole > 0.0) {
      out.status = {PlanStatus::Code::kNotApplicable,
                    "buffer zone of section " + std::to_string(k + 1) + " holds " + seconds(b) +
                        " of its " + seconds(whole) + " of work (must be under half)"};
      return out;
    }
  }
  return cycled(ctx, z.cut, z.works);
}

MethodResult aux_buffer_zone(const StageContext& ctx) {
  MethodResult out;
  const int n = ctx.options.nozzles;
  const double w = ctx.options.gantry_width_m;
  const double buffer = ctx.options.buffer_width_factor * w;
  const Division& division = divide(ctx);
  std::vector<double> borders{ctx.from_m};
  borders.insert(borders.end(), division.cuts.begin(), division.cuts.end());
  borders.push_back(ctx.to_m);
  for (int k = 0; k < n; ++k) {
    if (borders[k + 1] - borders[k] <= buffer + w) {
      out.status = {PlanStatus::Code::kNotApplicable,
                    "section " + std::to_string(k + 1) + " (" +
                        length(ctx.options, borders[k + 1] - borders[k]) +
                        ") is too narrow for a buffer zone and a gantry"};
      return out;
    }
  }
  // Every section gets a buffer zone at its left border. Where a nozzle would finish
  // its buffer before its right neighbour finishes its own, an auxiliary zone next to
  // its buffer keeps it busy (and away from the border) long enough.
  std::vector<std::vector<double>> widths(n, std::vector<double>{buffer});
  Zoned z = zoned_sections(ctx, division, widths, {"buffer", "auxiliary"});
  for (int k = 0; k + 1 < n; ++k) {
    const double own = z.zone_time_s[k][0], next = z.zone_time_s[k + 1][0];
    if (own > next) continue;
    double aux = 0.0;
    bool enough = false;
    while (!enough) {
      aux += 0.25 * w;
      if (borders[k] + buffer + aux >= borders[k + 1] - w) {
        out.status = {PlanStatus::Code::kNotApplicable,
                      "section " + std::to_string(k + 1) +
                          " has no room for an auxiliary zone long enough (buffer " + seconds(own) +
                          " against its neighbour's " + seconds(next) + ")"};
        return out;
      }
      if (PlanStatus late = stop_status(ctx, "sizing the auxiliary zones"); !late) {
        out.status = std::move(late);
        return out;
      }
      widths[k] = {buffer, aux};
      z = zoned_sections(ctx, division, widths, {"buffer", "auxiliary"});
      enough = z.zone_time_s[k][0] + z.zone_time_s[k][1] > z.zone_time_s[k + 1][0];
    }
  }
  MethodResult result = checked(ctx, build_paths(ctx, z.cut, z.works, std::vector<int>(n, 0)));
  result.vertices = static_cast<int>(z.cut.layer.points.size());
  if (!result.status) {
    if (PlanStatus late = stop_status(ctx, "the zones' tours"); !late) result.status = late;
  }
  return result;
}

}  // namespace ccbuild::planner::detail
