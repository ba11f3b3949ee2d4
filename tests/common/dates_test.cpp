// The one strict date and clock reader at its edges: exactly the digits the format shows
// (no sign, no space, no short field), each field in its range, the days of each month
// (leap years by the 4/100/400 rule), the first and last years, 24:00 only as a day's end.

#include "ccbuild/common/dates.hpp"

#include <gtest/gtest.h>

namespace ccbuild {
namespace {

TEST(Dates, OnlyTheDigitsTheFormatShowsAreRead) {
  EXPECT_EQ(parse_date("2027-03-01"), days_from_civil(2027, 3, 1));
  for (const char* bad : {"2027-03-+1", "2027- 3- 1", "2027-3-1", "2027-03-1", "2027-03-01 ",
                          " 2027-03-01", "+2027-03-01", "2027/03/01", "2027-03-0x", "20270301",
                          "2027-03-01T00:00", "", "２027-03-01"})
    EXPECT_FALSE(parse_date(bad)) << bad;
  EXPECT_EQ(parse_clock("07:00"), 420);
  for (const char* bad :
       {"+7:+0", "7:00", "07:0", "07:00:00", " 7:00", "07 :00", "-1:00", "07:-1", "0x:00", "07.00"})
    EXPECT_FALSE(parse_clock(bad)) << bad;
  EXPECT_FALSE(parse_date_time("2027-03-01T07:00:+1"));
  EXPECT_FALSE(parse_date_time("2027-03-01 7:00"));
  EXPECT_FALSE(parse_date_time("2027-03-01X07:00"));
  EXPECT_FALSE(parse_utc_offset("+7:+0"));
  EXPECT_FALSE(parse_utc_offset("+01:0-"));
}

TEST(Dates, EachFieldAtBothEndsOfItsRange) {
  EXPECT_TRUE(parse_date("2027-01-31"));
  EXPECT_FALSE(parse_date("2027-00-10"));
  EXPECT_FALSE(parse_date("2027-13-10"));
  EXPECT_FALSE(parse_date("2027-01-00"));
  EXPECT_FALSE(parse_date("2027-01-32"));
  EXPECT_TRUE(parse_date("2027-04-30"));
  EXPECT_FALSE(parse_date("2027-04-31"));
  // Leap years: every 4th, not every 100th, every 400th.
  EXPECT_FALSE(parse_date("2027-02-29"));
  EXPECT_TRUE(parse_date("2028-02-29"));
  EXPECT_FALSE(parse_date("2100-02-29"));
  EXPECT_TRUE(parse_date("2000-02-29"));
  // The first and last years a date may name.
  EXPECT_TRUE(parse_date("1971-01-01"));
  EXPECT_FALSE(parse_date("1970-12-31"));
  EXPECT_TRUE(parse_date("2200-12-31"));
  EXPECT_FALSE(parse_date("2201-01-01"));
  EXPECT_FALSE(parse_date("9999-12-31"));
  // Clocks: 00:00 and 24:00 end the day; 24:01 and minute 60 are not clocks.
  EXPECT_EQ(parse_clock("00:00"), 0);
  EXPECT_EQ(parse_clock("23:59"), 23 * 60 + 59);
  EXPECT_EQ(parse_clock("24:00"), 24 * 60);
  EXPECT_FALSE(parse_clock("24:01"));
  EXPECT_FALSE(parse_clock("12:60"));
  EXPECT_FALSE(parse_clock("25:00"));
  // A date and time: 24:00 is no time of day; seconds 00 to 59.
  EXPECT_FALSE(parse_date_time("2027-03-01 24:00"));
  EXPECT_EQ(parse_date_time("2027-03-01T23:59:59"), days_from_civil(2027, 3, 1) * 86400 + 86399);
  EXPECT_FALSE(parse_date_time("2027-03-01T23:59:60"));
  EXPECT_EQ(parse_date_time("2027-03-01 07:00"), days_from_civil(2027, 3, 1) * 86400 + 25200);
  // Offsets: Z, and up to 18 hours either way.
  EXPECT_EQ(parse_utc_offset("Z"), 0);
  EXPECT_EQ(parse_utc_offset("+01:00"), 3600);
  EXPECT_EQ(parse_utc_offset("-05:30"), -(5 * 3600 + 1800));
  EXPECT_EQ(parse_utc_offset("+18:00"), 18 * 3600);
  EXPECT_FALSE(parse_utc_offset("+18:01"));
  EXPECT_FALSE(parse_utc_offset("+01:60"));
}

TEST(Dates, DaysAndTextAgreeBothWays) {
  EXPECT_EQ(days_from_civil(1970, 1, 1), 0);
  EXPECT_EQ(days_from_civil(1971, 1, 1), 365);
  EXPECT_EQ(date_text(0), "1970-01-01");
  // Every day of the years a date may name reads back to itself.
  const auto first = *parse_date("1971-01-01"), last = *parse_date("2200-12-31");
  for (std::int64_t day = first; day <= last; ++day) {
    const std::string text = date_text(day);
    const auto back = parse_date(text);
    ASSERT_TRUE(back) << text;
    ASSERT_EQ(*back, day) << text;
  }
  EXPECT_EQ(date_time_text(days_from_civil(2027, 3, 1) * 86400 + 25261), "2027-03-01 07:01:01");
  EXPECT_EQ(date_time_text(-1), "1969-12-31 23:59:59");
}

}  // namespace
}  // namespace ccbuild
