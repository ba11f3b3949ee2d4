#include "ccbuild/common/document.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild {
namespace {

// ---------------------------------------------------------------- YAML -------------
int yaml_line(const YAML::Node& node, int fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : fallback;
}

DocNode from_yaml(const YAML::Node& node, const std::string& file, int fallback_line) {
  DocNode out;
  out.line = yaml_line(node, fallback_line);
  switch (node.Type()) {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null:
      out.kind = DocNode::Kind::kNull;
      break;
    case YAML::NodeType::Scalar:
      out.kind = DocNode::Kind::kScalar;
      out.text = node.Scalar();
      // yaml-cpp tags quoted scalars "!" and plain ones "?".
      out.quoted = node.Tag() == "!";
      break;
    case YAML::NodeType::Sequence:
      out.kind = DocNode::Kind::kSequence;
      for (const auto& item : node) out.items.push_back(from_yaml(item, file, out.line));
      break;
    case YAML::NodeType::Map: {
      out.kind = DocNode::Kind::kMap;
      std::set<std::string> seen;
      for (const auto& entry : node) {
        const int key_line = yaml_line(entry.first, out.line);
        if (!entry.first.IsScalar())
          throw InputError(file, key_line, "", "map keys must be plain words");
        std::string key = entry.first.Scalar();
        if (!seen.insert(key).second)
          throw InputError(file, key_line, key, "key '" + key + "' appears twice in the same map");
        DocNode value = from_yaml(entry.second, file, key_line);
        value.key_line = key_line;
        out.entries.emplace_back(std::move(key), std::move(value));
      }
      break;
    }
  }
  return out;
}

// ---------------------------------------------------------------- JSON -------------
// nlohmann's SAX events carry no position, so the parser reads through an iterator that
// counts lines; at each event the line of the last non-blank character read is the
// line of the token just parsed.
struct LineTracker {
  int line = 1;
  int token_line = 1;
};

class TrackingIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* position, LineTracker* tracker)
      : position_(position), tracker_(tracker) {}
  reference operator*() const { return *position_; }
  TrackingIterator& operator++() {
    const char c = *position_;
    if (c == '\n') {
      ++tracker_->line;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      tracker_->token_line = tracker_->line;
    }
    ++position_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackingIterator& other) const { return position_ == other.position_; }
  bool operator!=(const TrackingIterator& other) const { return position_ != other.position_; }

 private:
  const char* position_;
  LineTracker* tracker_;
};

class JsonBuilder : public nlohmann::json_sax<nlohmann::json> {
 public:
  JsonBuilder(const std::string& file, const LineTracker& tracker)
      : file_(file), tracker_(tracker) {}

  DocNode take_root() { return std::move(root_); }

  bool null() override { return add(DocNode{}); }
  bool boolean(bool value) override { return add(scalar(value ? "true" : "false", false)); }
  bool number_integer(number_integer_t value) override {
    return add(scalar(std::to_string(value), false));
  }
  bool number_unsigned(number_unsigned_t value) override {
    return add(scalar(std::to_string(value), false));
  }
  bool number_float(number_float_t, const string_t& text) override {
    return add(scalar(text, false));
  }
  bool string(string_t& value) override { return add(scalar(value, true)); }
  bool binary(binary_t&) override { return false; }
  bool start_object(std::size_t) override {
    DocNode node;
    node.kind = DocNode::Kind::kMap;
    return open(std::move(node));
  }
  bool key(string_t& value) override {
    DocNode& map = *stack_.back();
    for (const auto& entry : map.entries) {
      if (entry.first == value)
        throw InputError(file_, tracker_.token_line, value,
                         "key '" + value + "' appears twice in the same object");
    }
    pending_key_ = value;
    pending_key_line_ = tracker_.token_line;
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    DocNode node;
    node.kind = DocNode::Kind::kSequence;
    return open(std::move(node));
  }
  bool end_array() override {
    stack_.pop_back();
    return true;
  }
  bool parse_error(std::size_t, const std::string&,
                   const nlohmann::detail::exception& error) override {
    std::string message = error.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error..."
    if (const auto colon = message.find(": "); colon != std::string::npos)
      message = message.substr(colon + 2);
    throw InputError(file_, tracker_.line, "", "invalid JSON: " + message);
  }

 private:
  DocNode scalar(std::string text, bool quoted) const {
    DocNode node;
    node.kind = DocNode::Kind::kScalar;
    node.text = std::move(text);
    node.quoted = quoted;
    return node;
  }
  // Places a finished value into its parent; returns a pointer to where it now lives.
  DocNode* place(DocNode node) {
    node.line = tracker_.token_line;
    if (stack_.empty()) {
      root_ = std::move(node);
      return &root_;
    }
    DocNode& parent = *stack_.back();
    if (parent.kind == DocNode::Kind::kMap) {
      node.key_line = pending_key_line_;
      parent.entries.emplace_back(pending_key_, std::move(node));
      return &parent.entries.back().second;
    }
    parent.items.push_back(std::move(node));
    return &parent.items.back();
  }
  bool add(DocNode node) {
    place(std::move(node));
    return true;
  }
  bool open(DocNode node) {
    // Children are appended only to the innermost open container, so pointers to
    // outer containers stay valid while it fills.
    stack_.push_back(place(std::move(node)));
    return true;
  }

  const std::string& file_;
  const LineTracker& tracker_;
  DocNode root_;
  std::vector<DocNode*> stack_;
  std::string pending_key_;
  int pending_key_line_ = 0;
};

// -------------------------------------------------------------- helpers ------------
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

std::string describe(const DocNode& node) {
  switch (node.kind) {
    case DocNode::Kind::kNull:
      return "nothing";
    case DocNode::Kind::kMap:
      return "a map";
    case DocNode::Kind::kSequence:
      return "a list";
    case DocNode::Kind::kScalar:
      return node.quoted ? "the string \"" + node.text + "\"" : "'" + node.text + "'";
  }
  return "?";
}

}  // namespace

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string index_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

std::string read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), 0, "", "is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file (does it exist?)");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), 0, "", "cannot read file");
  return text.str();
}

Document parse_yaml(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw InputError(file, error.mark.line >= 0 ? error.mark.line + 1 : 0, "",
                     "invalid YAML: " + error.msg);
  }
  return Document{file, from_yaml(root, file, 1)};
}

Document parse_json(const std::string& text, const std::string& file) {
  LineTracker tracker;
  JsonBuilder builder(file, tracker);
  const char* begin = text.data();
  nlohmann::json::sax_parse(TrackingIterator(begin, &tracker),
                            TrackingIterator(begin + text.size(), &tracker), &builder);
  return Document{file, builder.take_root()};
}

Document load_document(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  if (path.extension() == ".json") return parse_json(text, path.string());
  return parse_yaml(text, path.string());
}

// ---------------------------------------------------------------- Field ------------
void Field::fail(const std::string& message) const {
  throw InputError(document_->file, node_->line, path_, message);
}

double Field::as_number() const {
  if (!is_scalar() || node_->quoted) fail("expected a number, got " + describe(*node_));
  std::string text = node_->text;
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  // YAML spells the special values .nan, .inf, -.inf; from_chars does not know them.
  std::string lower;
  for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".nan" || lower == ".inf" || lower == "-.inf")
    fail("expected a finite number, got '" + node_->text + "' (NaN and infinity are not allowed)");
  double value = 0.0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (text.empty() || ec != std::errc() || ptr != end)
    fail("expected a number, got '" + node_->text + "'");
  if (!std::isfinite(value))
    fail("expected a finite number, got '" + node_->text + "' (NaN and infinity are not allowed)");
  return value;
}

std::int64_t Field::as_positive_id() const {
  if (!is_scalar() || node_->quoted)
    fail("expected a positive integer id, got " + describe(*node_));
  std::int64_t value = 0;
  const char* begin = node_->text.data();
  const char* end = begin + node_->text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || value <= 0)
    fail("expected a positive integer id, got '" + node_->text + "'");
  return value;
}

std::int64_t Field::as_count() const {
  if (!is_scalar() || node_->quoted)
    fail("expected a non-negative integer, got " + describe(*node_));
  std::int64_t value = 0;
  const char* begin = node_->text.data();
  const char* end = begin + node_->text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || value < 0)
    fail("expected a non-negative integer, got '" + node_->text + "'");
  return value;
}

std::string Field::as_string() const {
  if (!is_scalar()) fail("expected a single value, got " + describe(*node_));
  return node_->text;
}

bool Field::as_bool() const {
  if (is_scalar() && !node_->quoted) {
    if (node_->text == "true") return true;
    if (node_->text == "false") return false;
  }
  fail("expected true or false, got " + describe(*node_));
}

std::vector<Field> Field::items() const {
  if (!is_sequence()) fail("expected a list, got " + describe(*node_));
  std::vector<Field> out;
  out.reserve(node_->items.size());
  for (std::size_t i = 0; i < node_->items.size(); ++i)
    out.emplace_back(*document_, node_->items[i], index_path(path_, i));
  return out;
}

// ------------------------------------------------------------ MapReader ------------
MapReader::MapReader(const Field& field, std::vector<std::string> allowed)
    : field_(field), allowed_(std::move(allowed)) {
  if (!field_.is_map()) field_.fail("expected a map of keys, got " + describe(field_.node()));
}

bool MapReader::has(const std::string& key) const {
  return optional(key).has_value();
}

std::optional<Field> MapReader::optional(const std::string& key) const {
  for (const auto& [name, value] : field_.node().entries) {
    if (name == key) return field_.child(value, join_path(field_.path(), key));
  }
  return std::nullopt;
}

Field MapReader::required(const std::string& key) const {
  if (auto value = optional(key)) return *value;
  field_.fail("missing required key '" + key + "'");
}

void MapReader::reject_unknown() const {
  for (const auto& [name, value] : field_.node().entries) {
    if (std::find(allowed_.begin(), allowed_.end(), name) != allowed_.end()) continue;
    std::string message = "unknown key '" + name + "'";
    std::string best;
    std::size_t best_distance = 3;  // suggest only near misses
    for (const auto& candidate : allowed_) {
      const std::size_t d = edit_distance(name, candidate);
      if (d < best_distance) {
        best_distance = d;
        best = candidate;
      }
    }
    if (!best.empty()) message += "; did you mean '" + best + "'?";
    std::string list;
    for (const auto& candidate : allowed_) list += (list.empty() ? "" : ", ") + candidate;
    message += " (expected one of: " + list + ")";
    throw InputError(field_.file(), value.key_line > 0 ? value.key_line : value.line,
                     join_path(field_.path(), name), message);
  }
}

}  // namespace ccbuild
