#pragma once
// Formatting numbers with their unit for messages and reports.

#include <cstddef>
#include <string>
#include <vector>

namespace ccbuild {

/// printf into a std::string.
std::string printf_string(const char* pattern, ...) __attribute__((format(printf, 1, 2)));

/// Levenshtein distance between two words (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b);
/// The candidate nearest to `word`, for a "did you mean"; empty when none is within
/// `max_distance` edits (exclusive).
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates,
                         std::size_t max_distance);

/// A number as people write it: up to 6 significant digits, no exponent between 1e-4
/// and 1e9 ("0.15", "2400", "1e+308"); "NaN", "infinity" or "-infinity" otherwise.
std::string plain_number(double value);

/// A CSV field (RFC 4180): as it is, or quoted with its quotes doubled when it holds a
/// comma, a quote or a line break. Every CSV ccbuild writes quotes its fields so.
std::string csv_field(const std::string& text);

/// A plausible range of values, closed unless an end is said to be open.
struct Range {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;  ///< min itself is outside
  bool max_open = false;

  static Range closed(double min, double max) { return {min, max, false, false}; }
  /// (min, max]: for quantities that must be positive.
  static Range above(double min, double max) { return {min, max, true, false}; }

  bool contains(double value) const;
  /// As people say it: "from 0 to 60 s", "more than 0 and at most 2 m/s". `per_unit`
  /// converts the ends into `unit` (the ends divided by it).
  std::string describe(const std::string& unit, double per_unit = 1.0) const;
  /// "" when `value` is in range, else "must be <describe>, got <got>": the one wording
  /// of every out-of-range message (`got` as the user wrote it, with its unit).
  std::string violation(double value, const std::string& got, const std::string& unit,
                        double per_unit = 1.0) const;
};

/// Text for XML and HTML (SVG, MSPDI, a results page): & < > " ' as entities, control
/// characters XML 1.0 forbids dropped.
std::string xml_escape(const std::string& text);

/// The one escape for text ccbuild writes into YAML (names, GlobalIds, file names, notes;
/// values and comments alike): the inside of a double-quoted scalar, on one line. Quotes
/// and backslashes are escaped, and every character YAML does not print as itself (control
/// characters, line breaks including NEL, LS and PS, the byte order mark, non-characters);
/// bytes that are not UTF-8 become U+FFFD, and `exact` (when given) is set false, since
/// YAML text cannot hold them.
std::string yaml_escaped(const std::string& text, bool* exact = nullptr);
/// The offset of the first byte of `text` that does not start or continue a well-formed
/// UTF-8 character (shortest form, no surrogates, at most U+10FFFF); npos when it is all
/// UTF-8.
std::size_t first_invalid_utf8(const std::string& text);
/// A YAML double-quoted scalar that reads back as `text` exactly (yaml_escaped in quotes).
std::string yaml_quoted(const std::string& text);

/// `text` on one line, for a comment (YAML or shell `#`, XML `<!-- -->`) or a message:
/// control characters shown escaped (`\n`, `\t`, `\x1b`), `--` split so that an XML
/// comment cannot end early.
std::string comment_text(const std::string& text);

/// A value from the user, as a message echoes it: on one line (control characters shown
/// escaped, as comment_text does, `--` kept) and cut to
/// about `max_chars` characters, the rest counted ("... (10485760 bytes in all)").
std::string echoed(const std::string& value, std::size_t max_chars = 80);

/// The units a time is read in.
enum class TimeUnit { kSecond, kMinute, kHour, kDay };
/// The unit people read `s` seconds in (or a column whose largest value is `s`): seconds
/// under 2 min, minutes under 2 h, hours under 2 days, else days.
TimeUnit time_unit_for(double s);
/// "s", "min", "h", "d".
const char* time_unit_symbol(TimeUnit unit);
/// `s` in `unit` with its symbol, at the precision the unit deserves: "12.5 s", "3.3 min",
/// "19.32 h", "2.05 d". Every figure of a column goes through one unit.
std::string duration_in(double s, TimeUnit unit);
/// The one duration formatter of ccbuild's text: duration_in(s, time_unit_for(|s|)).
std::string duration_text(double s);
/// "day 3 07:05" ("day 3 07:05:09" with seconds): `t_s` seconds after day 1 00:00, as
/// times are told without a site calendar. Rounded to the second; without seconds, the
/// minute it falls in (as a clock shows it).
std::string day_clock_text(double t_s, bool with_seconds = false);

/// "4.500 m" (3 decimals by default).
std::string metres(double value_m, int decimals = 3);
/// "12.5 s" (1 decimal by default).
std::string seconds(double value_s, int decimals = 1);

}  // namespace ccbuild
