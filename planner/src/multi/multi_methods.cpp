// The multi-nozzle methods: path cycling (individual and global), buffer zone path
// cycling, auxiliary buffer zone, and waits (delay).

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

Sequence rotated(const Sequence& tour, int by) {
  if (tour.empty()) return tour;
  Sequence out(tour.begin() + by, tour.end());
  out.insert(out.end(), tour.begin(), tour.begin() + by);
  return out;
}

// A section's walls as their own layer, and the map from cut-layer index to local index.
struct SectionModel {
  floors::Layer layer;
  std::vector<int> local_of;  // by cut-layer segment; -1 when not in the section
  std::unique_ptr<CostModel> model;

  SectionModel(const StageContext& ctx, const CutLayer& cut, const std::vector<int>& segments)
      : layer(floors::sub_layer(cut.layer, segments)), local_of(cut.layer.segments.size(), -1) {
    for (std::size_t i = 0; i < segments.size(); ++i) local_of[segments[i]] = static_cast<int>(i);
    if (!segments.empty())
      model = std::make_unique<CostModel>(layer, ctx.machine, ctx.options.planning.metric);
  }
  Sequence local(const Sequence& s) const {
    Sequence out;
    out.reserve(s.size());
    for (const Step& step : s) {
      CCBUILD_CHECK(local_of[step.segment] >= 0, "a nozzle only builds walls of its section");
      out.push_back({local_of[step.segment], step.reversed});
    }
    return out;
  }
};

Eigen::Vector2d park_point(const StageContext& ctx, double rail_at) {
  Eigen::Vector2d lo = ctx.layer.points.empty() ? Eigen::Vector2d::Zero() : ctx.layer.points[0],
                  hi = lo;
  for (const auto& p : ctx.layer.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Eigen::Vector2d c = 0.5 * (lo + hi);
  (ctx.options.rail_axis == RailAxis::kX ? c.x() : c.y()) = rail_at;
  return c;
}

Sequence concatenated(const NozzleWork& work, int cycle) {
  Sequence out;
  for (const auto& block : work.fixed_blocks) out.insert(out.end(), block.begin(), block.end());
  const Sequence w = rotated(work.working, cycle);
  out.insert(out.end(), w.begin(), w.end());
  return out;
}

// When each step's wait begins, from the timing of the cost model.
std::vector<double> step_starts(const Evaluation& e, const Sequence& sequence,
                                const CostModel& model, const std::vector<double>& waits) {
  std::vector<double> starts;
  double t = 0.0;
  std::size_t move = 0;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    starts.push_back(t);
    if (k < waits.size()) t += waits[k];
    if (k > 0) t += e.moves[move++].time_s;
    t +=
        model.layer().segments[sequence[k].segment].length_m / model.machine().deposition_speed_m_s;
  }
  return starts;
}

}  // namespace

std::vector<NozzlePath> build_paths(const StageContext& ctx, const CutLayer& cut,
                                    const std::vector<NozzleWork>& works,
                                    const std::vector<int>& cycles,
                                    const std::vector<std::vector<double>>& waits) {
  std::vector<NozzlePath> paths;
  for (std::size_t k = 0; k < works.size(); ++k) {
    const NozzleWork& work = works[k];
    NozzlePath path;
    path.nozzle = static_cast<int>(k);
    path.section_from_m = work.from_m;
    path.section_to_m = work.to_m;
    path.start_offset = cycles.empty() ? 0 : cycles[k];
    SectionModel section(ctx, cut, work.section_segments);
    const Sequence full = concatenated(work, path.start_offset);
    for (std::size_t b = 0; b < work.fixed_blocks.size(); ++b)
      path.zones.insert(path.zones.end(), work.fixed_blocks[b].size(), work.fixed_names[b]);
    path.zones.insert(path.zones.end(), work.working.size(), "working");
    if (k < waits.size()) path.wait_before_step_s = waits[k];
    if (full.empty()) {
      path.timeline = parked_at(park_point(ctx, 0.5 * (work.from_m + work.to_m)));
    } else {
      path.sequence = section.local(full);
      path.evaluation = section.model->evaluate(path.sequence, PathSpec::closed_tour());
      path.timeline = timeline_of(*section.model, path.sequence, PathSpec::closed_tour(),
                                  path.wait_before_step_s);
      path.step_start_s =
          step_starts(path.evaluation, path.sequence, *section.model, path.wait_before_step_s);
    }
    path.layer = std::move(section.layer);  // the model is not used past this point
    path.finish_s = path.timeline.end_s();
    path.wait_s =
        std::accumulate(path.wait_before_step_s.begin(), path.wait_before_step_s.end(), 0.0);
    path.busy_s = path.finish_s - path.wait_s;
    paths.push_back(std::move(path));
  }
  return paths;
}

std::string verify(const StageContext& ctx, const std::vector<NozzlePath>& paths, double& min_gap) {
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  const int n = static_cast<int>(paths.size());
  min_gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < n; ++k) {
    min_gap = std::min(min_gap, min_gap_m(paths[k].timeline, paths[k + 1].timeline, axis));
    if (const auto c = first_conflict(paths[k].timeline, paths[k + 1].timeline, axis, w))
      return "nozzles " + std::to_string(k + 1) + " and " + std::to_string(k + 2) +
             " collide at t = " + seconds(c->time_s) + " (rail positions " + metres(c->left_m, 2) +
             " and " + metres(c->right_m, 2) + ")";
  }
  // Each gantry must stay where the others leave it room on the rails.
  for (int k = 0; k < n; ++k) {
    const double lo = ctx.rail_min_m + k * w, hi = ctx.rail_max_m - (n - 1 - k) * w;
    for (const auto& p : paths[k].timeline.positions()) {
      const double r = rail_coordinate(p, axis);
      if (r < lo - 1e-9 || r > hi + 1e-9)
        return "nozzle " + std::to_string(k + 1) + " would need rail position " + metres(r, 2) +
               ", outside its reach " + metres(lo, 2) + " to " + metres(hi, 2);
    }
  }
  return "";
}

std::optional<std::vector<int>> compatible_cycles(const StageContext& ctx, const CutLayer& cut,
                                                  const std::vector<NozzleWork>& works,
                                                  std::string& why) {
  const int n = static_cast<int>(works.size());
  std::vector<std::unique_ptr<SectionModel>> sections;
  std::vector<Sequence> prefix(n), working(n);
  std::vector<int> count(n);
  for (int k = 0; k < n; ++k) {
    sections.push_back(std::make_unique<SectionModel>(ctx, cut, works[k].section_segments));
    Sequence fixed;
    for (const auto& block : works[k].fixed_blocks)
      fixed.insert(fixed.end(), block.begin(), block.end());
    prefix[k] = sections[k]->local(fixed);
    working[k] = sections[k]->local(works[k].working);
    count[k] = std::max<int>(1, static_cast<int>(working[k].size()));
  }
  std::vector<std::map<int, Timeline>> cache(n);
  auto timeline = [&](int k, int c) -> const Timeline& {
    auto it = cache[k].find(c);
    if (it != cache[k].end()) return it->second;
    Sequence s = prefix[k];
    const Sequence w = rotated(working[k], c);
    s.insert(s.end(), w.begin(), w.end());
    Timeline t = s.empty() ? parked_at(park_point(ctx, 0.5 * (works[k].from_m + works[k].to_m)))
                           : timeline_of(*sections[k]->model, s, PathSpec::closed_tour());
    return cache[k].emplace(c, std::move(t)).first->second;
  };
  std::vector<std::vector<char>> dead(n);
  for (int k = 0; k < n; ++k) dead[k].assign(count[k], 0);
  std::vector<int> choice(n, 0);
  long checks = 0;
  bool out_of_budget = false;
  // Can nozzles k+1.. be placed, given nozzle k uses cycle c? Results depend only on
  // (k, c) because only neighbours can collide, so failures are remembered.
  std::function<bool(int, int)> extend = [&](int k, int c) -> bool {
    if (k == n - 1) return true;
    for (int c2 = 0; c2 < count[k + 1]; ++c2) {
      if (dead[k + 1][c2]) continue;
      if (++checks > ctx.options.max_cycle_checks || (checks % 64 == 0 && ctx.stop.should_stop())) {
        out_of_budget = true;
        return false;
      }
      if (first_conflict(timeline(k, c), timeline(k + 1, c2), ctx.options.rail_axis,
                         ctx.options.gantry_width_m))
        continue;
      if (extend(k + 1, c2)) {
        choice[k + 1] = c2;
        return true;
      }
      if (out_of_budget) return false;
    }
    dead[k][c] = 1;
    return false;
  };
  for (int c0 = 0; c0 < count[0] && !out_of_budget; ++c0) {
    if (extend(0, c0)) {
      choice[0] = c0;
      return choice;
    }
  }
  why = out_of_budget ? "gave up after " + std::to_string(checks) + " cycle pairs"
                      : "no combination of start points is collision-free (" +
                            std::to_string(checks) + " cycle pairs checked)";
  return std::nullopt;
}

namespace {

std::optional<std::vector<NozzlePath>> checked(const StageContext& ctx,
                                               std::vector<NozzlePath> paths, std::string& why) {
  double gap = 0.0;
  why = verify(ctx, paths, gap);
  if (!why.empty()) return std::nullopt;
  return paths;
}

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

std::optional<std::vector<NozzlePath>> path_cycling(const StageContext& ctx, std::string& why,
                                                    int& vertices) {
  const Sections& s = sections_of(ctx);
  vertices = static_cast<int>(s.cut.layer.points.size());
  const auto cycles = compatible_cycles(ctx, s.cut, s.works, why);
  if (!cycles) return std::nullopt;
  return checked(ctx, build_paths(ctx, s.cut, s.works, *cycles), why);
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

std::optional<std::vector<NozzlePath>> global_path_cycling(const StageContext& ctx,
                                                           std::string& why, int& vertices) {
  const int n = ctx.options.nozzles;
  const double w = ctx.options.gantry_width_m;
  const CutLayer cut = cut_layer(ctx.layer, ctx.options.rail_axis, {});
  vertices = static_cast<int>(cut.layer.points.size());
  std::vector<int> all(cut.layer.segments.size());
  std::iota(all.begin(), all.end(), 0);
  const Sequence tour = closed_tour(cut.layer, all, ctx);
  if (static_cast<int>(tour.size()) < n) {
    why = "the layer has fewer walls (" + std::to_string(tour.size()) + ") than nozzles";
    return std::nullopt;
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
    why = "no cut of the tour into " + std::to_string(n) + " balanced pieces was found";
    return std::nullopt;
  }
  // 3. Path cycling on the pieces, the best-ranked split first.
  std::string first_why;
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
    std::string reason;
    if (const auto cycles = compatible_cycles(ctx, cut, works, reason))
      if (auto paths = checked(ctx, build_paths(ctx, cut, works, *cycles), reason)) return paths;
    if (first_why.empty()) {
      first_why = reason;
      if (split.shortfall_m > 1e-9)
        first_why += "; the best split's pieces are " + metres(split.shortfall_m, 2) +
                     " short of a gantry width apart along the rails";
    }
    if (ctx.stop.should_stop()) break;
  }
  why = first_why + " (" + std::to_string(ranked.size()) + " balanced splits of the tour tried)";
  return std::nullopt;
}

std::optional<std::vector<NozzlePath>> buffer_zone_path_cycling(const StageContext& ctx,
                                                                std::string& why, int& vertices) {
  const int n = ctx.options.nozzles;
  const double buffer = ctx.options.buffer_width_factor * ctx.options.gantry_width_m;
  const Division& division = divide(ctx);
  // A buffer zone at every inner border, on the right-hand section's side.
  std::vector<std::vector<double>> widths(n);
  for (int k = 1; k < n; ++k) {
    const double section = (k == n - 1 ? ctx.to_m : division.cuts[k]) - division.cuts[k - 1];
    if (section <= buffer) {
      why = "section " + std::to_string(k + 1) + " (" + metres(section, 2) +
            ") is not wider than its buffer zone (" + metres(buffer, 2) + ")";
      return std::nullopt;
    }
    widths[k] = {buffer};
  }
  const Zoned z = zoned_sections(ctx, division, widths, {"buffer"});
  vertices = static_cast<int>(z.cut.layer.points.size());
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
      why = "buffer zone of section " + std::to_string(k + 1) + " holds " + seconds(b) +
            " of its " + seconds(whole) + " of work (must be under half)";
      return std::nullopt;
    }
  }
  const auto cycles = compatible_cycles(ctx, z.cut, z.works, why);
  if (!cycles) return std::nullopt;
  return checked(ctx, build_paths(ctx, z.cut, z.works, *cycles), why);
}

std::optional<std::vector<NozzlePath>> aux_buffer_zone(const StageContext& ctx, std::string& why,
                                                       int& vertices) {
  const int n = ctx.options.nozzles;
  const double w = ctx.options.gantry_width_m;
  const double buffer = ctx.options.buffer_width_factor * w;
  const Division& division = divide(ctx);
  std::vector<double> borders{ctx.from_m};
  borders.insert(borders.end(), division.cuts.begin(), division.cuts.end());
  borders.push_back(ctx.to_m);
  for (int k = 0; k < n; ++k) {
    if (borders[k + 1] - borders[k] <= buffer + w) {
      why = "section " + std::to_string(k + 1) + " (" + metres(borders[k + 1] - borders[k], 2) +
            ") is too narrow for a buffer zone and a gantry";
      return std::nullopt;
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
        why = "section " + std::to_string(k + 1) +
              " has no room for an auxiliary zone long enough (buffer " + seconds(own) +
              " against its neighbour's " + seconds(next) + ")";
        return std::nullopt;
      }
      widths[k] = {buffer, aux};
      z = zoned_sections(ctx, division, widths, {"buffer", "auxiliary"});
      enough = z.zone_time_s[k][0] + z.zone_time_s[k][1] > z.zone_time_s[k + 1][0];
    }
  }
  vertices = static_cast<int>(z.cut.layer.points.size());
  return checked(ctx, build_paths(ctx, z.cut, z.works, std::vector<int>(n, 0)), why);
}

namespace {

double stage_time_s(const std::vector<NozzlePath>& paths) {
  double t = 0.0;
  for (const auto& p : paths) t = std::max(t, p.finish_s);
  return t;
}

// Delay, alternative 1: waits where needed. Take the earliest conflict and make one of the
// two nozzles hold before the step it was on (or a few steps earlier), for the shortest
// hold after which it can finish that step without meeting either neighbour; failing
// that, the shortest hold that at least moves the conflict later.
std::optional<std::vector<NozzlePath>> with_waits(const StageContext& ctx, const Sections& s,
                                                  const std::vector<int>& cycles,
                                                  std::string& detail) {
  const int n = ctx.options.nozzles;
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  std::vector<std::vector<double>> waits(n);
  for (int k = 0; k < n; ++k) waits[k].assign(s.works[k].working.size(), 0.0);
  auto paths = build_paths(ctx, s.cut, s.works, cycles, waits);
  // Holds that would make the stage longer than all the nozzles' work done one after
  // another are pointless (and a nozzle finished in another's way makes them grow without
  // end): give up there.
  double one_after_another_s = 0.0;
  for (const auto& p : paths) one_after_another_s += p.busy_s;
  // Each nozzle's walls and cost model, kept for the many trial holds.
  std::vector<std::unique_ptr<SectionModel>> models;
  for (int k = 0; k < n; ++k)
    models.push_back(std::make_unique<SectionModel>(ctx, s.cut, s.works[k].section_segments));
  auto earliest = [&](const std::vector<NozzlePath>& p, int& pair) -> std::optional<Conflict> {
    std::optional<Conflict> first;
    for (int k = 0; k + 1 < n; ++k) {
      if (auto c = first_conflict(p[k].timeline, p[k + 1].timeline, axis, w);
          c && (!first || c->time_s < first->time_s)) {
        first = c;
        pair = k;
      }
    }
    return first;
  };
  for (int round = 0; round < 400 && !ctx.stop.should_stop(); ++round) {
    int pair = 0;
    const auto conflict = earliest(paths, pair);
    if (!conflict) {
      std::string problem;
      auto ok = checked(ctx, paths, problem);
      if (ok) {
        double total = 0.0;
        for (const auto& p : paths) total += p.wait_s;
        detail = "delay (" + std::to_string(round) + " waits, " + seconds(total) + " in all)";
      }
      return ok;
    }
    if (conflict->time_s <= 1e-9) return std::nullopt;  // they start too close
    struct Hold {
      double s = std::numeric_limits<double>::infinity();
      int nozzle = -1;
      std::size_t step = 0;
    } finishes, later;  // lets the nozzle finish its step / only moves the conflict later
    for (int y : {pair, pair + 1}) {
      const int o = y == pair ? pair + 1 : pair;
      const auto& starts = paths[y].step_start_s;
      if (starts.empty()) continue;
      std::size_t current = 0;
      while (current + 1 < starts.size() && starts[current + 1] <= conflict->time_s) ++current;
      const double current_end =
          current + 1 < starts.size() ? starts[current + 1] : paths[y].finish_s;
      // Hold before the step in progress; if resting where that step begins is itself in
      // the way, hold a few steps earlier.
      for (std::size_t back = 0; back <= std::min<std::size_t>(current, 6); ++back) {
        const std::size_t step = current - back;
        std::vector<double> holds;
        for (double t : paths[o].timeline.times())
          if (t > starts[step]) holds.push_back(t - starts[step]);
        holds.push_back(paths[o].finish_s - starts[step]);
        std::sort(holds.begin(), holds.end());
        holds.erase(std::unique(holds.begin(), holds.end()), holds.end());
        for (double hold : holds) {
          if (hold <= 0.0 || hold >= finishes.s) break;
          auto trial = waits[y];
          trial[step] += hold;
          const Timeline candidate =
              timeline_of(*models[y]->model, paths[y].sequence, PathSpec::closed_tour(),
                          paths[y].evaluation, trial);
          std::optional<double> next;  // y's first conflict with either neighbour now
          for (int other : {y - 1, y + 1}) {
            if (other < 0 || other >= n) continue;
            const auto& left = other < y ? paths[other].timeline : candidate;
            const auto& right = other < y ? candidate : paths[other].timeline;
            if (auto c = first_conflict(left, right, axis, w); c && (!next || c->time_s < *next))
              next = c->time_s;
          }
          if (!next || *next > current_end + hold + 1e-6) {
            finishes = {hold, y, step};
            break;
          }
          if (*next > conflict->time_s + 1e-6 && hold < later.s) later = {hold, y, step};
        }
      }
    }
    const Hold& chosen = finishes.nozzle >= 0 ? finishes : later;
    if (chosen.nozzle < 0) return std::nullopt;
    waits[chosen.nozzle][chosen.step] += chosen.s;
    auto rebuilt = build_paths(ctx, s.cut, {s.works[chosen.nozzle]}, {cycles[chosen.nozzle]},
                               {waits[chosen.nozzle]});
    rebuilt[0].nozzle = chosen.nozzle;
    paths[chosen.nozzle] = std::move(rebuilt[0]);
    if (paths[chosen.nozzle].finish_s > one_after_another_s) return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::vector<NozzlePath>> delay_method(const StageContext& ctx, std::string& why,
                                                    int& vertices, std::string& detail) {
  const int n = ctx.options.nozzles;
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  const Sections& s = sections_of(ctx);
  vertices = static_cast<int>(s.cut.layer.points.size());
  // Where a nozzle may rest while its neighbours work anywhere in their sections: a
  // gantry width clear of each neighbouring section. Start each tour there (nearest the
  // middle of that interval), so a nozzle holding at its start, or finished there, is
  // out of its neighbours' way.
  std::vector<int> cycles(n, 0);
  std::vector<char> rests_clear(n, 1);
  for (int k = 0; k < n; ++k) {
    const double lo = k > 0 ? s.works[k].from_m + w : -std::numeric_limits<double>::infinity();
    const double hi = k + 1 < n ? s.works[k].to_m - w : std::numeric_limits<double>::infinity();
    // Inside the interval first; then, between two ends, nearest its middle, and at an
    // end of the rails, as far from the one neighbour as possible.
    const double target = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi)
                          : std::isfinite(lo)                    ? s.works[k].to_m
                                                                 : s.works[k].from_m;
    std::pair<double, double> best{std::numeric_limits<double>::infinity(), 0.0};
    for (std::size_t c = 0; c < s.works[k].working.size(); ++c) {
      const Step& step = s.works[k].working[c];
      const auto& seg = s.cut.layer.segments[step.segment];
      const double r =
          rail_coordinate(step.reversed ? s.cut.layer.end_m(seg) : s.cut.layer.start_m(seg), axis);
      const std::pair<double, double> score{std::max({0.0, lo - r, r - hi}), std::abs(r - target)};
      if (score < best) {
        best = score;
        cycles[k] = static_cast<int>(c);
        rests_clear[k] = score.first <= 1e-9;
      }
    }
  }

  // The alternatives; the fastest collision-free one is returned.
  std::optional<std::vector<NozzlePath>> fastest;
  auto consider = [&](std::optional<std::vector<NozzlePath>> paths, std::string what) {
    if (paths && (!fastest || stage_time_s(*paths) < stage_time_s(*fastest))) {
      fastest = std::move(paths);
      detail = std::move(what);
    }
  };

  // 1. Waits.
  {
    std::string what;
    auto paths = with_waits(ctx, s, cycles, what);
    consider(std::move(paths), what);
  }

  // 2. Turns: even-numbered nozzles work while odd ones hold at their start points, then
  //    the other way round. Safe when every holding nozzle rests a gantry width clear of
  //    its working neighbours' sections (the tours start there when they can).
  if (std::all_of(rests_clear.begin(), rests_clear.end(), [](char c) { return c != 0; })) {
    const auto alone = build_paths(ctx, s.cut, s.works, cycles);
    std::vector<std::vector<double>> turn(n);
    double even_finish = 0.0;
    for (int k = 0; k < n; k += 2) even_finish = std::max(even_finish, alone[k].busy_s);
    for (int k = 0; k < n; ++k) {
      turn[k].assign(s.works[k].working.size(), 0.0);
      if (k % 2 == 1 && !turn[k].empty()) turn[k][0] = even_finish;
    }
    std::string problem;
    consider(checked(ctx, build_paths(ctx, s.cut, s.works, cycles, turn), problem),
             "delay (odd nozzles wait for even ones: " + seconds(even_finish) + ")");
  }

  // 3. One nozzle builds the stage alone, on its single-nozzle tour of the uncut walls
  //    (planned as a single nozzle would plan it); the others park clear of the layout at
  //    the ends of the rails.
  {
    const CutLayer whole = cut_layer(ctx.layer, axis, {});
    NozzleWork all;
    all.from_m = ctx.from_m;
    all.to_m = ctx.to_m;
    all.section_segments.resize(whole.layer.segments.size());
    std::iota(all.section_segments.begin(), all.section_segments.end(), 0);
    bool planned = false;
    for (int j = 0; j < n; ++j) {
      std::vector<NozzleWork> works(n);
      bool fits = true;
      for (int k = 0; k < n; ++k) {
        if (k == j) continue;
        // Left of the worker: pack against the left end of the rails; right: the right end.
        const double at = k < j ? ctx.rail_min_m + k * w : ctx.rail_max_m - (n - 1 - k) * w;
        works[k].from_m = works[k].to_m = at;
        if ((k < j && at > ctx.from_m - w) || (k > j && at < ctx.to_m + w)) fits = false;
      }
      if (!fits) continue;
      if (!planned) {
        PlanOptions o = ctx.options.planning;
        o.algorithm = Algorithm::kCcTsp;
        o.path = PathSpec::closed_tour();
        o.time_limit_s = std::max(0.05, std::min(o.time_limit_s, ctx.stop.remaining_s()));
        all.working = plan_layer(whole.layer, ctx.machine, o).sequence;
        planned = true;
      }
      works[j] = all;
      std::string problem;
      if (auto ok = checked(ctx, build_paths(ctx, whole, works, std::vector<int>(n, 0)), problem)) {
        consider(std::move(ok),
                 "delay (nozzle " + std::to_string(j + 1) + " alone, the others parked)");
        break;
      }
    }
  }
  if (fastest) return fastest;
  why =
      "no waits resolve the conflicts, no turns are safe (a nozzle cannot rest a gantry width "
      "clear of its neighbours' sections), and the rails leave no room to park";
  return std::nullopt;
}

}  // namespace ccbuild::planner::detail
