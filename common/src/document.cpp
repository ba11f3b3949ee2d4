#include "ccbuild/common/document.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/limits.hpp"

namespace ccbuild {
namespace {

// ---------------------------------------------------------------- YAML -------------
int yaml_line(const YAML::Node& node, int fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : fallback;
}

// Converts yaml-cpp's tree, which shares aliased nodes, into ours, which copies them: so
// expansion is counted (an alias "billion laughs" stops at the value limit) and depth is
// bounded (an alias that contains itself stops at the depth limit, not the stack's end).
class YamlConverter {
 public:
  explicit YamlConverter(const std::string& file) : file_(file) {}

  DocNode convert(const YAML::Node& node, int fallback_line, int depth) {
    DocNode out;
    out.line = yaml_line(node, fallback_line);
    if (++values_ > limits::kMaxDocumentValues)
      throw InputError(file_, out.line, "",
                       "the document holds more than " +
                           std::to_string(limits::kMaxDocumentValues) +
                           " values once its aliases are expanded; this is not a plausible "
                           "ccbuild file (an alias bomb?)");
    if (depth > limits::kMaxNestingDepth)
      throw InputError(file_, out.line, "",
                       "maps and lists are nested more than " +
                           std::to_string(limits::kMaxNestingDepth) +
                           " levels deep (an alias that refers to itself?)");
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
        for (const auto& item : node) out.items.push_back(convert(item, out.line, depth + 1));
        break;
      case YAML::NodeType::Map: {
        out.kind = DocNode::Kind::kMap;
        std::set<std::string> seen;
        for (const auto& entry : node) {
          const int key_line = yaml_line(entry.first, out.line);
          if (!entry.first.IsScalar())
            throw InputError(file_, key_line, "", "map keys must be plain words");
          std::string key = entry.first.Scalar();
          if (!seen.insert(key).second)
            throw InputError(file_, key_line, key,
                             "key '" + key + "' appears twice in the same map");
          DocNode value = convert(entry.second, key_line, depth + 1);
          value.key_line = key_line;
          out.entries.emplace_back(std::move(key), std::move(value));
        }
        break;
      }
    }
    return out;
  }

 private:
  const std::string& file_;
  std::size_t values_ = 0;
};

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
    if (++values_ > limits::kMaxDocumentValues)
      throw InputError(
          file_, node.line, "",
          "the document holds more than " + std::to_string(limits::kMaxDocumentValues) + " values");
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
    // The tree is destroyed recursively: bound its depth before it can grow past it.
    if (static_cast<int>(stack_.size()) >= limits::kMaxNestingDepth)
      throw InputError(file_, tracker_.token_line, "",
                       "objects and arrays are nested more than " +
                           std::to_string(limits::kMaxNestingDepth) + " levels deep");
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
  std::size_t values_ = 0;
};

// -------------------------------------------------------------- helpers ------------
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

namespace {
std::atomic<std::size_t> text_files_count{0};
}  // namespace

std::size_t text_files_read() {
  return text_files_count.load();
}

std::string read_text_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw InputError(path.string(), 0, "", "cannot open file (does it exist?)");
  if (fs::is_directory(status))
    throw InputError(path.string(), 0, "", "is a directory, expected a file");
  // A FIFO would block the run and a device such as /dev/zero never ends: only regular
  // files are read, and only up to the size limit.
  if (!fs::is_regular_file(status))
    throw InputError(path.string(), 0, "",
                     "is not a regular file (a FIFO, device or socket?); expected a file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > limits::kMaxInputFileBytes)
    throw InputError(path.string(), 0, "",
                     "is " + std::to_string(size / (1024 * 1024)) +
                         " MiB; ccbuild reads input files of at most " +
                         std::to_string(limits::kMaxInputFileBytes / (1024 * 1024)) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file (permissions?)");
  // In chunks, never past the limit even if the file grows while it is read.
  std::string text;
  if (!ec) text.reserve(static_cast<std::size_t>(size));
  char chunk[64 * 1024];
  while (in && text.size() <= limits::kMaxInputFileBytes) {
    in.read(chunk, sizeof chunk);
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path.string(), 0, "", "cannot read file");
  if (text.size() > limits::kMaxInputFileBytes)
    throw InputError(path.string(), 0, "",
                     "is larger than " +
                         std::to_string(limits::kMaxInputFileBytes / (1024 * 1024)) +
                         " MiB, the most ccbuild reads");
  ++text_files_count;
  note_file_read(path);  // an input of this run: never one of its outputs
  return text;
}

namespace {

std::string yaml_scalar(const DocNode& node) {
  if (node.kind == DocNode::Kind::kNull) return "null";
  if (!node.quoted) return node.text;
  std::string out = "\"";
  for (char c : node.text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

bool all_scalars(const DocNode& node) {
  for (const auto& [key, value] : node.entries)
    if (value.kind == DocNode::Kind::kMap || value.kind == DocNode::Kind::kSequence) return false;
  return true;
}

void write_yaml(const DocNode& node, int indent, std::string& out) {
  const std::string pad(indent, ' ');
  if (node.kind == DocNode::Kind::kMap) {
    if (node.entries.empty()) {
      out += pad + "{}\n";
      return;
    }
    for (const auto& [key, value] : node.entries) {
      out += pad + key + ":";
      if (value.kind == DocNode::Kind::kMap && !value.entries.empty()) {
        out += "\n";
        write_yaml(value, indent + 2, out);
      } else if (value.kind == DocNode::Kind::kSequence && !value.items.empty()) {
        out += "\n";
        write_yaml(value, indent + 2, out);
      } else if (value.kind == DocNode::Kind::kSequence) {
        out += " []\n";
      } else if (value.kind == DocNode::Kind::kMap) {
        out += " {}\n";
      } else {
        out += " " + yaml_scalar(value) + "\n";
      }
    }
  } else if (node.kind == DocNode::Kind::kSequence) {
    for (const auto& item : node.items) {
      if (item.kind == DocNode::Kind::kMap && all_scalars(item)) {
        std::string line;
        for (const auto& [key, value] : item.entries)
          line += (line.empty() ? "" : ", ") + key + ": " + yaml_scalar(value);
        out += pad + "- {" + line + "}\n";
      } else if (item.kind == DocNode::Kind::kMap || item.kind == DocNode::Kind::kSequence) {
        std::string inner;
        write_yaml(item, indent + 2, inner);
        out += pad + "- " + inner.substr(indent + 2);
      } else {
        out += pad + "- " + yaml_scalar(item) + "\n";
      }
    }
  } else {
    out += pad + yaml_scalar(node) + "\n";
  }
}

}  // namespace

std::string to_yaml(const DocNode& root, const std::string& comment) {
  std::string out;
  std::size_t start = 0;
  while (start < comment.size()) {
    const std::size_t end = std::min(comment.find('\n', start), comment.size());
    out += "# " + comment.substr(start, end - start) + "\n";
    start = end + 1;
  }
  write_yaml(root, 0, out);
  return out;
}

namespace {

/// Reads YAML's events only, to find where each document starts and whether it holds
/// anything: yaml-cpp 0.7's LoadAll loops for ever (and fills memory) on a stray flow
/// entry (`,`) where a node should be, returning an empty document each time without
/// reading on.
class DocumentScan : public YAML::EventHandler {
 public:
  struct Start {
    int line = 0;          ///< 1-based
    int position = 0;      ///< in bytes
    bool empty = true;     ///< no node but a null
    int content_line = 0;  ///< 1-based, of its first node
  };
  std::vector<Start> documents;

  void OnDocumentStart(const YAML::Mark& mark) override {
    documents.push_back({mark.line + 1, mark.pos, true});
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { content(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    content(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    content(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    content(mark);
  }
  void OnMapEnd() override {}

 private:
  void content(const YAML::Mark& mark) {
    if (documents.empty() || !documents.back().empty) return;
    documents.back().empty = false;
    documents.back().content_line = mark.line + 1;
  }
};

/// How many documents `text` holds. Throws InputError when more than one has content, or
/// when yaml-cpp stops reading on (an empty document at the same place twice).
std::size_t count_documents(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentScan scan;
  while (parser.HandleNextDocument(scan)) {
    const auto& d = scan.documents;
    if (d.size() >= 2 && d[d.size() - 1].position == d[d.size() - 2].position)
      throw InputError(file, d.back().line, "",
                       "invalid YAML: a token where a value should start (a stray ',' "
                       "outside brackets?)");
    // A second document would otherwise be ignored without a word.
    for (std::size_t k = 1; k < d.size(); ++k)
      if (!d[k].empty)
        throw InputError(file, d[k].content_line, "",
                         "a second YAML document starts here (after '---'); a ccbuild file "
                         "holds one document");
  }
  return scan.documents.size();
}

}  // namespace

Document parse_yaml(const std::string& text, const std::string& file) {
  // YAML is Unicode text: a stray byte would reach names, messages and JSON outputs.
  if (const std::size_t bad = first_invalid_utf8(text); bad != std::string::npos)
    throw InputError(file, 1 + static_cast<int>(std::count(text.begin(), text.begin() + bad, '\n')),
                     "",
                     printf_string("is not UTF-8 text: byte 0x%02x at offset %zu does not start "
                                   "or continue a character; save the file as UTF-8",
                                   static_cast<unsigned char>(text[bad]), bad));
  std::vector<YAML::Node> documents;
  try {
    if (count_documents(text, file) > 0) documents = {YAML::Load(text)};
  } catch (const YAML::Exception& error) {
    std::string message = error.msg;
    // yaml-cpp's depth guard says only "bad file".
    if (message == "bad file")
      message = "too deeply nested or malformed (yaml-cpp stopped reading here)";
    throw InputError(file, error.mark.line >= 0 ? error.mark.line + 1 : 0, "",
                     "invalid YAML: " + message);
  }
  if (documents.empty()) {
    DocNode empty;
    empty.line = 1;
    return Document{file, std::move(empty)};
  }
  YamlConverter converter(file);
  return Document{file, converter.convert(documents[0], 1, 0)};
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
    fail("expected a finite number, got '" + echoed(node_->text) +
         "' (NaN and infinity are not allowed)");
  double value = 0.0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (text.empty() || ec != std::errc() || ptr != end)
    fail("expected a number, got '" + echoed(node_->text) + "'");
  if (!std::isfinite(value))
    fail("expected a finite number, got '" + echoed(node_->text) +
         "' (NaN and infinity are not allowed)");
  return value;
}

double Field::as_number_in(const Range& range_si, const std::string& unit,
                           double si_per_unit) const {
  const double value = as_number() * si_per_unit;
  const std::string wrong =
      range_si.violation(value, node_->text + (unit.empty() ? "" : " " + unit), unit, si_per_unit);
  if (!wrong.empty()) fail(wrong);
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
    fail("expected a positive integer id, got '" + echoed(node_->text) + "'");
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
    fail("expected a non-negative integer, got '" + echoed(node_->text) + "'");
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
    const std::string best = nearest_word(name, allowed_, 3);  // only near misses
    if (!best.empty()) message += "; did you mean '" + best + "'?";
    std::string list;
    for (const auto& candidate : allowed_) list += (list.empty() ? "" : ", ") + candidate;
    message += " (expected one of: " + list + ")";
    throw InputError(field_.file(), value.key_line > 0 ? value.key_line : value.line,
                     join_path(field_.path(), name), message);
  }
}

}  // namespace ccbuild
