#pragma once
// What an importer says it left out or ignored, capped: the first kMaxNotesPerKind notes of
// each kind, then one line saying how many more of that kind there were. A drawing of a
// thousand duplicated lines says so in a few lines, not in one per pair (issue 49: 26 MB of
// stderr). Internal to ccbuild::import; every importer's notes go through it.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "ccbuild/common/limits.hpp"

namespace ccbuild::import::detail {

/// Notes of one kind said one by one; more are counted, and said as one line (the cap on
/// reported problems, limits::kMaxListed).
inline constexpr std::size_t kMaxNotesPerKind = limits::kMaxListed;

class NoteLog {
 public:
  /// Keeps `text` when fewer than kMaxNotesPerKind notes of `kind` were kept (`kind`: a
  /// short description that completes "and N more of the same kind: ..."), else counts it.
  void add(const std::string& kind, std::string text);
  /// The same for a note that says something of the drawing or model was left out.
  void left_out(const std::string& kind, std::string text);
  /// Notes of other logs, or lines already capped (each its own kind: one line each).
  void add_all(const std::vector<std::string>& lines, const std::string& kind);
  /// The notes kept, in the order they came, each kind's count of those not kept right after
  /// its last kept note.
  std::vector<std::string> lines() const;
  bool empty() const { return kept_.empty(); }
  /// The notes kept that say something was left out, in the order they came.
  std::vector<std::string> left_out_lines() const;
  /// The first note kept (for an error that wants an example), or "".
  std::string first() const { return kept_.empty() ? std::string() : kept_.front().second; }

 private:
  std::vector<std::pair<std::string, std::string>> kept_;  ///< (kind, text)
  std::vector<bool> kept_left_out_;                        ///< by kept_'s index
  std::map<std::string, std::size_t> count_;               ///< by kind, all of them
};

}  // namespace ccbuild::import::detail
