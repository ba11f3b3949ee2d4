#include "ccbuild/common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild {
namespace fs = std::filesystem;
namespace {

/// Absolute, with links and `..` resolved as far as the path exists.
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return path.lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

/// Whether two paths name the same file: the same inode when both exist, else the same
/// resolved path.
bool same_file(const fs::path& a, const fs::path& resolved_a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  return resolved_a == resolved(b);
}

/// Why an existing `path` cannot be written as an output file (empty when it can).
std::string unwritable(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) return "";
  switch (status.type()) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::character:
      return "is a character device (a terminal, /dev/null); ccbuild writes its outputs to "
             "regular files only: give a file name, or leave the flag out";
    case fs::file_type::directory:
      return "is a directory, expected a file name";
    case fs::file_type::fifo:
      return "is a FIFO (named pipe), which would wait for a reader; expected a file name";
    case fs::file_type::socket:
      return "is a socket; expected a file name";
    case fs::file_type::block:
      return "is a block device; ccbuild writes its outputs to regular files only: give a "
             "file name";
    default:
      return "is not a regular file; expected a file name";
  }
}

InputError refused(const fs::path& path, const std::string& flag, const std::string& why) {
  return InputError(path.string(), 0, flag, why);
}

/// Writes all of `content` to the open descriptor `fd`; false with errno on failure.
bool write_all(int fd, const std::string& content) {
  const char* at = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, at, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

fs::path temporary_beside(const fs::path& path) {
  return path.string() + ".tmp." + std::to_string(static_cast<long>(::getpid()));
}

/// Creates a new file beside `path` for its content (never over an existing one: a name
/// taken gets a counter). Returns its descriptor and sets `made`; -1 with errno on failure.
int create_beside(const fs::path& path, fs::path& made) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = temporary_beside(path).string();
    if (attempt > 0) name.append(".").append(std::to_string(attempt));
    made = name;
    const int fd = ::open(made.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

std::mutex read_mutex;
std::vector<fs::path> read_paths;
std::set<std::string> read_set;

}  // namespace

void note_file_read(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const fs::path& kept = ec ? path : absolute;
  std::lock_guard<std::mutex> lock(read_mutex);
  if (read_set.insert(kept.string()).second) read_paths.push_back(kept);
}

std::vector<fs::path> files_read() {
  std::lock_guard<std::mutex> lock(read_mutex);
  return read_paths;
}

bool is_character_device(const fs::path& path) {
  std::error_code ec;
  return fs::is_character_file(path, ec);
}

struct OutputClaims::Claim {
  std::string flag;
  fs::path path;
  fs::path resolved;  ///< absolute, links and `..` resolved
  bool folder = false;
  bool in_place = false;   ///< read back and updated in place (a journal)
  bool overwrite = false;  ///< an existing file may be replaced
  fs::path temporary;      ///< where its content was written (empty: not yet)
};

OutputClaims::OutputClaims(std::vector<fs::path> inputs, bool files_read_are_inputs)
    : inputs_(std::move(inputs)), files_read_are_inputs_(files_read_are_inputs) {}

OutputClaims::~OutputClaims() {
  if (committed_) return;
  for (const auto& claim : claims_)
    if (!claim->temporary.empty()) std::remove(claim->temporary.c_str());
}

void OutputClaims::add_input(const fs::path& path) {
  inputs_.push_back(path);
  for (const auto& claim : claims_)
    if (!claim->folder && same_file(claim->path, claim->resolved, path))
      throw refused(
          claim->path, claim->flag,
          "output would overwrite an input file (" + path.string() + "); choose another path");
}

namespace {
// What a claim in a folder that is not there is told (the folder named as the user wrote it).
std::string missing_folder(const std::string& noun, const fs::path& path) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  return noun + " '" + parent.string() + "' does not exist";
}
}  // namespace

bool OutputClaims::folder_ready(const fs::path& path) const {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(parent, ec)) return true;
  const fs::path where = resolved(parent);
  for (const auto& claim : claims_)
    if (claim->folder && claim->resolved == where) return true;
  return false;
}

void OutputClaims::check_claim_against_inputs(const Claim& claim) const {
  const auto check = [&](const fs::path& input) {
    if (same_file(claim.path, claim.resolved, input))
      throw refused(
          claim.path, claim.flag,
          "output would overwrite an input file (" + input.string() + "); choose another path");
  };
  for (const auto& input : inputs_) check(input);
  if (files_read_are_inputs_)
    for (const auto& input : files_read()) check(input);
}

void OutputClaims::check_not_input_or_claimed(const std::string& flag, const fs::path& path,
                                              const fs::path& resolved_path) const {
  Claim probe;
  probe.flag = flag;
  probe.path = path;
  probe.resolved = resolved_path;
  check_claim_against_inputs(probe);
  for (const auto& claim : claims_)
    if (same_file(path, resolved_path, claim->path) || resolved_path == claim->resolved)
      throw refused(path, flag,
                    "is the same file as " + claim->flag + " (" + claim->path.string() +
                        "); each output needs a file of its own");
}

void OutputClaims::claim_file(const std::string& flag, const fs::path& path, bool overwrite) {
  if (path.empty()) throw refused(path, flag, "expected a file name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  if (const std::string why = unwritable(path); !why.empty()) throw refused(path, flag, why);
  std::error_code ec;
  if (fs::exists(path, ec) && !overwrite)
    throw refused(path, flag, "output file exists; pass --force to overwrite it");
  if (!folder_ready(path)) throw refused(path, flag, missing_folder("output folder", path));
  auto claim = std::make_unique<Claim>();
  claim->flag = flag;
  claim->path = path;
  claim->resolved = where;
  claim->overwrite = overwrite;
  claims_.push_back(std::move(claim));
}

void OutputClaims::claim_derived(const std::string& flag, const fs::path& path,
                                 const fs::path& owner, bool overwrite, const std::string& mark) {
  std::error_code ec;
  if (overwrite && fs::is_regular_file(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    if (mark.empty() || head.find(mark) == std::string::npos)
      throw refused(path, flag,
                    "exists, and is not the file ccbuild wrote beside " + owner.string() +
                        " before (--force replaces only that one): move it away, or choose "
                        "another output name");
  }
  claim_file(flag, path, overwrite);
}

void OutputClaims::claim_read_write(const std::string& flag, const fs::path& path,
                                    const std::vector<std::string>& siblings) {
  if (path.empty()) throw refused(path, flag, "expected a file name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    throw refused(path, flag, unwritable(path));
  }
  if (!folder_ready(path)) throw refused(path, flag, missing_folder("folder", path));
  const auto add = [&](const fs::path& p, const fs::path& r) {
    auto claim = std::make_unique<Claim>();
    claim->flag = flag;
    claim->path = p;
    claim->resolved = r;
    claim->in_place = true;
    claims_.push_back(std::move(claim));
  };
  add(path, where);
  for (const auto& suffix : siblings) {
    const fs::path sibling = path.string() + suffix;
    const fs::path sibling_where = resolved(sibling);
    check_not_input_or_claimed(flag, sibling, sibling_where);
    add(sibling, sibling_where);
  }
}

void OutputClaims::claim_folder(const std::string& flag, const fs::path& path) {
  if (path.empty()) throw refused(path, flag, "expected a folder name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec))
    throw refused(path, flag, "exists and is not a folder; expected a folder name");
  auto claim = std::make_unique<Claim>();
  claim->flag = flag;
  claim->path = path;
  claim->resolved = where;
  claim->folder = true;
  claims_.push_back(std::move(claim));
}

OutputClaims::Claim& OutputClaims::claimed(const fs::path& path) {
  for (const auto& claim : claims_)
    if (!claim->folder && !claim->in_place && claim->path == path) return *claim;
  CCBUILD_CHECK(false, "an output written without being claimed first: " + path.string());
  throw InternalError("unreachable");
}

fs::path OutputClaims::writing_path(const fs::path& path) {
  Claim& claim = claimed(path);
  if (claim.temporary.empty()) {
    fs::path made;
    const int fd = create_beside(path, made);
    if (fd < 0)
      throw InputError(path.string(), 0, "",
                       std::string("cannot create output file: ") + std::strerror(errno));
    ::close(fd);
    claim.temporary = made;
  }
  return claim.temporary;
}

void OutputClaims::write(const fs::path& path, const std::string& content) {
  Claim& claim = claimed(path);
  if (!claim.temporary.empty()) std::remove(claim.temporary.c_str());
  claim.temporary.clear();
  fs::path made;
  const int fd = create_beside(path, made);
  if (fd < 0)
    throw InputError(path.string(), 0, "",
                     std::string("cannot create output file: ") + std::strerror(errno));
  claim.temporary = made;
  const bool written = write_all(fd, content);
  const int write_errno = errno;
  const bool closed = ::close(fd) == 0;
  if (!written || !closed) {
    std::remove(made.c_str());
    claim.temporary.clear();
    throw InputError(
        path.string(), 0, "",
        std::string("cannot write output file: ") + std::strerror(!written ? write_errno : errno));
  }
}

void OutputClaims::commit() {
  CCBUILD_CHECK(!committed_, "outputs committed twice");
  // Every claim again: a file read since it was made, or one made there since, is refused
  // before any output is moved.
  const auto remove_temporaries = [&] {
    for (const auto& claim : claims_)
      if (!claim->temporary.empty()) std::remove(claim->temporary.c_str());
  };
  for (const auto& claim : claims_) {
    if (claim->folder || claim->in_place || claim->temporary.empty()) continue;
    try {
      check_claim_against_inputs(*claim);
      if (const std::string why = unwritable(claim->path); !why.empty())
        throw refused(claim->path, claim->flag, why);
      std::error_code ec;
      if (!claim->overwrite && fs::exists(claim->path, ec))
        throw refused(claim->path, claim->flag,
                      "output file was made by someone else while this run worked; pass "
                      "--force to overwrite it");
    } catch (...) {
      remove_temporaries();  // nothing of this run left behind
      throw;
    }
  }
  // Each file in place, the one it replaces kept aside until all are.
  struct Moved {
    const Claim* claim;
    fs::path kept;  ///< the replaced file, aside (empty: there was none)
  };
  std::vector<Moved> moved;
  const auto undo = [&] {
    for (auto it = moved.rbegin(); it != moved.rend(); ++it) {
      if (it->kept.empty())
        std::remove(it->claim->path.c_str());
      else
        std::rename(it->kept.c_str(), it->claim->path.c_str());
    }
    remove_temporaries();
  };
  for (const auto& claim : claims_) {
    if (claim->temporary.empty()) continue;
    Moved m{claim.get(), {}};
    std::error_code ec;
    if (fs::exists(claim->path, ec)) {
      m.kept = claim->path.string() + ".old." + std::to_string(static_cast<long>(::getpid()));
      fs::rename(claim->path, m.kept, ec);
      if (ec) {
        undo();
        throw InputError(claim->path.string(), 0, claim->flag,
                         "cannot replace the existing file: " + ec.message() +
                             "; no output of this run was written");
      }
    }
    fs::rename(claim->temporary, claim->path, ec);
    if (ec) {
      if (!m.kept.empty()) std::rename(m.kept.c_str(), claim->path.c_str());
      undo();
      throw InputError(claim->path.string(), 0, claim->flag,
                       "cannot move finished output into place: " + ec.message() +
                           "; no output of this run was written");
    }
    claim->temporary.clear();
    moved.push_back(m);
  }
  committed_ = true;
  for (const auto& m : moved)
    if (!m.kept.empty()) std::remove(m.kept.c_str());
}

void check_output_path(const fs::path& path, bool overwrite, const std::vector<fs::path>& inputs) {
  OutputClaims(inputs, false).claim_file("", path, overwrite);
}

void write_file_atomically(const fs::path& path, const std::string& content, bool overwrite,
                           const std::vector<fs::path>& inputs) {
  OutputClaims outputs(inputs, false);
  outputs.claim_file("", path, overwrite);
  outputs.write(path, content);
  outputs.commit();
}

}  // namespace ccbuild
