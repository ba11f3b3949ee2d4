// The faults a dispatch run is asked to inject (ccbuild::dispatch::parse_injected,
// check_injected): the grammar at its boundaries and against a schedule's machines.

#include <gtest/gtest.h>

#include <string>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/dispatch/run_inputs.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "test_support.hpp"

namespace ccbuild::dispatch {
namespace {

/// The message of the InputError `text` is refused with ("" when it is accepted).
std::string refusal(const std::string& text) {
  try {
    parse_injected(text);
    return "";
  } catch (const InputError& e) {
    EXPECT_EQ(e.first().field, "--inject") << text;
    return e.what();
  }
}

TEST(InjectedFaults, ProbabilitiesAndCountsHoldAtTheirBounds) {
  const InjectedFaults f = parse_injected("drop=0.9,duplicate=0,clog=gantry-2@1:3,pin=1000");
  ASSERT_EQ(f.network.size(), 2u);
  EXPECT_EQ(f.network[0].first, "drop");
  EXPECT_DOUBLE_EQ(f.network[0].second, 0.9);
  ASSERT_EQ(f.machine.size(), 2u);
  EXPECT_EQ(f.machine[0].machine, "gantry-2");
  EXPECT_EQ(f.machine[0].floor, 1);
  EXPECT_EQ(f.machine[0].layer, 3);
  EXPECT_EQ(f.machine[1].machine, "gantry-1");  // unless MACHINE@ names another
  EXPECT_EQ(f.flags().at("gantry-2"), (std::vector<std::string>{"--clog-at", "1:3"}));
  EXPECT_EQ(f.flags().at("gantry-1"), (std::vector<std::string>{"--pin-failures", "1000"}));
  EXPECT_EQ(refusal("stall=0,crash=100000000"), "");
  EXPECT_NE(refusal("drop=0.9000001").find("a probability from 0 to 0.9"), std::string::npos);
  EXPECT_NE(refusal("pin=1001").find("a count from 1 to 1000"), std::string::npos);
  EXPECT_NE(refusal("pin=0").find("a count from 1 to 1000"), std::string::npos);
  EXPECT_NE(refusal("crash=100000001").find("a count"), std::string::npos);
  EXPECT_NE(refusal("stall=1000000001").find("from 0 to 1e9"), std::string::npos);
  EXPECT_NE(refusal("clog=1").find("FLOOR:LAYER"), std::string::npos);
  EXPECT_NE(refusal("drop=0.1,drop=0.2").find("drop given twice"), std::string::npos);
  EXPECT_NE(refusal("clog=0:1,clog=0:2").find("clog on gantry-1 given twice"), std::string::npos);
  EXPECT_EQ(refusal("clog=0:1,clog=gantry-2@0:2"), "") << "one per machine";
  EXPECT_NE(refusal("melt=1").find("unknown fault 'melt'"), std::string::npos);
  EXPECT_NE(refusal("drop").find("no '='"), std::string::npos);
}

TEST(InjectedFaults, AreHeldAgainstTheSchedule) {
  // The house: two floors of 30 layers on one gantry, no climbs.
  const auto path = testing::source_path("tests/regression/house.schedule.json");
  const schedule::ScheduleDocument house =
      schedule::parse_schedule(testing::slurp(path), path.string());
  const std::vector<DispatchJob> jobs = jobs_of_schedule(house);
  const std::vector<std::string> ids = {"gantry-1"};
  const auto check = [&](const std::string& text) {
    try {
      check_injected(parse_injected(text), house, jobs, ids);
      return std::string();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(check("clog=1:29"), "");
  EXPECT_NE(check("clog=1:30").find("deposits nothing on floor 1 layer 30"), std::string::npos);
  EXPECT_NE(check("clog=gantry-2@0:0").find("no machine gantry-2 (it has gantry-1)"),
            std::string::npos);
  EXPECT_NE(check("pin=1").find("no climbs"), std::string::npos);
  EXPECT_EQ(check("crash=" + std::to_string(jobs.size())), "");
  EXPECT_NE(check("crash=" + std::to_string(jobs.size() + 1)).find("never reaches"),
            std::string::npos);
  const double end_s = house.schedule.totals.makespan_s;
  EXPECT_EQ(check(printf_string("stall=%.17g", end_s)), "");
  EXPECT_NE(check(printf_string("stall=%.17g", end_s + 0.01)).find("before the stall"),
            std::string::npos);
}

}  // namespace
}  // namespace ccbuild::dispatch
