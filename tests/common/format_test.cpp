// The one duration formatter at its boundaries: the unit changes exactly at 2 min, 2 h and
// 2 days; a column speaks the unit of its largest value; a day clock rounds to the second
// and rolls over at midnight.

#include "ccbuild/common/format.hpp"

#include <gtest/gtest.h>

namespace ccbuild {
namespace {

TEST(Durations, TheUnitChangesExactlyAtTwoOfTheNext) {
  EXPECT_EQ(duration_text(119.9), "119.9 s");
  EXPECT_EQ(duration_text(120.0), "2.0 min");
  EXPECT_EQ(duration_text(7199.0), "120.0 min");
  EXPECT_EQ(duration_text(7200.0), "2.00 h");
  EXPECT_EQ(duration_text(172799.0), "48.00 h");
  EXPECT_EQ(duration_text(172800.0), "2.00 d");
  EXPECT_EQ(duration_text(-7200.0), "-2.00 h");  // the unit of its size
  EXPECT_EQ(duration_text(0.0), "0.0 s");
}

TEST(Durations, AColumnSpeaksTheUnitOfItsLargestValue) {
  const TimeUnit unit = time_unit_for(3.85 * 86400.0);
  EXPECT_EQ(duration_in(69120.0, unit), "0.80 d");
  EXPECT_EQ(duration_in(3.85 * 86400.0, unit), "3.85 d");
  EXPECT_STREQ(time_unit_symbol(time_unit_for(60.0)), "s");
  EXPECT_STREQ(time_unit_symbol(time_unit_for(600.0)), "min");
}

TEST(DayClock, RoundsToTheSecondAndRollsOverAtMidnight) {
  EXPECT_EQ(day_clock_text(0.0), "day 1 00:00");
  EXPECT_EQ(day_clock_text(86399.4, true), "day 1 23:59:59");
  EXPECT_EQ(day_clock_text(86399.6, true), "day 2 00:00:00");
  EXPECT_EQ(day_clock_text(86399.6), "day 2 00:00");
  EXPECT_EQ(day_clock_text(86340.0 + 59.4), "day 1 23:59");  // the minute it falls in
  EXPECT_EQ(day_clock_text(2 * 86400.0 + 7 * 3600.0 + 5 * 60.0 + 9.0, true), "day 3 07:05:09");
}

}  // namespace
}  // namespace ccbuild
