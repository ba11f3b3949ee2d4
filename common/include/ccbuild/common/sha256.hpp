#pragma once
// SHA-256 (FIPS 180-4) of files and strings, so that a schedule names exactly the inputs
// it was computed from.

#include <filesystem>
#include <string>

namespace ccbuild {

/// 64 lowercase hex digits.
std::string sha256_hex(const std::string& bytes);
/// Of a file's bytes. Throws InputError (naming the file) when it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);

}  // namespace ccbuild
