#include "ccbuild/orchestrator/dispatch_jobs.hpp"

#include <algorithm>
#include <array>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/timed_path.hpp"

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

/// Schedule waypoints (JSON) as a timed path.
machine::TimedPath timed_path(const json& waypoints) {
  machine::TimedPath path;
  for (const json& w : waypoints)
    path.push_back(w.at("t_s").get<double>(), w.at("x_m").get<double>(), w.at("y_m").get<double>(),
                   w.at("z_m").get<double>(), w.at("heading_rad").get<double>(),
                   w.at("extruding").get<bool>(), w.at("wall").get<std::int64_t>(),
                   w.at("piece").get<std::int32_t>());
  return path;
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
    // Nozzle -> its last position (x, y, z, heading), if it deposited the layer before.
    std::map<int, std::array<double, 4>> last, ending;
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
        machine::TimedPath path = timed_path(n.at("waypoints"));
        if (path.size() == 0) continue;
        for (double& z_m : path.z_m) z_m += dz_m;  // this layer's height
        // The move from where this nozzle ended to where it starts, in a straight line.
        const auto from = last.find(nozzle);
        if (from != last.end() && move_s > 0.0) {
          const auto& [x0, y0, z0, h0] = from->second;
          machine::TimedPath move;
          move.push_back(0.0, x0, y0, z0, h0, false, 0, 0);
          move.push_back(move_s, path.x_m[0], path.y_m[0], path.z_m[0], path.heading_rad[0], false,
                         0, 0);
          DispatchJob t;
          t.job = job_of(
              ccbuild_job_t::TRAVEL, gantry_id(nozzle), waited_from_s - move_s, move_s, floor,
              layer, nozzle, "",
              printf_string("move to floor %d layer %d, nozzle %d", floor, layer, nozzle + 1));
          t.chunks = machine::chunks_of(move, t.job.machine_id);
          t.job.chunk_count = 1;
          t.job.point_count = 2;
          jobs.push_back(std::move(t));
        }
        const std::size_t end = path.size() - 1;
        ending[nozzle] = {path.x_m[end], path.y_m[end], path.z_m[end], path.heading_rad[end]};
        const double duration_s = path.t_s.back();
        DispatchJob d;
        d.job = job_of(ccbuild_job_t::DEPOSIT, gantry_id(nozzle), start_s, duration_s, floor, layer,
                       nozzle, key,
                       printf_string("floor %d layer %d, nozzle %d", floor, layer, nozzle + 1));
        d.chunks = machine::chunks_of(path, d.job.machine_id);
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
