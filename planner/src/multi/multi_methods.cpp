// The multi-nozzle methods: path cycling (individual and global), buffer zone path
// cycling, auxiliary buffer zone, and waits (delay).

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
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

std::optional<std::vector<NozzlePath>> global_path_cycling(const StageContext& ctx,
                                                           std::string& why, int& vertices) {
  const int n = ctx.options.nozzles;
  const CutLayer cut = cut_layer(ctx.layer, ctx.options.rail_axis, {});
  vertices = static_cast<int>(cut.layer.points.size());
  std::vector<int> all(cut.layer.segments.size());
  std::iota(all.begin(), all.end(), 0);
  Sequence tour = closed_tour(cut.layer, all, ctx);
  // Each piece becomes a closed path of its own, so the moves between pieces are
  // dropped: start the tour after its longest move, then choose the split points that
  // make the longest piece (deposition, inner moves, return to its start) shortest.
  const CostModel model(cut.layer, ctx.machine, ctx.options.planning.metric);
  {
    const Evaluation e = model.evaluate(tour, PathSpec::closed_tour());
    std::size_t longest = 0;  // moves[k] leads to step k + 1; the last is the closing move
    for (std::size_t k = 0; k < e.moves.size(); ++k)
      if (e.moves[k].time_s > e.moves[longest].time_s) longest = k;
    std::rotate(tour.begin(), tour.begin() + (longest + 1) % tour.size(), tour.end());
  }
  const Evaluation e = model.evaluate(tour, PathSpec::closed_tour());
  const double deposition_speed = ctx.machine.deposition_speed_m_s;
  auto closing_s = [&](std::size_t first, std::size_t last) {
    return model.move_time_s(model.step_end_m(tour[last]), model.step_start_m(tour[first]), 0.0,
                             false);
  };
  auto pack = [&](double limit, std::vector<std::size_t>* starts) {
    int count = 1;
    std::size_t first = 0;
    double inner = cut.layer.segments[tour[0].segment].length_m / deposition_speed;
    if (starts) starts->assign(1, 0);
    for (std::size_t k = 1; k < tour.size(); ++k) {
      const double add =
          e.moves[k - 1].time_s + cut.layer.segments[tour[k].segment].length_m / deposition_speed;
      if (inner + add + closing_s(first, k) > limit) {
        ++count;
        first = k;
        inner = cut.layer.segments[tour[k].segment].length_m / deposition_speed;
        if (starts) starts->push_back(k);
      } else {
        inner += add;
      }
    }
    return count;
  };
  double lo_t = 0.0, hi_t = e.layer_time_s + 1.0;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo_t + hi_t);
    (pack(mid, nullptr) <= n ? hi_t : lo_t) = mid;
  }
  std::vector<std::size_t> starts;
  pack(hi_t, &starts);
  std::vector<Sequence> pieces;
  for (std::size_t p = 0; p < starts.size(); ++p) {
    const std::size_t end = p + 1 < starts.size() ? starts[p + 1] : tour.size();
    pieces.emplace_back(tour.begin() + starts[p], tour.begin() + end);
  }
  // Pieces go to gantries in the order of their mean rail position.
  auto centre = [&](const Sequence& p) {
    if (p.empty()) return 0.0;
    double sum = 0.0;
    for (const Step& step : p) {
      const auto& seg = cut.layer.segments[step.segment];
      sum += rail_coordinate(0.5 * (cut.layer.start_m(seg) + cut.layer.end_m(seg)),
                             ctx.options.rail_axis);
    }
    return sum / p.size();
  };
  std::stable_sort(pieces.begin(), pieces.end(),
                   [&](const Sequence& a, const Sequence& b) { return centre(a) < centre(b); });
  std::vector<NozzleWork> works;
  for (const Sequence& p : pieces) {
    NozzleWork w;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Step& step : p) {
      const auto& seg = cut.layer.segments[step.segment];
      w.section_segments.push_back(step.segment);
      for (const auto& q : {cut.layer.start_m(seg), cut.layer.end_m(seg)}) {
        lo = std::min(lo, rail_coordinate(q, ctx.options.rail_axis));
        hi = std::max(hi, rail_coordinate(q, ctx.options.rail_axis));
      }
    }
    w.from_m = p.empty() ? ctx.from_m : lo;
    w.to_m = p.empty() ? ctx.from_m : hi;
    w.working = p;
    works.push_back(std::move(w));
  }
  const auto cycles = compatible_cycles(ctx, cut, works, why);
  if (!cycles) return std::nullopt;
  return checked(ctx, build_paths(ctx, cut, works, *cycles), why);
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
  std::vector<std::vector<double>> waits(n);
  for (int k = 0; k < n; ++k) waits[k].assign(s.works[k].working.size(), 0.0);

  // 1. Waits where needed: take the earliest conflict and make one of the two nozzles
  //    hold before the step it was on, just long enough that the conflict moves later;
  //    choose the shorter hold.
  auto paths = build_paths(ctx, s.cut, s.works, cycles, waits);
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
      if (auto ok = checked(ctx, paths, problem)) {
        double total = 0.0;
        for (const auto& p : paths) total += p.wait_s;
        detail = "delay (" + std::to_string(round) + " waits, " + seconds(total) + " in all)";
        return ok;
      }
      break;
    }
    if (conflict->time_s <= 1e-9) break;  // they start too close: no hold can help
    double best_hold = std::numeric_limits<double>::infinity();
    int best_nozzle = -1;
    std::size_t best_step = 0;
    for (int y : {pair, pair + 1}) {
      const int o = y == pair ? pair + 1 : pair;
      const auto& starts = paths[y].step_start_s;
      if (starts.empty()) continue;
      std::size_t current = 0;
      while (current + 1 < starts.size() && starts[current + 1] <= conflict->time_s) ++current;
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
          if (hold <= 0.0 || hold >= best_hold) continue;
          auto trial = waits[y];
          trial[step] += hold;
          const Timeline candidate =
              timeline_of(*models[y]->model, paths[y].sequence, PathSpec::closed_tour(),
                          paths[y].evaluation, trial);
          // Progress: nothing involving y may now conflict at or before the old conflict.
          bool progress = true;
          for (int other : {y - 1, y + 1}) {
            if (other < 0 || other >= n) continue;
            const auto& left = other < y ? paths[other].timeline : candidate;
            const auto& right = other < y ? candidate : paths[other].timeline;
            if (auto c = first_conflict(left, right, axis, w);
                c && c->time_s <= conflict->time_s + 1e-6)
              progress = false;
          }
          if (progress) {
            best_hold = hold;
            best_nozzle = y;
            best_step = step;
            break;
          }
        }
      }
    }
    if (best_nozzle < 0) break;
    waits[best_nozzle][best_step] += best_hold;
    auto rebuilt = build_paths(ctx, s.cut, {s.works[best_nozzle]}, {cycles[best_nozzle]},
                               {waits[best_nozzle]});
    rebuilt[0].nozzle = best_nozzle;
    paths[best_nozzle] = std::move(rebuilt[0]);
  }

  // 2. Turns: even-numbered nozzles work while odd ones hold at their start points, then
  //    the other way round. Safe when every holding nozzle rests a gantry width clear of
  //    its working neighbours' sections (the tours start there when they can).
  if (std::all_of(rests_clear.begin(), rests_clear.end(), [](char c) { return c != 0; })) {
    std::vector<std::vector<double>> turn(n);
    double even_finish = 0.0;
    for (int k = 0; k < n; k += 2) even_finish = std::max(even_finish, paths[k].busy_s);
    for (int k = 0; k < n; ++k) {
      turn[k].assign(s.works[k].working.size(), 0.0);
      if (k % 2 == 1 && !turn[k].empty()) turn[k][0] = even_finish;
    }
    std::string problem;
    if (auto ok = checked(ctx, build_paths(ctx, s.cut, s.works, cycles, turn), problem)) {
      detail = "delay (odd nozzles wait for even ones: " + seconds(even_finish) + ")";
      return ok;
    }
  }

  // 3. One nozzle builds everything; the others park clear of the layout on the rails.
  {
    std::vector<int> everything(s.cut.layer.segments.size());
    std::iota(everything.begin(), everything.end(), 0);
    NozzleWork all;
    all.from_m = ctx.from_m;
    all.to_m = ctx.to_m;
    all.section_segments = everything;
    all.working = closed_tour(s.cut.layer, everything, ctx);
    for (int j = 0; j < n; ++j) {
      std::vector<NozzleWork> works(n);
      bool fits = true;
      for (int k = 0; k < n; ++k) {
        if (k == j) {
          works[k] = all;
          continue;
        }
        // Left of the worker: pack against the left end of the rails; right: the right end.
        const double at = k < j ? ctx.rail_min_m + k * w : ctx.rail_max_m - (n - 1 - k) * w;
        works[k].from_m = works[k].to_m = at;
        if ((k < j && at > ctx.from_m - w) || (k > j && at < ctx.to_m + w)) fits = false;
      }
      if (!fits) continue;
      std::string problem;
      if (auto ok = checked(ctx, build_paths(ctx, s.cut, works, std::vector<int>(n, 0)), problem)) {
        detail = "delay (nozzle " + std::to_string(j + 1) + " alone, the others parked)";
        return ok;
      }
    }
  }
  why =
      "no waits resolve the conflicts, no turns are safe (a nozzle cannot rest a gantry width "
      "clear of its "
      "neighbours' sections), and the rails leave no room to park";
  return std::nullopt;
}

}  // namespace ccbuild::planner::detail
