#pragma once
// Typed, located reads of a JSON document that ccbuild wrote and reads back (a schedule, a
// study's plan and results): every value is reached through its JSON pointer
// (`/layers/3/start_s`), and every error names the file, the line of that value in the
// text and the pointer, and says what was expected. Lines are found only when an error is
// reported, by walking the text to the pointer. (Files people write go through
// document.hpp's Field instead.)

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/common/format.hpp"

namespace ccbuild {

/// The text a document was parsed from, to locate values in it.
class JsonText {
 public:
  JsonText(std::string file, const std::string& text) : file_(std::move(file)), text_(&text) {}
  const std::string& file() const { return file_; }
  /// The 1-based line where the value at `pointer` starts (0 when it is not found).
  int line_of(const std::string& pointer) const;
  /// InputError at `pointer`: "file:line: pointer: message".
  [[noreturn]] void refuse(const std::string& pointer, const std::string& message) const;

 private:
  std::string file_;
  const std::string* text_;
};

/// Throws InputError (with the line) when `text` nests arrays and objects deeper than
/// `max_depth`, before a parser sees it; `what` names the kind of file for the message
/// ("a schedule").
void check_nesting(const std::string& text, const std::string& file, int max_depth,
                   const std::string& what);

/// Parses JSON text; a syntax error, a number out of double's range (1e400) or an
/// invalid UTF-8 string is an InputError with its line.
nlohmann::json parse_located(const std::string& text, const std::string& file);

/// One value of the document and its pointer.
class JsonAt {
 public:
  JsonAt(const JsonText& text, const nlohmann::json& value, std::string pointer)
      : text_(&text), value_(&value), pointer_(std::move(pointer)) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  bool is_null() const { return value_->is_null(); }
  [[noreturn]] void refuse(const std::string& message) const { text_->refuse(pointer_, message); }

  /// The member `key` of an object (required: a missing key is an error).
  JsonAt at(const std::string& key) const;
  /// The member `key`, unless it is missing or null.
  std::optional<JsonAt> maybe(const std::string& key) const;
  /// Throws when this object has a key not in `allowed`, or is not an object.
  void only_keys(const std::vector<std::string>& allowed) const;
  /// The items of an array (at most `max_items`).
  std::vector<JsonAt> elements(std::size_t max_items) const;
  /// The members of an object, in the document's order (at most `max_items`).
  std::vector<std::pair<std::string, JsonAt>> members(std::size_t max_items) const;

  /// A finite number in `range` (`unit` for the message).
  double number(const Range& range, const std::string& unit = "") const;
  /// The same, or unset for null.
  std::optional<double> number_or_null(const Range& range, const std::string& unit = "") const;
  /// A whole number from `min` to `max`.
  std::int64_t integer(std::int64_t min, std::int64_t max) const;
  std::uint64_t unsigned_integer() const;
  std::string string(std::size_t max_length = 100'000) const;
  bool boolean() const;

 private:
  std::string shown() const;
  const JsonText* text_;
  const nlohmann::json* value_;
  std::string pointer_;
};

/// "/a/b" + "c" -> "/a/b/c" (escaping ~ and / as JSON pointers do).
std::string pointer_to(const std::string& parent, const std::string& key);
std::string pointer_to(const std::string& parent, std::size_t index);

}  // namespace ccbuild
