#pragma once
// The one rule for every file ccbuild writes (docs/formats.md, "Output files"):
//   - every output of a run, the names derived from another included (a fitted profile's
//     URDF, an import's plan files), is claimed before anything is written;
//   - never a file the run reads: the inputs named to the claims, every file read through
//     read_text_file or sha256_file_hex in this process (note_file_read), and the inputs a
//     schedule records (compared by inode, after resolving links and `..`);
//   - never two outputs of one run on the same file;
//   - never a device, directory, FIFO or socket: outputs are regular files;
//   - an existing regular file replaced only when asked (--force); a derived name only
//     when the file there is the one ccbuild wrote beside the same output before;
//   - all or nothing for the whole run: each output goes to a temporary file beside its
//     target, and commit() moves them all into place together (undoing the ones moved when
//     one cannot be); a run that stops before commit() leaves nothing; a write error (a
//     full disk) is reported with the path.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace ccbuild {

/// Notes that this process read `path`, so that no output of it may be that file.
/// read_text_file and sha256_file_hex call it. Thread-safe.
void note_file_read(const std::filesystem::path& path);
/// Every file noted by note_file_read in this process, in the order first read.
std::vector<std::filesystem::path> files_read();

/// The outputs a run writes: claimed (and checked against its inputs and each other)
/// before any work is done, written to temporary files as the run makes them, and put in
/// place together by commit(). Destroyed without commit(), it removes what it wrote.
/// Every check throws InputError naming the path and the flag. Not thread-safe.
class OutputClaims {
 public:
  /// `inputs`: files the run reads besides those it reads through read_text_file (every
  /// one of those is an input too, unless `files_read_are_inputs` is false: for a run's
  /// own state files, which it reads back and replaces).
  explicit OutputClaims(std::vector<std::filesystem::path> inputs = {},
                        bool files_read_are_inputs = true);
  ~OutputClaims();
  OutputClaims(const OutputClaims&) = delete;
  OutputClaims& operator=(const OutputClaims&) = delete;

  /// One more file the run reads (a schedule's recorded inputs, say). Throws when a file
  /// claimed already is that file.
  void add_input(const std::filesystem::path& path);
  /// Claims a file that the run writes whole (write(), then commit()). Throws when it is
  /// an input, claimed already, anything but a regular file (a device, directory, FIFO,
  /// socket), an existing file and `overwrite` is false, or in a folder that does not
  /// exist (nor is claimed).
  void claim_file(const std::string& flag, const std::filesystem::path& path, bool overwrite);
  /// Claims a file whose name the run derives from an output the user named (`owner`):
  /// as claim_file, and an existing file there is replaced (with `overwrite`) only when
  /// its first 4 KiB hold `mark`, the line ccbuild writes into such a file to say whose
  /// it is; otherwise it is someone else's file and the claim throws.
  void claim_derived(const std::string& flag, const std::filesystem::path& path,
                     const std::filesystem::path& owner, bool overwrite, const std::string& mark);
  /// Claims a file that the run reads back and updates in place (a journal): it may exist,
  /// then as a regular file; `siblings` are suffixes of files made beside it ("-wal"),
  /// which are claimed too. Throws as claim_file does, except that it may exist.
  void claim_read_write(const std::string& flag, const std::filesystem::path& path,
                        const std::vector<std::string>& siblings = {});
  /// Claims a folder the run writes into (made when missing, with its parents); files in
  /// it may be claimed next. Throws when it exists and is not a folder, or is an input or
  /// claimed already.
  void claim_folder(const std::string& flag, const std::filesystem::path& path);

  /// Writes `content` for the claimed file `path` to a temporary file beside it (put in
  /// place by commit()). Throws InputError naming `path` when it cannot be written (the
  /// temporary file is removed), InternalError when `path` was not claimed.
  void write(const std::filesystem::path& path, const std::string& content);
  /// A temporary file for the claimed file `path` that the caller writes itself over the
  /// run (a log), put in place by commit(). Throws InternalError when not claimed.
  std::filesystem::path writing_path(const std::filesystem::path& path);
  /// Checks every claim again (against every file read since it was made too), then puts
  /// every written file in place: all of them, or, when one cannot be, none (files already
  /// moved are put back as they were). Throws InputError naming the path.
  void commit();

  const std::vector<std::filesystem::path>& inputs() const { return inputs_; }

 private:
  struct Claim;
  /// Whether `path`'s folder exists, or is a folder claimed (made when the run starts).
  bool folder_ready(const std::filesystem::path& path) const;
  void check_not_input_or_claimed(const std::string& flag, const std::filesystem::path& path,
                                  const std::filesystem::path& resolved) const;
  void check_claim_against_inputs(const Claim& claim) const;
  Claim& claimed(const std::filesystem::path& path);
  std::vector<std::filesystem::path> inputs_;
  std::vector<std::unique_ptr<Claim>> claims_;
  bool files_read_are_inputs_ = true;
  bool committed_ = false;
};

/// Throws InputError when writing `path` would break the rule above (see
/// OutputClaims::claim_file), so a command with one output can check it before doing any
/// work.
void check_output_path(const std::filesystem::path& path, bool overwrite,
                       const std::vector<std::filesystem::path>& inputs = {});

/// Writes `content` to `path` whole or not at all (see above): one claim, written and
/// committed, checked against `inputs` only: for the files a run keeps its own state in
/// (a study's plan and results, a dry-run's records), which it reads back and replaces.
/// A command's outputs go through OutputClaims. Throws InputError naming `path` when
/// refused or when writing fails (nothing is left behind then).
void write_file_atomically(const std::filesystem::path& path, const std::string& content,
                           bool overwrite, const std::vector<std::filesystem::path>& inputs = {});

/// Whether `path` names an existing character device.
bool is_character_device(const std::filesystem::path& path);

}  // namespace ccbuild
