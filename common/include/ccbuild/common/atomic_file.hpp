#pragma once
// The one rule for every file ccbuild writes (docs/formats.md, "Output files"):
//   - never a file the run reads (compared by inode, after resolving links and `..`);
//   - never two outputs of one run on the same file;
//   - never a directory, FIFO, socket or block device replaced or written; an existing
//     character device (/dev/null, a terminal) is written into, never replaced;
//   - an existing regular file replaced only when asked (--force);
//   - written whole or not at all: content goes to a temporary file in the same folder,
//     renamed over the target only when complete; a write error (a full disk) is reported
//     with the path, and the temporary file removed.
// Commands claim all their outputs in an OutputClaims before doing any work.

#include <filesystem>
#include <string>
#include <vector>

namespace ccbuild {

/// The outputs a run will write, checked against its inputs and each other before any
/// work is done. Every check throws InputError naming the path and the flag.
class OutputClaims {
 public:
  /// `inputs`: every file the run reads.
  explicit OutputClaims(std::vector<std::filesystem::path> inputs = {});

  /// One more file the run reads.
  void add_input(const std::filesystem::path& path);
  /// Claims a file that the run writes whole (write_file_atomically, PendingOutput). Throws
  /// when it is an input, claimed already, a directory, FIFO, socket or block device, an
  /// existing regular file and `overwrite` is false, or in a folder that does not exist.
  void claim_file(const std::string& flag, const std::filesystem::path& path, bool overwrite);
  /// Claims a file that the run reads back and updates in place (a journal): it may exist,
  /// then as a regular file; `siblings` are suffixes of files made beside it ("-wal"),
  /// which are claimed too. Throws as claim_file does, except that it may exist.
  void claim_read_write(const std::string& flag, const std::filesystem::path& path,
                        const std::vector<std::string>& siblings = {});
  /// Claims a folder the run writes into (made when missing, with its parents); files in
  /// it may be claimed next. Throws when it exists and is not a folder, or is an input or
  /// claimed already.
  void claim_folder(const std::string& flag, const std::filesystem::path& path);

  const std::vector<std::filesystem::path>& inputs() const { return inputs_; }

 private:
  struct Claim {
    std::string flag;
    std::filesystem::path path;
    std::filesystem::path resolved;  ///< absolute, links and `..` resolved
    bool folder = false;
  };
  /// Whether `path`'s folder exists, or is a folder claimed (made when the run starts).
  bool folder_ready(const std::filesystem::path& path) const;
  void check_not_input_or_claimed(const std::string& flag, const std::filesystem::path& path,
                                  const std::filesystem::path& resolved) const;
  std::vector<std::filesystem::path> inputs_;
  std::vector<Claim> claims_;
};

/// Throws InputError when writing `path` would break the rule above (see
/// OutputClaims::claim_file), so a command with one output can check it before doing any
/// work.
void check_output_path(const std::filesystem::path& path, bool overwrite,
                       const std::vector<std::filesystem::path>& inputs = {});

/// Writes `content` to `path` whole or not at all (see above), after check_output_path.
/// Throws InputError naming `path` when refused or when writing fails (nothing is left
/// behind then).
void write_file_atomically(const std::filesystem::path& path, const std::string& content,
                           bool overwrite, const std::vector<std::filesystem::path>& inputs = {});

/// An output written over a run and put in place when it is complete: the writer writes
/// writing_path() (a temporary file beside the target, or the target itself when that is
/// a character device), and commit() renames it over the target. Destroyed without
/// commit(), the temporary file is removed. Claim the path first.
class PendingOutput {
 public:
  explicit PendingOutput(std::filesystem::path path);
  ~PendingOutput();
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& writing_path() const { return writing_; }
  /// Puts the finished file in place. Throws InputError naming the path when it cannot.
  void commit();

 private:
  std::filesystem::path path_, writing_;
  bool committed_ = false;
};

/// Whether `path` names an existing character device (written into, never replaced).
bool is_character_device(const std::filesystem::path& path);

}  // namespace ccbuild
