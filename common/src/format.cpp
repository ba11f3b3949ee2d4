#include "ccbuild/common/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>

namespace ccbuild {

std::string printf_string(const char* pattern, ...) {
  va_list args;
  va_start(args, pattern);
  va_list copy;
  va_copy(copy, args);
  const int needed = std::vsnprintf(nullptr, 0, pattern, copy);
  va_end(copy);
  std::string out(needed > 0 ? static_cast<std::size_t>(needed) : 0, '\0');
  if (needed > 0) std::vsnprintf(out.data(), out.size() + 1, pattern, args);
  va_end(args);
  return out;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates,
                         std::size_t max_distance) {
  std::string best;
  std::size_t best_distance = max_distance;
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::string yaml_escaped(const std::string& text, bool* exact) {
  std::string out;
  out.reserve(text.size() + 8);
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  for (std::size_t k = 0; k < text.size();) {
    // One UTF-8 character (shortest form, no surrogates), or a byte that is none.
    const unsigned char b = byte(k);
    std::size_t n = b < 0x80           ? 1
                    : (b >> 5) == 0x6  ? 2
                    : (b >> 4) == 0xE  ? 3
                    : (b >> 3) == 0x1E ? 4
                                       : 0;
    std::uint32_t c = n == 1 ? b : n == 2 ? (b & 0x1Fu) : n == 3 ? (b & 0x0Fu) : (b & 0x07u);
    if (n == 0 || k + n > text.size()) n = 0;
    for (std::size_t j = 1; j < n; ++j) {
      if ((byte(k + j) & 0xC0) != 0x80) {
        n = 0;
        break;
      }
      c = (c << 6) | (byte(k + j) & 0x3Fu);
    }
    static const std::uint32_t kShortest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (n > 0 && (c < kShortest[n] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF))) n = 0;
    if (n == 0) {
      out += "\\uFFFD";
      if (exact) *exact = false;
      ++k;
      continue;
    }
    // YAML's printable characters, less the quote, the backslash and the line breaks.
    const bool printable = (c >= 0x20 && c <= 0x7E && c != '"' && c != '\\') ||
                           (c >= 0xA0 && c <= 0xD7FF && c != 0x2028 && c != 0x2029) ||
                           (c >= 0xE000 && c <= 0xFFFD && c != 0xFEFF) || c >= 0x10000;
    if (printable) {
      out.append(text, k, n);
    } else if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x100) {
      out += printf_string("\\x%02X", static_cast<unsigned>(c));
    } else {
      out += printf_string("\\u%04X", static_cast<unsigned>(c));
    }
    k += n;
  }
  return out;
}

std::size_t first_invalid_utf8(const std::string& text) {
  std::size_t k = 0;
  while (k < text.size()) {
    const auto b = static_cast<unsigned char>(text[k]);
    const std::size_t n = b < 0x80           ? 1
                          : (b >> 5) == 0x6  ? 2
                          : (b >> 4) == 0xE  ? 3
                          : (b >> 3) == 0x1E ? 4
                                             : 0;
    if (n == 0 || k + n > text.size()) return k;
    std::uint32_t c = n == 1 ? b : n == 2 ? (b & 0x1Fu) : n == 3 ? (b & 0x0Fu) : (b & 0x07u);
    for (std::size_t j = 1; j < n; ++j) {
      const auto next = static_cast<unsigned char>(text[k + j]);
      if ((next & 0xC0) != 0x80) return k;
      c = (c << 6) | (next & 0x3Fu);
    }
    static const std::uint32_t kShortest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (c < kShortest[n] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return k;
    k += n;
  }
  return std::string::npos;
}

std::string yaml_quoted(const std::string& text) {
  return "\"" + yaml_escaped(text) + "\"";
}

namespace {
/// `text` on one line: control characters shown escaped; `--` split when `split_dashes`.
std::string one_line(const std::string& text, bool split_dashes) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (u < 0x20 || u == 0x7f)
      out += printf_string("\\x%02x", u);
    else if (split_dashes && c == '-' && !out.empty() && out.back() == '-')
      out += " -";  // "--" would end an XML comment
    else
      out += c;
  }
  return out;
}
}  // namespace

std::string comment_text(const std::string& text) {
  return one_line(text, true);
}

std::string echoed(const std::string& value, std::size_t max_chars) {
  if (value.size() <= max_chars) return one_line(value, false);
  // Cut at a character's start, never inside a UTF-8 sequence.
  std::size_t cut = max_chars;
  while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xc0) == 0x80) --cut;
  return one_line(value.substr(0, cut), false) +
         printf_string("... (%zu bytes in all)", value.size());
}

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // Control characters are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
    }
  }
  return out;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string plain_number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "infinity" : "-infinity";
  const double magnitude = std::abs(value);
  if (magnitude != 0.0 && (magnitude < 1e-4 || magnitude >= 1e9))
    return printf_string("%.6g", value);
  std::string text = printf_string("%.6f", value);
  // Six significant digits at most, then no trailing zeros.
  int digits = 0;
  bool counting = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c < '0' || c > '9') continue;
    if (c != '0') counting = true;
    if (counting && ++digits > 6) {
      const auto dot = text.find('.');
      if (dot != std::string::npos && i > dot) text.resize(i);
      break;
    }
  }
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

bool Range::contains(double value) const {
  if (std::isnan(value)) return false;
  const bool above_min = min_open ? value > min : value >= min;
  const bool below_max = max_open ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::describe(const std::string& unit, double per_unit) const {
  const std::string suffix = unit.empty() ? "" : " " + unit;
  const std::string lo = plain_number(min / per_unit), hi = plain_number(max / per_unit);
  if (!min_open && !max_open) return "from " + lo + " to " + hi + suffix;
  return std::string(min_open ? "more than " : "at least ") + lo +
         (max_open ? " and less than " : " and at most ") + hi + suffix;
}

std::string Range::violation(double value, const std::string& got, const std::string& unit,
                             double per_unit) const {
  return contains(value) ? "" : "must be " + describe(unit, per_unit) + ", got " + got;
}

TimeUnit time_unit_for(double s) {
  s = std::abs(s);
  if (s >= 2 * 86400.0) return TimeUnit::kDay;
  if (s >= 2 * 3600.0) return TimeUnit::kHour;
  if (s >= 120.0) return TimeUnit::kMinute;
  return TimeUnit::kSecond;
}

const char* time_unit_symbol(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kDay:
      return "d";
    case TimeUnit::kHour:
      return "h";
    case TimeUnit::kMinute:
      return "min";
    case TimeUnit::kSecond:
      break;
  }
  return "s";
}

std::string duration_in(double s, TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kDay:
      return printf_string("%.2f d", s / 86400.0);
    case TimeUnit::kHour:
      return printf_string("%.2f h", s / 3600.0);
    case TimeUnit::kMinute:
      return printf_string("%.1f min", s / 60.0);
    case TimeUnit::kSecond:
      break;
  }
  return printf_string("%.1f s", s);
}

std::string duration_text(double s) {
  return duration_in(s, time_unit_for(s));
}

std::string day_clock_text(double t_s, bool with_seconds) {
  const long long total = std::llround(t_s);  // to the second; the minutes drop the seconds
  const long long day = total >= 0 ? total / 86400 : (total - 86399) / 86400;
  const long long rest = total - day * 86400;
  return with_seconds
             ? printf_string("day %lld %02lld:%02lld:%02lld", day + 1, rest / 3600, rest / 60 % 60,
                             rest % 60)
             : printf_string("day %lld %02lld:%02lld", day + 1, rest / 3600, rest / 60 % 60);
}

std::string metres(double value_m, int decimals) {
  return printf_string("%.*f m", decimals, value_m);
}

std::string seconds(double value_s, int decimals) {
  return printf_string("%.*f s", decimals, value_s);
}

}  // namespace ccbuild
