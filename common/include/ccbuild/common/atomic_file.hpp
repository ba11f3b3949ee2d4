#pragma once
// Output files are written whole or not at all: content goes to a temporary file in the
// same folder, which is renamed over the target only when complete.

#include <filesystem>
#include <string>
#include <vector>

namespace ccbuild {

/// Writes `content` to `path` atomically. Refuses (InputError, nothing written) when
/// `path` is one of `inputs`, or exists and `overwrite` is false.
void write_file_atomically(const std::filesystem::path& path, const std::string& content,
                           bool overwrite, const std::vector<std::filesystem::path>& inputs = {});

/// Throws InputError when writing `path` would be refused (see write_file_atomically),
/// so a command can check its outputs before doing any work.
void check_output_path(const std::filesystem::path& path, bool overwrite,
                       const std::vector<std::filesystem::path>& inputs = {});

}  // namespace ccbuild
