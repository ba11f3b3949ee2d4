#pragma once
// Limits on what ccbuild reads. Hostile input is normal input: a file that is too big,
// nested too deep or expands too far is an input error (exit 2) with a clear message,
// never a stack overflow, a hang or memory exhaustion. docs/formats.md lists them all.

#include <cstddef>
#include <cstdint>

namespace ccbuild::limits {

/// Largest file ccbuild reads (building, plan, profile, URDF), bytes.
inline constexpr std::uintmax_t kMaxInputFileBytes = 32ull * 1024 * 1024;
/// Deepest nesting of maps and lists in a YAML or JSON file, and of elements in a URDF.
inline constexpr int kMaxNestingDepth = 64;
/// Most values a YAML or JSON document may hold once YAML aliases are expanded.
inline constexpr std::size_t kMaxDocumentValues = 2'000'000;
/// Problems with an input (and an importer's notes of one kind) said one by one; the rest
/// are counted in one line, so that a drawing of a thousand copies of one mistake is said
/// in a screenful, in bounded memory (issue 49: 26 MB of stderr).
inline constexpr std::size_t kMaxListed = 50;

}  // namespace ccbuild::limits
