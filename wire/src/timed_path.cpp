#include "ccbuild/wire/timed_path.hpp"

#include "ccbuild/wire/path_chunks.hpp"

#include <algorithm>

namespace ccbuild::wire {

void TimedPath::push_back(double t, double x, double y, double z, double heading, bool deposits,
                          std::int64_t wall_id, std::int32_t piece_number) {
  t_s.push_back(t);
  x_m.push_back(x);
  y_m.push_back(y);
  z_m.push_back(z);
  heading_rad.push_back(heading);
  extruding.push_back(deposits);
  wall.push_back(wall_id);
  piece.push_back(piece_number);
}

std::array<double, 4> position_at(const TimedPath& p, double t_s) {
  const auto it = std::upper_bound(p.t_s.begin(), p.t_s.end(), t_s);
  const std::size_t k = static_cast<std::size_t>(it - p.t_s.begin());
  if (k == 0 || k >= p.size()) {
    const std::size_t j = k == 0 ? 0 : p.size() - 1;
    return {p.x_m[j], p.y_m[j], p.z_m[j], p.heading_rad[j]};
  }
  const double span = p.t_s[k] - p.t_s[k - 1];
  const double f = span > 0.0 ? (t_s - p.t_s[k - 1]) / span : 1.0;
  const auto lerp = [&](const std::vector<double>& v) { return v[k - 1] + f * (v[k] - v[k - 1]); };
  return {lerp(p.x_m), lerp(p.y_m), lerp(p.z_m), lerp(p.heading_rad)};
}

void append_waypoint(TimedPath& path, const ccbuild_lcm::ccbuild_path_chunk_t& c, int k) {
  path.push_back(c.t_s[k], c.x_m[k], c.y_m[k], c.z_m[k], c.heading_rad[k], c.extruding[k],
                 c.wall[k], c.piece[k]);
}

std::vector<ccbuild_lcm::ccbuild_path_chunk_t> chunks_of(const TimedPath& path,
                                                         const std::string& machine_id) {
  using ccbuild_lcm::ccbuild_path_chunk_t;
  const int total = static_cast<int>(path.size());
  const int per = ccbuild_path_chunk_t::MAX_POINTS;
  const int count = (total + per - 1) / per;
  std::vector<ccbuild_path_chunk_t> out;
  for (int c = 0; c < count; ++c) {
    ccbuild_path_chunk_t chunk;
    chunk.utime = 0;
    chunk.machine_id = machine_id;
    chunk.job_id = 0;
    chunk.seq = 0;
    chunk.chunk_index = c;
    chunk.chunk_count = count;
    const auto from = static_cast<std::ptrdiff_t>(c) * per;
    const auto to = std::min<std::ptrdiff_t>(total, from + per);
    chunk.n = static_cast<std::int32_t>(to - from);
    auto slice = [&](const auto& column, auto& into) {
      into.assign(column.begin() + from, column.begin() + to);
    };
    slice(path.t_s, chunk.t_s);
    slice(path.x_m, chunk.x_m);
    slice(path.y_m, chunk.y_m);
    slice(path.z_m, chunk.z_m);
    slice(path.heading_rad, chunk.heading_rad);
    slice(path.extruding, chunk.extruding);
    slice(path.wall, chunk.wall);
    slice(path.piece, chunk.piece);
    out.push_back(std::move(chunk));
  }
  return out;
}

TimedPath path_of(const std::vector<ccbuild_lcm::ccbuild_path_chunk_t>& chunks) {
  TimedPath path;
  for (const auto& c : chunks)
    for (int k = 0; k < c.n; ++k) append_waypoint(path, c, k);
  return path;
}

void add_deposits(rules::DepositIndex& index, const TimedPath& path, double origin_s,
                  int stopped_at) {
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    if (stopped_at >= 0 && static_cast<int>(k) + 1 > stopped_at) break;
    if (!path.extruding[k]) continue;
    index.add(path.wall[k], {Eigen::Vector2d(path.x_m[k], path.y_m[k]),
                             Eigen::Vector2d(path.x_m[k + 1], path.y_m[k + 1]),
                             origin_s + path.t_s[k], origin_s + path.t_s[k + 1], path.piece[k]});
  }
}

}  // namespace ccbuild::wire
