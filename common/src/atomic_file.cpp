#include "ccbuild/common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

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

/// Why an existing `path` cannot be written as an output file (empty when it can), and
/// whether it is a character device.
std::string unwritable(const fs::path& path, bool& device) {
  device = false;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) return "";
  switch (status.type()) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::character:
      device = true;
      return "";
    case fs::file_type::directory:
      return "is a directory, expected a file name";
    case fs::file_type::fifo:
      return "is a FIFO (named pipe), which would wait for a reader; expected a file name";
    case fs::file_type::socket:
      return "is a socket; expected a file name";
    case fs::file_type::block:
      return "is a block device, never written; expected a file name";
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

}  // namespace

bool is_character_device(const fs::path& path) {
  std::error_code ec;
  return fs::is_character_file(path, ec);
}

OutputClaims::OutputClaims(std::vector<fs::path> inputs) : inputs_(std::move(inputs)) {}

void OutputClaims::add_input(const fs::path& path) {
  inputs_.push_back(path);
}

bool OutputClaims::folder_ready(const fs::path& path) const {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(parent, ec)) return true;
  const fs::path where = resolved(parent);
  for (const auto& claim : claims_)
    if (claim.folder && claim.resolved == where) return true;
  return false;
}

void OutputClaims::check_not_input_or_claimed(const std::string& flag, const fs::path& path,
                                              const fs::path& resolved_path) const {
  for (const auto& input : inputs_)
    if (same_file(path, resolved_path, input))
      throw refused(
          path, flag,
          "output would overwrite an input file (" + input.string() + "); choose another path");
  for (const auto& claim : claims_)
    if (same_file(path, resolved_path, claim.path) || resolved_path == claim.resolved)
      throw refused(path, flag,
                    "is the same file as " + claim.flag + " (" + claim.path.string() +
                        "); each output needs a file of its own");
}

void OutputClaims::claim_file(const std::string& flag, const fs::path& path, bool overwrite) {
  if (path.empty()) throw refused(path, flag, "expected a file name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  bool device = false;
  if (const std::string why = unwritable(path, device); !why.empty())
    throw refused(path, flag, why);
  std::error_code ec;
  if (!device && fs::exists(path, ec) && !overwrite)
    throw refused(path, flag, "output file exists; pass --force to overwrite it");
  if (!device && !folder_ready(path))
    throw refused(path, flag,
                  "output folder '" +
                      (path.has_parent_path() ? path.parent_path() : fs::path(".")).string() +
                      "' does not exist");
  claims_.push_back({flag, path, where});
}

void OutputClaims::claim_read_write(const std::string& flag, const fs::path& path,
                                    const std::vector<std::string>& siblings) {
  if (path.empty()) throw refused(path, flag, "expected a file name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    bool device = false;
    const std::string why = unwritable(path, device);
    throw refused(
        path, flag,
        why.empty() ? "is a device, not a file this run can keep; expected a file name" : why);
  }
  if (!folder_ready(path))
    throw refused(path, flag,
                  "folder '" +
                      (path.has_parent_path() ? path.parent_path() : fs::path(".")).string() +
                      "' does not exist");
  claims_.push_back({flag, path, where});
  for (const auto& suffix : siblings) {
    const fs::path sibling = path.string() + suffix;
    const fs::path sibling_where = resolved(sibling);
    check_not_input_or_claimed(flag, sibling, sibling_where);
    claims_.push_back({flag, sibling, sibling_where});
  }
}

void OutputClaims::claim_folder(const std::string& flag, const fs::path& path) {
  if (path.empty()) throw refused(path, flag, "expected a folder name, got an empty one");
  const fs::path where = resolved(path);
  check_not_input_or_claimed(flag, path, where);
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec))
    throw refused(path, flag, "exists and is not a folder; expected a folder name");
  claims_.push_back({flag, path, where, true});
}

void check_output_path(const fs::path& path, bool overwrite, const std::vector<fs::path>& inputs) {
  OutputClaims(inputs).claim_file("", path, overwrite);
}

void write_file_atomically(const fs::path& path, const std::string& content, bool overwrite,
                           const std::vector<fs::path>& inputs) {
  check_output_path(path, overwrite, inputs);
  PendingOutput pending(path);
  const fs::path& target = pending.writing_path();
  const bool device = target == path;
  const int fd =
      device ? ::open(target.c_str(), O_WRONLY | O_CLOEXEC)
             : ::open(target.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0)
    throw InputError(path.string(), 0, "",
                     std::string("cannot create output file: ") + std::strerror(errno));
  const bool written = write_all(fd, content);
  const int write_errno = errno;
  const bool closed = ::close(fd) == 0;
  if (!written || !closed)
    throw InputError(
        path.string(), 0, "",
        std::string("cannot write output file: ") + std::strerror(!written ? write_errno : errno));
  pending.commit();
}

PendingOutput::PendingOutput(fs::path path) : path_(std::move(path)) {
  writing_ = is_character_device(path_) ? path_ : temporary_beside(path_);
}

PendingOutput::~PendingOutput() {
  if (!committed_ && writing_ != path_) std::remove(writing_.c_str());
}

void PendingOutput::commit() {
  if (committed_) return;
  committed_ = true;
  if (writing_ == path_) return;
  std::error_code ec;
  fs::rename(writing_, path_, ec);
  if (ec) {
    std::remove(writing_.c_str());
    throw InputError(path_.string(), 0, "",
                     "cannot move finished output into place: " + ec.message());
  }
}

}  // namespace ccbuild
