#include "note_log.hpp"

#include "ccbuild/common/format.hpp"

namespace ccbuild::import::detail {

void NoteLog::add(const std::string& kind, std::string text) {
  if (++count_[kind] > kMaxNotesPerKind) return;
  kept_.emplace_back(kind, std::move(text));
  kept_left_out_.push_back(false);
}

void NoteLog::left_out(const std::string& kind, std::string text) {
  add(kind, std::move(text));
  if (!kept_left_out_.empty() && kept_.back().first == kind && count_[kind] <= kMaxNotesPerKind)
    kept_left_out_.back() = true;
}

std::vector<std::string> NoteLog::left_out_lines() const {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < kept_.size(); ++k)
    if (kept_left_out_[k]) out.push_back(kept_[k].second);
  return out;
}

void NoteLog::add_all(const std::vector<std::string>& lines, const std::string& kind) {
  for (const std::string& line : lines) add(kind, line);
}

std::vector<std::string> NoteLog::lines() const {
  std::vector<std::string> out;
  out.reserve(kept_.size() + count_.size());
  std::map<std::string, std::size_t> seen;
  for (const auto& [kind, text] : kept_) {
    out.push_back(text);
    const std::size_t all = count_.at(kind);
    if (++seen[kind] == kMaxNotesPerKind && all > kMaxNotesPerKind)
      out.push_back(
          printf_string("and %zu more of the same kind: %s", all - kMaxNotesPerKind, kind.c_str()));
  }
  return out;
}

}  // namespace ccbuild::import::detail
