#include "ccbuild/common/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild {
namespace {

using json = nlohmann::json;

int line_at_byte(const std::string& text, std::size_t byte) {
  byte = std::min(byte, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + byte, '\n'));
}

/// Walks JSON text (already parsed once, so well formed) to find where values start.
struct Walker {
  const std::string& t;
  std::size_t i = 0;

  void blanks() {
    while (i < t.size() && std::strchr(" \t\r\n", t[i]) != nullptr && t[i] != '\0') ++i;
  }
  /// A string at i (decoded into `out` when given, escapes simplified).
  bool string(std::string* out) {
    if (i >= t.size() || t[i] != '"') return false;
    ++i;
    while (i < t.size()) {
      const char c = t[i++];
      if (c == '"') return true;
      if (c == '\\') {
        if (i >= t.size()) return false;
        const char e = t[i++];
        if (e == 'u') {
          i += 4;
          if (out) out->push_back('?');
          continue;
        }
        if (out) {
          static const std::string from = "nrtbf", to = "\n\r\t\b\f";
          const std::size_t k = from.find(e);
          out->push_back(k == std::string::npos ? e : to[k]);
        }
        continue;
      }
      if (out) out->push_back(c);
    }
    return false;
  }
  bool skip_value(int depth) {
    blanks();
    if (i >= t.size() || depth > 256) return false;
    const char c = t[i];
    if (c == '"') return string(nullptr);
    if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++i;
      blanks();
      if (i < t.size() && t[i] == close) {
        ++i;
        return true;
      }
      while (true) {
        if (c == '{') {
          blanks();
          if (!string(nullptr)) return false;
          blanks();
          if (i >= t.size() || t[i] != ':') return false;
          ++i;
        }
        if (!skip_value(depth + 1)) return false;
        blanks();
        if (i >= t.size()) return false;
        if (t[i] == ',') {
          ++i;
          continue;
        }
        if (t[i] == close) {
          ++i;
          return true;
        }
        return false;
      }
    }
    while (i < t.size() && std::strchr(",}] \t\r\n", t[i]) == nullptr) ++i;
    return true;
  }
  /// Moves to the start of member `key` (in an object) or item `index` (in an array).
  bool enter(const std::string& token) {
    blanks();
    if (i >= t.size()) return false;
    if (t[i] == '{') {
      ++i;
      while (true) {
        blanks();
        std::string key;
        if (!string(&key)) return false;
        blanks();
        if (i >= t.size() || t[i] != ':') return false;
        ++i;
        if (key == token) {
          blanks();
          return true;
        }
        if (!skip_value(0)) return false;
        blanks();
        if (i >= t.size() || t[i] != ',') return false;
        ++i;
      }
    }
    if (t[i] == '[') {
      ++i;
      char* end = nullptr;
      const unsigned long index = std::strtoul(token.c_str(), &end, 10);
      if (token.empty() || *end != '\0') return false;
      for (unsigned long k = 0; k < index; ++k) {
        if (!skip_value(0)) return false;
        blanks();
        if (i >= t.size() || t[i] != ',') return false;
        ++i;
      }
      blanks();
      return true;
    }
    return false;
  }
};

std::vector<std::string> pointer_tokens(const std::string& pointer) {
  std::vector<std::string> tokens;
  std::size_t at = 0;
  while (at < pointer.size() && pointer[at] == '/') {
    const std::size_t end = std::min(pointer.find('/', at + 1), pointer.size());
    std::string token = pointer.substr(at + 1, end - at - 1);
    for (std::size_t k = 0; (k = token.find('~', k)) != std::string::npos; ++k)
      token.replace(k, 2, k + 1 < token.size() && token[k + 1] == '1' ? "/" : "~");
    tokens.push_back(token);
    at = end;
  }
  return tokens;
}

/// A DOM builder for nlohmann's SAX parser that refuses duplicate keys and remembers where
/// the text went wrong.
class LocatedDom {
 public:
  explicit LocatedDom(json& root) : root_(root) {}

  bool null() { return put(json(nullptr)); }
  bool boolean(bool b) { return put(json(b)); }
  bool number_integer(json::number_integer_t n) { return put(json(n)); }
  bool number_unsigned(json::number_unsigned_t n) { return put(json(n)); }
  bool number_float(json::number_float_t x, const json::string_t&) { return put(json(x)); }
  bool string(json::string_t& s) { return put(json(std::move(s))); }
  bool binary(json::binary_t&) { return put(json(nullptr)); }
  bool start_object(std::size_t) {
    json* made = place(json::object());
    stack_.push_back(made);
    return made != nullptr;
  }
  bool key(json::string_t& k) {
    json& object = *stack_.back();
    if (object.contains(k)) {
      duplicate_ = k;
      return false;
    }
    key_ = &object[k];
    return true;
  }
  bool end_object() {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    json* made = place(json::array());
    stack_.push_back(made);
    return made != nullptr;
  }
  bool end_array() {
    stack_.pop_back();
    return true;
  }
  template <class Exception>
  bool parse_error(std::size_t byte, const std::string&, const Exception& error) {
    error_byte_ = byte;
    error_ = error.what();
    return false;
  }

  const std::string& duplicate() const { return duplicate_; }
  std::size_t error_byte() const { return error_byte_; }
  const std::string& error() const { return error_; }

 private:
  json* place(json value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    json& top = *stack_.back();
    if (top.is_array()) {
      top.push_back(std::move(value));
      return &top.back();
    }
    *key_ = std::move(value);
    return key_;
  }
  bool put(json value) { return place(std::move(value)) != nullptr; }

  json& root_;
  std::vector<json*> stack_;
  json* key_ = nullptr;
  std::string duplicate_, error_;
  std::size_t error_byte_ = 0;
};

}  // namespace

int JsonText::line_of(const std::string& pointer) const {
  Walker w{*text_};
  for (const auto& token : pointer_tokens(pointer))
    if (!w.enter(token)) return 0;
  w.blanks();
  return line_at_byte(*text_, w.i);
}

void JsonText::refuse(const std::string& pointer, const std::string& message) const {
  throw InputError(file_, line_of(pointer), pointer, message);
}

void check_nesting(const std::string& text, const std::string& file, int max_depth,
                   const std::string& what) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (in_string) {
      if (c == '\\')
        ++k;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > max_depth)
        throw InputError(file, line_at_byte(text, k), "",
                         printf_string("arrays and objects nested more than %d deep; %s "
                                       "nests at most %d",
                                       max_depth, what.c_str(), max_depth));
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

json parse_located(const std::string& text, const std::string& file) {
  json root;
  LocatedDom dom(root);
  bool ok = false;
  try {
    ok = json::sax_parse(text, &dom);
  } catch (const json::exception& e) {  // e.g. invalid UTF-8 in a string
    throw InputError(file, 0, "", std::string("not valid JSON: ") + e.what());
  }
  if (ok) return root;
  if (!dom.duplicate().empty())
    throw InputError(
        file, 0, "",
        "the key \"" + dom.duplicate() + "\" appears twice in one object; each key once");
  std::string why = dom.error();
  // nlohmann's words after its own prefix ("[json.exception.parse_error.101] ").
  if (const std::size_t close = why.find("] ");
      why.rfind("[json.exception", 0) == 0 && close != std::string::npos)
    why = why.substr(close + 2);
  throw InputError(file, line_at_byte(text, dom.error_byte() > 0 ? dom.error_byte() - 1 : 0), "",
                   "not valid JSON: " + why);
}

std::string pointer_to(const std::string& parent, const std::string& key) {
  std::string escaped;
  for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return parent + "/" + escaped;
}

std::string pointer_to(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

std::string JsonAt::shown() const {
  const json& v = *value_;
  if (v.is_null()) return "null";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    if (s.size() > 40) s = s.substr(0, 40) + "...";
    return "the string \"" + s + "\"";
  }
  if (v.is_number()) return v.dump();
  if (v.is_array()) return "an array";
  return "an object";
}

JsonAt JsonAt::at(const std::string& key) const {
  if (!value_->is_object()) refuse("expected an object with \"" + key + "\", got " + shown());
  const auto it = value_->find(key);
  if (it == value_->end()) refuse("\"" + key + "\" is missing");
  return JsonAt(*text_, *it, pointer_to(pointer_, key));
}

std::optional<JsonAt> JsonAt::maybe(const std::string& key) const {
  if (!value_->is_object()) refuse("expected an object, got " + shown());
  const auto it = value_->find(key);
  if (it == value_->end() || it->is_null()) return std::nullopt;
  return JsonAt(*text_, *it, pointer_to(pointer_, key));
}

void JsonAt::only_keys(const std::vector<std::string>& allowed) const {
  if (!value_->is_object()) refuse("expected an object, got " + shown());
  for (auto it = value_->begin(); it != value_->end(); ++it)
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
      const std::string near = nearest_word(it.key(), allowed, 3);
      text_->refuse(pointer_to(pointer_, it.key()),
                    "unknown key \"" + it.key() + "\"" +
                        (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
    }
}

std::vector<JsonAt> JsonAt::elements(std::size_t max_items) const {
  if (!value_->is_array()) refuse("expected an array, got " + shown());
  if (value_->size() > max_items)
    refuse(printf_string("holds %zu items; at most %zu are accepted", value_->size(), max_items));
  std::vector<JsonAt> out;
  out.reserve(value_->size());
  for (std::size_t k = 0; k < value_->size(); ++k)
    out.emplace_back(*text_, (*value_)[k], pointer_to(pointer_, k));
  return out;
}

std::vector<std::pair<std::string, JsonAt>> JsonAt::members(std::size_t max_items) const {
  if (!value_->is_object()) refuse("expected an object, got " + shown());
  if (value_->size() > max_items)
    refuse(printf_string("holds %zu members; at most %zu are accepted", value_->size(), max_items));
  std::vector<std::pair<std::string, JsonAt>> out;
  for (auto it = value_->begin(); it != value_->end(); ++it)
    out.emplace_back(it.key(), JsonAt(*text_, *it, pointer_to(pointer_, it.key())));
  return out;
}

double JsonAt::number(const Range& range, const std::string& unit) const {
  if (!value_->is_number()) refuse("expected a number, got " + shown());
  const double v = value_->get<double>();
  if (!std::isfinite(v)) refuse("expected a finite number, got " + shown());
  const std::string wrong = range.violation(v, value_->dump(), unit);
  if (!wrong.empty()) refuse(wrong);
  return v;
}

std::optional<double> JsonAt::number_or_null(const Range& range, const std::string& unit) const {
  if (value_->is_null()) return std::nullopt;
  if (!value_->is_number()) refuse("expected a number or null, got " + shown());
  return number(range, unit);
}

std::int64_t JsonAt::integer(std::int64_t min, std::int64_t max) const {
  const std::string range = "from " + std::to_string(min) + " to " + std::to_string(max);
  if (!value_->is_number_integer()) refuse("expected a whole number " + range + ", got " + shown());
  if (value_->is_number_unsigned() &&
      value_->get<std::uint64_t>() > static_cast<std::uint64_t>(max))
    refuse("must be " + range + ", got " + shown());
  const std::int64_t v = value_->get<std::int64_t>();
  if (v < min || v > max) refuse("must be " + range + ", got " + shown());
  return v;
}

std::uint64_t JsonAt::unsigned_integer() const {
  if (!value_->is_number_integer() ||
      (!value_->is_number_unsigned() && value_->get<std::int64_t>() < 0))
    refuse("expected a whole number from 0 to 18446744073709551615, got " + shown());
  return value_->get<std::uint64_t>();
}

std::string JsonAt::string(std::size_t max_length) const {
  if (!value_->is_string()) refuse("expected a string, got " + shown());
  const std::string& s = value_->get_ref<const std::string&>();
  if (s.size() > max_length)
    refuse(printf_string("a string of %zu characters; at most %zu are accepted", s.size(),
                         max_length));
  return s;
}

bool JsonAt::boolean() const {
  if (!value_->is_boolean()) refuse("expected true or false, got " + shown());
  return value_->get<bool>();
}

}  // namespace ccbuild
