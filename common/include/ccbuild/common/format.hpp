#pragma once
// Formatting numbers with their unit for messages and reports.

#include <string>

namespace ccbuild {

/// printf into a std::string.
std::string printf_string(const char* pattern, ...) __attribute__((format(printf, 1, 2)));

/// "4.500 m" (3 decimals by default).
std::string metres(double value_m, int decimals = 3);
/// "12.5 s" (1 decimal by default).
std::string seconds(double value_s, int decimals = 1);

}  // namespace ccbuild
