#include "ccbuild/dispatch/replan.hpp"

#include <algorithm>
#include <cmath>

namespace ccbuild::dispatch {

std::vector<LaidEnd> laid_ends(const machine::TimedPath& path, double started_s, int stopped_at) {
  std::vector<LaidEnd> out;
  for (const auto& [k, wall] : machine::piece_ends(path))
    if (stopped_at < 0 || static_cast<int>(k) <= stopped_at)
      out.push_back({wall, path.x_m[k], path.y_m[k], started_s + path.t_s[k]});
  return out;
}

StartWindow& StartWindow::intersect(const StartWindow& other) {
  earliest_s = std::max(earliest_s, other.earliest_s);
  latest_s = std::min(latest_s, other.latest_s);
  ends_covered += other.ends_covered;
  newest_below_s = std::max(newest_below_s, other.newest_below_s);
  return *this;
}

StartWindow start_window(const machine::TimedPath& path, const std::vector<LaidEnd>& below,
                         double min_interval_s, double max_interval_s) {
  StartWindow w;
  for (const auto& [k, wall] : machine::piece_ends(path)) {
    bool covers = false;
    for (const LaidEnd& e : below) {
      if (e.wall != wall || std::abs(e.x_m - path.x_m[k]) > machine::kPieceEndMatch_m ||
          std::abs(e.y_m - path.y_m[k]) > machine::kPieceEndMatch_m)
        continue;
      // Covered at start + t_k: start + t_k - laid within [min, max].
      w.earliest_s = std::max(w.earliest_s, e.t_s + min_interval_s - path.t_s[k]);
      w.latest_s = std::min(w.latest_s, e.t_s + max_interval_s - path.t_s[k]);
      w.newest_below_s = std::max(w.newest_below_s, e.t_s);
      covers = true;
    }
    w.ends_covered += covers;
  }
  return w;
}

}  // namespace ccbuild::dispatch
