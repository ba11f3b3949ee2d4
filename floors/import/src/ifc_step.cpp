// The text of an IFC STEP file checked before IFC++ reads it: IFC++ reads a truncated file
// as far as it goes without a word, and a number too large for a double as 0, so both are
// found here, with the line they are on.

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

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
  // The schema, from the header.
  const std::size_t schema_at = text.find("FILE_SCHEMA");
  const std::size_t data_at =
      text.find("\nDATA;") != std::string::npos ? text.find("\nDATA;") + 1 : text.find("DATA;");
  if (data_at == std::string::npos)
    throw InputError(file, 0, "", "no DATA section: truncated, or not an IFC model");
  if (schema_at != std::string::npos && schema_at < data_at) {
    const std::size_t open = text.find('\'', schema_at);
    const std::size_t close = open == std::string::npos ? open : text.find('\'', open + 1);
    if (close != std::string::npos && close < data_at)
      out.schema = upper(text.substr(open + 1, close - open - 1));
  }
  if (out.schema.empty())
    throw InputError(file, 0, "", "the header names no schema (FILE_SCHEMA): not an IFC model?");
  if (out.schema != "IFC4" && out.schema != "IFC2X3" && out.schema.rfind("IFC4ADD", 0) != 0)
    throw InputError(file, 0, "",
                     "schema " + out.schema +
                         ": ccbuild reads IFC4 and IFC2X3 models; export the model in one of them");
  // The DATA section, statement by statement.
  int line = 1;
  for (std::size_t k = 0; k < data_at; ++k) line += text[k] == '\n';
  bool closed = false;
  std::size_t k = data_at + 5;
  bool statement_start = true;
  while (k < text.size()) {
    const char c = text[k];
    if (c == '\n') {
      ++line;
      ++k;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++k;
      continue;
    }
    if (c == '/' && k + 1 < text.size() && text[k + 1] == '*') {  // a comment
      const std::size_t end = text.find("*/", k + 2);
      if (end == std::string::npos)
        throw InputError(file, line, "", "a comment that never ends: truncated?");
      for (std::size_t j = k; j < end; ++j) line += text[j] == '\n';
      k = end + 2;
      continue;
    }
    if (c == '\'') {  // a string; '' is a quote inside it
      std::size_t j = k + 1;
      for (;;) {
        if (j >= text.size())
          throw InputError(file, line, "", "a string that never ends: truncated?");
        if (text[j] == '\n') ++line;
        if (text[j] == '\'') {
          if (j + 1 < text.size() && text[j + 1] == '\'') {
            j += 2;
            continue;
          }
          break;
        }
        ++j;
      }
      k = j + 1;
      statement_start = false;
      continue;
    }
    if (statement_start && starts_with_at(text, k, "ENDSEC;")) {
      closed = true;
      k += 7;
      break;
    }
    if (c == '#') {
      std::size_t j = k + 1;
      while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
      if (statement_start) {
        if (++out.entities > max_entities)
          throw InputError(file, line, "",
                           printf_string("more than %zu entities; ccbuild reads models of at most "
                                         "that many (export only what is to be printed: the "
                                         "storeys and their walls)",
                                         max_entities));
      }
      k = j;
      statement_start = false;
      continue;
    }
    if (c == ';') {
      statement_start = true;
      ++k;
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {  // a keyword
      while (k < text.size() && (std::isalnum(static_cast<unsigned char>(text[k])) ||
                                 text[k] == '_' || text[k] == '-'))
        ++k;
      statement_start = false;
      continue;
    }
    if (c == '.' && k + 1 < text.size() && std::isalpha(static_cast<unsigned char>(text[k + 1]))) {
      const std::size_t end = text.find('.', k + 1);  // an enumeration: .ELEMENT.
      k = end == std::string::npos ? text.size() : end + 1;
      statement_start = false;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        ((c == '-' || c == '+' || c == '.') && k + 1 < text.size() &&
         (std::isdigit(static_cast<unsigned char>(text[k + 1])) || text[k + 1] == '.'))) {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(text.c_str() + k, &end);
      const std::size_t length = static_cast<std::size_t>(end - (text.c_str() + k));
      if (length == 0) {
        ++k;
        continue;
      }
      if (!std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
        throw InputError(file, line, "",
                         "the number " + text.substr(k, std::min<std::size_t>(length, 40)) +
                             " is not a finite number a double holds");
      k += length;
      statement_start = false;
      continue;
    }
    ++k;
    statement_start = false;
  }
  if (!closed)
    throw InputError(file, line, "",
                     "the DATA section ends without ENDSEC: the file is truncated; export it "
                     "again");
  if (text.find("END-ISO-10303-21", k) == std::string::npos)
    throw InputError(file, line, "",
                     "the file ends without END-ISO-10303-21: truncated? Export it again");
  return out;
}

}  // namespace ccbuild::import::ifc
