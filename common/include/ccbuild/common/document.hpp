#pragma once
// A small, read-only document tree that remembers where every value came from. YAML and
// JSON files both load into it, so one reader validates both encodings and reports the
// same field paths, with the line of the offending value.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/common/format.hpp"

namespace ccbuild {

/// A node of a loaded YAML or JSON document.
struct DocNode {
  enum class Kind { kNull, kScalar, kMap, kSequence };
  Kind kind = Kind::kNull;
  std::string text;     ///< scalar text as written (numbers are not converted yet)
  bool quoted = false;  ///< scalar was a quoted string ("1" is text, 1 is a number)
  std::vector<std::pair<std::string, DocNode>> entries;  ///< map entries, in file order
  std::vector<DocNode> items;                            ///< sequence items
  int line = 0;                                          ///< 1-based line of the value
  int key_line = 0;  ///< 1-based line of the key, when this node is a map value
};

struct Document {
  std::string file;  ///< path as the user gave it, used in messages
  DocNode root;
};

/// Parses YAML text. Throws InputError (with the line) on a syntax error or a
/// duplicate map key.
Document parse_yaml(const std::string& text, const std::string& file);
/// Parses strict JSON text. Throws InputError (with the line) on a syntax error or a
/// duplicate object key.
Document parse_json(const std::string& text, const std::string& file);
/// Reads a file and parses it as JSON when it ends in `.json`, else as YAML. Throws
/// InputError when the file cannot be read or does not parse.
Document load_document(const std::filesystem::path& path);
/// Writes a document tree as block YAML that parse_yaml reads back to the same tree
/// (quoted scalars stay quoted; a map of scalars inside a sequence is written on one
/// line). `comment` (lines without "# ") goes first.
std::string to_yaml(const DocNode& root, const std::string& comment = "");
/// Reads a whole file. Throws InputError naming the file when it cannot be read, is not a
/// regular file (a FIFO, a device), or is larger than limits::kMaxInputFileBytes.
std::string read_text_file(const std::filesystem::path& path);
/// How many files read_text_file has read in this process: lets tests prove that each
/// input file is read once.
std::size_t text_files_read();

/// A view of one node with its path in the document, for typed, validated reads. All
/// accessors throw InputError naming file, line and path, and saying what was expected.
class Field {
 public:
  Field(const Document& document, const DocNode& node, std::string path)
      : document_(&document), node_(&node), path_(std::move(path)) {}

  static Field root(const Document& document) { return {document, document.root, ""}; }

  const DocNode& node() const { return *node_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return document_->file; }
  int line() const { return node_->line; }

  bool is_map() const { return node_->kind == DocNode::Kind::kMap; }
  bool is_sequence() const { return node_->kind == DocNode::Kind::kSequence; }
  bool is_scalar() const { return node_->kind == DocNode::Kind::kScalar; }
  bool is_string() const { return is_scalar() && node_->quoted; }

  /// A finite decimal number (rejects NaN, infinities and text).
  double as_number() const;
  /// A number in the file's unit (`si_per_unit` SI units per file unit, `unit` its name)
  /// whose SI value lies in `range_si`; returns the SI value. Out of range throws an
  /// InputError that states the range in the file's unit.
  double as_number_in(const Range& range_si, const std::string& unit = "",
                      double si_per_unit = 1.0) const;
  /// A positive integer identifier (1, 2, ...).
  std::int64_t as_positive_id() const;
  /// A non-negative integer.
  std::int64_t as_count() const;
  /// Any scalar, as text.
  std::string as_string() const;
  /// true/false.
  bool as_bool() const;
  /// The items of a sequence (throws when this is not a sequence).
  std::vector<Field> items() const;

  /// A node below this one, at the given path (used by MapReader).
  Field child(const DocNode& node, std::string path) const {
    return Field(*document_, node, std::move(path));
  }

  /// Throws InputError at this node: "<path>: <message>".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  const Document* document_;
  const DocNode* node_;
  std::string path_;
};

/// Reads the keys of a map node and rejects the ones nobody asked for, so that a typo
/// (`thicknes:`) is an error instead of being silently ignored.
class MapReader {
 public:
  /// `allowed` lists every key this map may hold (for the unknown-key message).
  MapReader(const Field& field, std::vector<std::string> allowed);

  bool has(const std::string& key) const;
  std::optional<Field> optional(const std::string& key) const;
  Field required(const std::string& key) const;
  /// Throws InputError for the first key not in `allowed`, suggesting the closest one.
  void reject_unknown() const;
  const Field& field() const { return field_; }

 private:
  Field field_;
  std::vector<std::string> allowed_;
};

/// Joins a parent path and a key: ("floors[0]", "plan") -> "floors[0].plan".
std::string join_path(const std::string& parent, const std::string& key);
/// ("walls", 3) -> "walls[3]".
std::string index_path(const std::string& parent, std::size_t index);

}  // namespace ccbuild
