// The one duration formatter at its boundaries: the unit changes exactly at 2 min, 2 h and
// 2 days; a column speaks the unit of its largest value; a day clock rounds to the second
// and rolls over at midnight.

#include "ccbuild/common/format.hpp"

#include <gtest/gtest.h>

#include <cstdint>

#include "ccbuild/common/document.hpp"

namespace ccbuild {
namespace {

// One CSV quoting for every CSV written (exports, study results, sweep): quoted only
// when a field needs it, its quotes doubled.
TEST(CsvField, QuotesOnlyWhatNeedsItAndDoublesItsQuotes) {
  EXPECT_EQ(csv_field("plain text; no comma"), "plain text; no comma");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("the \"gantry\""), "\"the \"\"gantry\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
}

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

TEST(TextOut, AQuotedYamlScalarReadsBackExactly) {
  // Seeded, without std:: distributions (their algorithms differ between libraries).
  std::uint64_t state = 49;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<unsigned>(state >> 33);
  };
  const std::vector<std::string> pieces = {
      "\n", "\r\n", "\t",   "\"",      "\\",   "#",    ": ", "- ",  "'",   "{", "}",
      "[",  "]",    ",",    "&a",      "*a",   "!!",   "%",  "@",   "`",   "é", "€",
      "𝄞",  " ",    "\x01", "\x1b[2J", "\x7f", "null", "~",  "yes", "0x1f"};
  for (int n = 0; n < 500; ++n) {
    std::string text;
    const unsigned parts = next() % 8;
    for (unsigned k = 0; k < parts; ++k) text += pieces[next() % pieces.size()];
    const Document doc = parse_yaml("name: " + yaml_quoted(text) + "\n", "generated.yaml");
    ASSERT_EQ(doc.root.kind, DocNode::Kind::kMap);
    const Field name = MapReader(Field::root(doc), {"name"}).required("name");
    EXPECT_EQ(name.as_string(), text) << yaml_quoted(text);
  }
}

TEST(TextOut, ACommentStaysOnOneLineAndCannotCloseAnXmlComment) {
  EXPECT_EQ(comment_text("a\nb\tc\r\x1b"), "a\\nb\\tc\\r\\x1b");
  EXPECT_EQ(comment_text("x--y---z"), "x- -y- - -z");
  EXPECT_EQ(comment_text("plain é"), "plain é");
}

TEST(TextOut, AnEchoedValueIsCutAtACharactersStart) {
  EXPECT_EQ(echoed(std::string(80, 'x')), std::string(80, 'x'));  // at the limit: whole
  const std::string long_value(10 * 1024 * 1024, 'y');
  const std::string shown = echoed(long_value);
  EXPECT_LT(shown.size(), 120u);
  EXPECT_NE(shown.find("10485760 bytes in all"), std::string::npos);
  // "é" is two bytes: a cut inside it moves back to its start.
  const std::string accents = std::string(79, 'a') + "éé";
  EXPECT_EQ(echoed(accents).substr(0, 80), std::string(79, 'a') + ".");
  EXPECT_EQ(echoed("a\nb"), "a\\nb");
  EXPECT_EQ(echoed("--time-limit"), "--time-limit");  // a flag stays as typed
}

}  // namespace
}  // namespace ccbuild
