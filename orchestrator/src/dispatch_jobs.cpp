#include "ccbuild/orchestrator/dispatch_jobs.hpp"

#include <algorithm>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::orchestrator {
namespace {

using ccbuild_lcm::ccbuild_job_t;
using ccbuild_lcm::ccbuild_path_chunk_t;
using nlohmann::json;

ccbuild_job_t job_of(std::int8_t kind, const std::string& machine, double start_s,
                     double duration_s, int floor, int layer, int nozzle, const std::string& plan,
                     const std::string& detail) {
  ccbuild_job_t j;
  j.utime = 0;
  j.machine_id = machine;
  j.job_id = 0;
  j.seq = 0;
  j.kind = kind;
  j.floor = floor;
  j.layer = layer;
  j.nozzle = nozzle;
  j.start_s = start_s;
  j.duration_s = duration_s;
  j.plan = plan;
  j.detail = detail;
  j.chunk_count = 0;
  j.point_count = 0;
  return j;
}

/// A timed path in chunks of at most MAX_POINTS waypoints (times from the job's start).
std::vector<ccbuild_path_chunk_t> chunks_of(const json& waypoints, const std::string& machine) {
  const int total = static_cast<int>(waypoints.size());
  const int per = ccbuild_path_chunk_t::MAX_POINTS;
  const int count = (total + per - 1) / per;
  std::vector<ccbuild_path_chunk_t> out;
  for (int c = 0; c < count; ++c) {
    ccbuild_path_chunk_t chunk;
    chunk.utime = 0;
    chunk.machine_id = machine;
    chunk.job_id = 0;
    chunk.seq = 0;
    chunk.chunk_index = c;
    chunk.chunk_count = count;
    const int from = c * per, to = std::min(total, from + per);
    chunk.n = to - from;
    for (int k = from; k < to; ++k) {
      const json& w = waypoints[k];
      chunk.t_s.push_back(w.at("t_s").get<double>());
      chunk.x_m.push_back(w.at("x_m").get<double>());
      chunk.y_m.push_back(w.at("y_m").get<double>());
      chunk.z_m.push_back(w.at("z_m").get<double>());
      chunk.heading_rad.push_back(w.at("heading_rad").get<double>());
      chunk.extruding.push_back(w.at("extruding").get<bool>());
      chunk.wall.push_back(w.at("wall").get<std::int64_t>());
      chunk.piece.push_back(w.at("piece").get<std::int32_t>());
    }
    out.push_back(std::move(chunk));
  }
  return out;
}

}  // namespace

std::string gantry_id(int nozzle) {
  return "gantry-" + std::to_string(nozzle + 1);
}

std::vector<DispatchJob> jobs_of_schedule(const json& schedule) {
  std::vector<DispatchJob> jobs;
  try {
    const json& plans = schedule.at("plans");
    const json machine = schedule.value("inputs", json::object()).value("machine", json::object());
    const double purge_s = machine.value("purge_s", 0.0);
    // Nozzle -> its last waypoint, if it deposited the layer before this one.
    std::map<int, json> last, ending;
    for (const json& l : schedule.at("layers")) {
      const std::string key = l.at("plan").get<std::string>();
      const json& plan = plans.at(key);
      const int floor = l.at("floor").get<int>(), layer = l.at("layer").get<int>();
      const double start_s = l.at("start_s").get<double>();
      const double dz_m = l.at("z_m").get<double>() - plan.at("z_top_m").get<double>();
      // Before the layer: the move to it, the wait (the machine idle, with its reasons),
      // then the purge (an event of its own).
      const double wait_s = l.value("wait_before_s", 0.0);
      const double move_s = l.value("move_before_s", 0.0);
      const double waited_from_s =
          start_s - (l.value("purge_before", false) ? purge_s : 0.0) - wait_s;
      if (wait_s > 0.0) {
        std::string why;
        for (const json& r : l.value("wait_reasons", json::array()))
          why += (why.empty() ? "" : "; ") + r.value("detail", std::string());
        jobs.push_back(
            {job_of(ccbuild_job_t::WAIT, gantry_id(0), waited_from_s, wait_s, floor, layer, -1, "",
                    printf_string("wait before floor %d layer %d: %s", floor, layer, why.c_str())),
             {}});
      }
      for (const json& n : plan.at("nozzles")) {
        const int nozzle = n.at("nozzle").get<int>();
        json path = n.at("waypoints");
        if (path.empty()) continue;
        for (json& w : path) w["z_m"] = w.at("z_m").get<double>() + dz_m;  // this layer's height
        // The move from where this nozzle ended to where it starts, in a straight line.
        const auto from = last.find(nozzle);
        if (from != last.end() && move_s > 0.0) {
          json a = from->second, b = path.front();
          for (json* w : {&a, &b}) {
            (*w)["extruding"] = false;
            (*w)["wall"] = 0;
            (*w)["piece"] = 0;
          }
          a["t_s"] = 0.0;
          b["t_s"] = move_s;
          DispatchJob t;
          t.job = job_of(
              ccbuild_job_t::TRAVEL, gantry_id(nozzle), waited_from_s - move_s, move_s, floor,
              layer, nozzle, "",
              printf_string("move to floor %d layer %d, nozzle %d", floor, layer, nozzle + 1));
          t.chunks = chunks_of(json::array({a, b}), t.job.machine_id);
          t.job.chunk_count = 1;
          t.job.point_count = 2;
          jobs.push_back(std::move(t));
        }
        ending[nozzle] = path.back();
        const double duration_s = path.back().at("t_s").get<double>();
        DispatchJob d;
        d.job = job_of(ccbuild_job_t::DEPOSIT, gantry_id(nozzle), start_s, duration_s, floor, layer,
                       nozzle, key,
                       printf_string("floor %d layer %d, nozzle %d", floor, layer, nozzle + 1));
        d.chunks = chunks_of(path, d.job.machine_id);
        d.job.chunk_count = static_cast<std::int32_t>(d.chunks.size());
        d.job.point_count = static_cast<std::int32_t>(path.size());
        jobs.push_back(std::move(d));
      }
      last.swap(ending);  // a nozzle idle for a layer moves without a job (as planned)
      ending.clear();
    }
    for (const json& e : schedule.at("events")) {
      const std::string kind = e.at("kind").get<std::string>();
      const int floor = e.at("floor").get<int>(), layer = e.at("after_layer").get<int>();
      const double start_s = e.at("start_s").get<double>(), end_s = e.at("end_s").get<double>();
      const std::string detail = e.at("detail").get<std::string>();
      if (kind == "climb") {
        double t = start_s;
        for (const json& p : e.at("climb").at("phases")) {
          const double d = p.at("duration_s").get<double>();
          const std::string unit =
              p.at("unit").is_string() ? " " + p.at("unit").get<std::string>() : "";
          jobs.push_back({job_of(ccbuild_job_t::CLIMB_PHASE, gantry_id(0), t, d, floor, layer, -1,
                                 "", detail + ": " + p.at("kind").get<std::string>() + unit),
                          {}});
          t += d;
        }
        continue;
      }
      const std::int8_t code = kind == "pipe"    ? ccbuild_job_t::PIPE
                               : kind == "slab"  ? ccbuild_job_t::SLAB
                               : kind == "purge" ? ccbuild_job_t::PURGE
                                                 : ccbuild_job_t::WAIT;
      jobs.push_back(
          {job_of(code, gantry_id(0), start_s, end_s - start_s, floor, layer, -1, "", detail), {}});
    }
  } catch (const json::exception& error) {
    throw InputError("", 0, "schedule", std::string("lacks what a job needs: ") + error.what());
  }
  // Schedule order: by planned start, then gantry; stable for equal keys.
  std::stable_sort(jobs.begin(), jobs.end(), [](const DispatchJob& a, const DispatchJob& b) {
    if (a.job.start_s != b.job.start_s) return a.job.start_s < b.job.start_s;
    return a.job.machine_id < b.job.machine_id;
  });
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    jobs[k].job.job_id = static_cast<std::int64_t>(10 * (k + 1));
    for (auto& c : jobs[k].chunks) c.job_id = jobs[k].job.job_id;
  }
  return jobs;
}

}  // namespace ccbuild::orchestrator
