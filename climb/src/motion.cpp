#include "motion.hpp"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

namespace ccbuild::climb::detail {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// OMPL's generators are seeded from one process-wide seed; these take a local seed so
// that the same problem and seed give the same path whatever was planned before.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint_fast32_t seed)
      : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededRRTConnect : public og::RRTConnect {
 public:
  SeededRRTConnect(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed)
      : og::RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

class SeededSimplifier : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed)
      : og::PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

std::vector<double> values(const ob::State* state, std::size_t n) {
  const auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  return std::vector<double>(s->values, s->values + n);
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(d);
}

// What a refusal is grouped by: its obstacle, or its whole reason (a limit).
const std::string& obstacle_of(const Verdict& v) {
  return v.obstacle.empty() ? v.why : v.obstacle;
}

// The first invalid state between a and b at steps of `step`; ok when there is none. With
// `all`, every distinct obstacle along the way (up to three), to say what blocks a motion.
Verdict first_invalid(const MotionProblem& p, const std::vector<double>& a,
                      const std::vector<double>& b, double step, bool all = false) {
  const int n = std::max(1, static_cast<int>(std::ceil(distance(a, b) / step)));
  std::vector<double> s(a.size());
  Verdict out;
  std::vector<std::string> seen;
  int reasons = 0;
  for (int i = 0; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    for (std::size_t k = 0; k < a.size(); ++k) s[k] = a[k] + f * (b[k] - a[k]);
    Verdict v;
    for (std::size_t k = 0; k < a.size() && v.ok; ++k)
      if (s[k] < p.lower[k] - 1e-9 || s[k] > p.upper[k] + 1e-9)
        v = Verdict::refused("joint " + std::to_string(k) + " leaves its limits");
    if (v.ok) v = p.valid(s);
    if (v.ok) continue;
    if (!all) return v;
    // One cause per obstacle: a leg sliding along a wall touches it with several links.
    const std::string& obstacle = obstacle_of(v);
    if (std::find(seen.begin(), seen.end(), obstacle) != seen.end()) continue;
    seen.push_back(obstacle);
    out.ok = false;
    out.unstable = out.unstable || v.unstable;
    out.why += (out.why.empty() ? "" : "; then ") + v.why;
    if (++reasons == 3) break;
  }
  return out;
}

// "; the planner's states were refused most by wall 5 of floor 0 (61%), ..." (up to three).
std::string most_refused(const std::map<std::string, long>& refusals) {
  std::vector<std::pair<long, std::string>> ranked;
  long total = 0;
  for (const auto& [what, count] : refusals) {
    ranked.emplace_back(-count, what);
    total += count;
  }
  if (total == 0) return "";
  std::sort(ranked.begin(), ranked.end());
  std::string out = "; the planner's states were refused most by ";
  for (std::size_t k = 0; k < ranked.size() && k < 3; ++k)
    out += (k ? ", " : "") + ranked[k].second + " (" +
           std::to_string(static_cast<int>(std::lround(-100.0 * ranked[k].first / total))) + "%)";
  return out;
}

std::once_flag quiet;

}  // namespace

MotionResult plan_motion(const MotionProblem& p) {
  std::call_once(quiet, [] { ompl::msg::setLogLevel(ompl::msg::LOG_ERROR); });
  const auto began = std::chrono::steady_clock::now();
  MotionResult out;
  const std::size_t n = p.start.size();
  double diagonal = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    diagonal += (p.upper[k] - p.lower[k]) * (p.upper[k] - p.lower[k]);
  diagonal = std::max(std::sqrt(diagonal), 1e-9);
  const double step = p.resolution * diagonal;
  auto finish = [&](MotionResult r) {
    r.planning_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    return r;
  };
  for (const auto* which : {&p.start, &p.goal}) {
    for (std::size_t k = 0; k < n; ++k)
      if ((*which)[k] < p.lower[k] - 1e-9 || (*which)[k] > p.upper[k] + 1e-9) {
        out.verdict =
            Verdict::refused(std::string(which == &p.start ? "the start" : "the goal") +
                             " is outside the joints' limits (joint " + std::to_string(k) + ")");
        return finish(out);
      }
    Verdict v = p.valid(*which);
    if (!v.ok) {
      out.verdict =
          v.within(std::string(which == &p.start ? "the start" : "the goal") + " is not valid: ");
      return finish(out);
    }
  }
  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(n));
  ob::RealVectorBounds bounds(static_cast<unsigned>(n));
  for (std::size_t k = 0; k < n; ++k) {
    bounds.setLow(k, p.lower[k]);
    // A fixed joint (equal limits) still needs a box with some width.
    bounds.setHigh(k, std::max(p.upper[k], p.lower[k] + 1e-9));
  }
  space->setBounds(bounds);
  const auto seed = static_cast<std::uint_fast32_t>(p.seed % 4294967291ULL);
  space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  // What refuses the planner's states, per obstacle: said when no motion is found.
  std::map<std::string, long> refusals;
  si->setStateValidityChecker([&](const ob::State* state) {
    const Verdict v = p.valid(values(state, n));
    if (!v.ok) ++refusals[obstacle_of(v)];
    return v.ok;
  });
  si->setStateValidityCheckingResolution(p.resolution);
  si->setup();
  ob::ScopedState<> start(space), goal(space);
  for (std::size_t k = 0; k < n; ++k) {
    start[k] = p.start[k];
    goal[k] = p.goal[k];
  }
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 1e-9);
  auto planner = std::make_shared<SeededRRTConnect>(si, seed);
  planner->setProblemDefinition(pdef);
  planner->setup();
  long iterations = 0;
  const auto deadline = began + std::chrono::duration<double>(p.time_s);
  const ob::PlannerTerminationCondition ptc([&] {
    if (++iterations > p.max_iterations) return true;
    if (std::chrono::steady_clock::now() > deadline) {
      out.timed_out = true;
      return true;
    }
    return false;
  });
  const ob::PlannerStatus status = planner->solve(ptc);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    const Verdict direct = first_invalid(p, p.start, p.goal, step / 4, true);
    out.verdict = Verdict::refused(
        std::string(out.timed_out ? "no motion within the time"
                                  : "no motion within " + std::to_string(p.max_iterations) +
                                        " planner iterations") +
            (direct.ok ? "" : "; the direct motion is blocked: " + direct.why) +
            most_refused(refusals),
        "", direct.unstable);
    return finish(out);
  }
  auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  SeededSimplifier simplifier(si, seed);
  simplifier.simplifyMax(path);
  for (std::size_t k = 0; k < path.getStateCount(); ++k)
    out.path.push_back(values(path.getState(k), n));
  // Before accepting it: every stretch at four times the planner's resolution.
  for (std::size_t k = 0; k + 1 < out.path.size(); ++k) {
    const Verdict v = first_invalid(p, out.path[k], out.path[k + 1], step / 4);
    if (!v.ok) {
      out.verdict = v.within("the planned motion fails the finer re-check: ");
      out.path.clear();
      return finish(out);
    }
  }
  out.path.front() = p.start;
  out.path.back() = p.goal;
  return finish(out);
}

}  // namespace ccbuild::climb::detail
