// The text of an IFC STEP file checked before IFC++ reads it: IFC++ reads a truncated file
// as far as it goes without a word, and a number too large for a double as 0, so both are
// found here, with the line they are on.
//
// The whole file is checked the way IFC++ (ReaderSTEP) reads it, so that nothing it reads
// escapes the check: it first drops every /* comment */ (anywhere, even in a string; a
// comment ends at the first '/' after a '*'), stops at a NUL byte, starts at the first
// "DATA;", drops white space outside strings (so "1 E999" is one number to it), ends a
// string at a quote unless doubled or after a backslash, and reads every statement that
// starts with '#' as an entity, wherever it is: after the DATA section's ENDSEC too (issue
// 49: a second DATA section moved a wall unchecked). So: one DATA section, only entities in
// it, nothing but END-ISO-10303-21; after it, and every number of every statement finite.

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <vector>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ifc_internal.hpp"

namespace ccbuild::import::ifc {
namespace {

bool starts_with_at(const std::string& text, std::size_t at, const char* word) {
  for (std::size_t k = 0; word[k] != '\0'; ++k)
    if (at + k >= text.size() || text[at + k] != word[k]) return false;
  return true;
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// The text without its comments, as IFC++ sees it, and where each of its characters was.
class Uncommented {
 public:
  Uncommented(const std::string& text, const std::string& file) {
    clean_.reserve(text.size());
    for (std::size_t k = 0; k < text.size(); ++k)
      if (text[k] == '\n') newlines_.push_back(k);
    std::size_t k = 0;
    while (k < text.size()) {
      if (text[k] == '\0')
        throw InputError(file, line_at_original(k), "",
                         "a NUL byte: not STEP text (IFC++ would stop reading here)");
      if (text[k] == '/' && k + 1 < text.size() && text[k + 1] == '*') {
        // IFC++'s rule: from the '*', the first '/' preceded by a '*' ends it ("/*/" too).
        std::size_t j = k + 1;
        while (j < text.size() && !(text[j] == '/' && text[j - 1] == '*')) ++j;
        if (j >= text.size())
          throw InputError(file, line_at_original(k), "", "a comment that never ends: truncated?");
        k = j + 1;
        jumps_.emplace_back(clean_.size(), k);
        continue;
      }
      clean_ += text[k];
      ++k;
    }
  }
  const std::string& text() const { return clean_; }
  /// The 1-based line of the original text that clean character `at` comes from.
  int line(std::size_t at) const {
    // The last comment removed before `at`: clean characters from there on follow its end.
    auto it = std::upper_bound(jumps_.begin(), jumps_.end(), std::pair{at, ~std::size_t{0}});
    const std::size_t original =
        it == jumps_.begin() ? at : std::prev(it)->second + (at - std::prev(it)->first);
    return line_at_original(original);
  }

 private:
  int line_at_original(std::size_t at) const {
    return 1 + static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(), at) -
                                newlines_.begin());
  }
  std::string clean_;
  std::vector<std::size_t> newlines_;
  std::vector<std::pair<std::size_t, std::size_t>> jumps_;  ///< (clean, original) after a comment
};

/// One statement as IFC++ reads it: white space outside strings dropped, strings kept whole.
struct Statement {
  std::string text;
  int line = 0;  ///< where it starts
};

/// The end (one past the closing quote) of the string whose opening quote is at `at`, by
/// IFC++'s rules: \X0\, \X2\, \X4\, \\ and \' are skipped; '' is a quote inside it, except
/// right after the opening quote (the empty string); npos when it never ends.
std::size_t string_end(const std::string& s, std::size_t at) {
  const std::size_t begin = at + 1;
  std::size_t k = begin;
  while (k < s.size()) {
    if (s[k] == '\\' && k + 1 < s.size()) {
      if (s[k + 1] == 'X' && k + 3 < s.size() &&
          (s[k + 2] == '0' || s[k + 2] == '2' || s[k + 2] == '4') && s[k + 3] == '\\') {
        k += 4;
        continue;
      }
      if (s[k + 1] == '\\' || s[k + 1] == '\'') {
        k += 2;
        continue;
      }
    }
    if (s[k] == '\'') {
      if (k + 1 < s.size() && s[k + 1] == '\'' && k != begin) {
        k += 2;
        continue;
      }
      return k + 1;
    }
    ++k;
  }
  return std::string::npos;
}

/// Checks every number in a statement: finite, and within a double (IFC++ reads them with
/// std::stod: "nan", "inf" and hexadecimal numbers too).
void check_numbers(const Statement& st, const std::string& file) {
  const std::string& t = st.text;
  std::size_t k = 0;
  const auto refuse = [&](std::size_t at, std::size_t length) {
    throw InputError(file, st.line, "",
                     "the number " + t.substr(at, std::min<std::size_t>(length, 40)) +
                         " is not a finite number a double holds");
  };
  while (k < t.size()) {
    const char c = t[k];
    if (c == '\'') {
      const std::size_t end = string_end(t, k);
      k = end == std::string::npos ? t.size() : end;
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {  // a keyword
      const std::size_t from = k;
      while (k < t.size() &&
             (std::isalnum(static_cast<unsigned char>(t[k])) || t[k] == '_' || t[k] == '-'))
        ++k;
      const std::string word = upper(t.substr(from, k - from));
      if (word == "NAN" || word == "INF" || word == "INFINITY") refuse(from, k - from);
      continue;
    }
    if (c == '.' && k + 1 < t.size() && std::isalpha(static_cast<unsigned char>(t[k + 1]))) {
      const std::size_t end = t.find('.', k + 1);  // an enumeration: .ELEMENT.
      k = end == std::string::npos ? t.size() : end + 1;
      continue;
    }
    if (c == '#') {  // an instance name or reference: its digits are no number
      ++k;
      while (k < t.size() && std::isdigit(static_cast<unsigned char>(t[k]))) ++k;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        ((c == '-' || c == '+' || c == '.') && k + 1 < t.size() &&
         (std::isdigit(static_cast<unsigned char>(t[k + 1])) || t[k + 1] == '.'))) {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(t.c_str() + k, &end);
      const std::size_t length = static_cast<std::size_t>(end - (t.c_str() + k));
      if (length == 0) {
        ++k;
        continue;
      }
      if (!std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0)) refuse(k, length);
      k += length;
      continue;
    }
    ++k;
  }
}

}  // namespace

StepSummary check_step_text(const std::string& text, const std::string& file,
                            std::size_t max_entities) {
  StepSummary out;
  std::size_t begin = 0;
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) begin = 3;  // a UTF-8 byte order mark
  while (begin < text.size() && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
  if (text.rfind("PK", 0) == 0)
    throw InputError(file, 0, "",
                     "an IFC-ZIP (.ifczip) archive: unzip it and give the .ifc inside");
  if (!starts_with_at(text, begin, "ISO-10303-21;")) {
    const bool xml = text.find("<?xml") != std::string::npos;
    throw InputError(file, 1, "",
                     xml ? "an ifcXML file: ccbuild reads IFC models as STEP text (.ifc); "
                           "export the model as IFC (STEP)"
                         : "not an IFC model (an IFC STEP file starts with ISO-10303-21;)");
  }
  const Uncommented uncommented(text, file);
  const std::string& s = uncommented.text();
  // IFC++ reads entities from the first "DATA;" on: it must be the DATA section's start.
  const std::size_t data_at = s.find("DATA;");
  if (data_at == std::string::npos)
    throw InputError(file, 0, "", "no DATA section: truncated, or not an IFC model");
  // The schema, from the header's FILE_SCHEMA, checked where the DATA section starts.
  const auto check_schema = [&] {
    if (out.schema.empty())
      throw InputError(file, 0, "", "the header names no schema (FILE_SCHEMA): not an IFC model?");
    if (out.schema != "IFC4" && out.schema != "IFC2X3" && out.schema.rfind("IFC4ADD", 0) != 0)
      throw InputError(file, 0, "",
                       "schema " + out.schema +
                           ": ccbuild reads IFC4 and IFC2X3 models; export the model in one of "
                           "them");
  };
  // The statements of the whole file, as IFC++ splits them.
  enum class Part { kHeader, kData, kAfterData, kEnded } part = Part::kHeader;
  Statement st;
  std::size_t st_begin = std::string::npos;  // where the current statement starts
  const auto finish = [&](std::size_t semicolon) {
    const std::string& t = st.text;
    const std::size_t from = st_begin;
    st_begin = std::string::npos;
    if (t.empty()) return;  // a lone ';': nothing to IFC++ either
    switch (part) {
      case Part::kHeader:
        if (t == "DATA") {
          if (from != data_at || semicolon != data_at + 4)
            throw InputError(file, st.line, "",
                             "the DATA section starts with 'DATA;' here, but IFC++ reads "
                             "from an earlier 'DATA;' (in the header): not a model ccbuild "
                             "reads");
          check_schema();
          part = Part::kData;
        } else if (t.rfind("FILE_SCHEMA", 0) == 0 && out.schema.empty()) {
          const std::size_t open = t.find('\'');
          const std::size_t close = open == std::string::npos ? open : t.find('\'', open + 1);
          if (close != std::string::npos) out.schema = upper(t.substr(open + 1, close - open - 1));
        } else if (t[0] == '#') {
          throw InputError(file, st.line, "",
                           "an entity instance before the DATA section: not a model ccbuild "
                           "reads");
        }
        break;
      case Part::kData:
        if (t == "ENDSEC") {
          part = Part::kAfterData;
        } else if (t[0] != '#') {
          // IFC++ reads no entity after a statement that is not one.
          throw InputError(file, st.line, "",
                           "'" + t.substr(0, 40) +
                               "' in the DATA section, which holds entity instances (#1=...) "
                               "only");
        } else if (++out.entities > max_entities) {
          throw InputError(file, st.line, "",
                           printf_string("more than %zu entities; ccbuild reads models of at "
                                         "most that many (export only what is to be printed: "
                                         "the storeys and their walls)",
                                         max_entities));
        }
        break;
      case Part::kAfterData:
        if (t == "END-ISO-10303-21") {
          part = Part::kEnded;
        } else {
          const bool data = t == "DATA" || t.rfind("DATA(", 0) == 0;
          throw InputError(file, st.line, "",
                           data ? "a second DATA section: ccbuild reads models of one (IFC++ "
                                  "would read its entities unchecked); export the model again"
                                : "'" + t.substr(0, 40) +
                                      "' after the DATA section's ENDSEC: only "
                                      "END-ISO-10303-21; may follow it");
        }
        break;
      case Part::kEnded:
        throw InputError(file, st.line, "",
                         "'" + t.substr(0, 40) + "' after END-ISO-10303-21;, the file's end");
    }
    check_numbers(st, file);
    st.text.clear();
  };
  std::size_t k = begin;
  while (k < s.size()) {
    const char c = s[k];
    // IFC++ drops white space outside strings, and '!' at the end of a line.
    if (c == '!' && k + 1 < s.size() && (s[k + 1] == '\n' || s[k + 1] == '\r')) {
      k += 2;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++k;
      continue;
    }
    if (st_begin == std::string::npos) {
      st_begin = k;
      st.line = uncommented.line(k);
    }
    if (c == '\'') {
      const std::size_t end = string_end(s, k);
      if (end == std::string::npos)
        throw InputError(file, uncommented.line(k), "", "a string that never ends: truncated?");
      st.text.append(s, k, end - k);
      k = end;
      continue;
    }
    if (c == ';') {
      finish(k);
      ++k;
      continue;
    }
    st.text += c;
    ++k;
  }
  const int last_line = uncommented.line(s.empty() ? 0 : s.size() - 1);
  if (part == Part::kHeader)
    throw InputError(file, last_line, "", "no DATA section: truncated, or not an IFC model");
  if (part == Part::kData)
    throw InputError(file, last_line, "",
                     "the DATA section ends without ENDSEC: the file is truncated; export it "
                     "again");
  if (part != Part::kEnded)
    throw InputError(file, last_line, "",
                     "the file ends without END-ISO-10303-21: truncated? Export it again");
  if (!st.text.empty())
    throw InputError(file, st.line, "",
                     "'" + st.text.substr(0, 40) + "' after END-ISO-10303-21;, the file's end");
  return out;
}

}  // namespace ccbuild::import::ifc
