#pragma once
// A study's results: one row per variant (its settings, its status, its measures), as
// CSV, JSON and an HTML page (the Pareto front of the makespan against each cost, each
// variant linked to its schedule, the makespan's sensitivity to each axis). The same
// variants give the same bytes, wherever they ran.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/study/runner.hpp"

namespace ccbuild::study {

/// The measures of one schedule JSON (all_measures(), in order): makespan_s, feasible,
/// nozzles_max, waits_s, wait_<reason>_s (the time that reason was the binding one, over
/// the layers' and the climbs' waits: they add up to those), concrete_m3, crew_h,
/// climbs, machine_s, idle_margin_s (the least a nozzle stays under its idle limit),
/// warnings.
nlohmann::ordered_json measures_of(const nlohmann::json& schedule);

/// The measure of one wait reason: "wait_anchor_strength_s".
std::string wait_measure(schedule::WaitKind kind);

struct Collected {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();  ///< one per variant
  std::vector<int> feasible, infeasible, failed, missing;         ///< variant indices
};

/// Reads every variant's result.json (a result whose inputs changed since counts as
/// missing).
Collected collect(const Plan& plan);

/// The costs the HTML page sets the makespan against, and their names.
const std::vector<std::pair<std::string, std::string>>& front_costs();

/// The feasible variants no other beats on both the makespan and `cost` (a measure):
/// none has both at most as large and one smaller. By cost, then makespan, then index.
std::vector<int> pareto_front(const Collected& collected, const std::string& cost);

/// Per axis, per value: the mean, least and largest makespan of the feasible variants
/// with that value, and how many.
struct Sensitivity {
  std::string axis;
  struct Value {
    std::string value;
    int count = 0;
    double mean_s = 0.0, min_s = 0.0, max_s = 0.0;
  };
  std::vector<Value> values;
  double spread_s = 0.0;  ///< the largest mean less the smallest
};
std::vector<Sensitivity> sensitivity(const Plan& plan, const Collected& collected);

std::string results_csv(const Plan& plan, const Collected& collected);
std::string results_json(const Plan& plan, const Collected& collected);
std::string results_html(const Plan& plan, const Collected& collected);

}  // namespace ccbuild::study
