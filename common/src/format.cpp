#include "ccbuild/common/format.hpp"

#include <cstdarg>
#include <cstdio>

namespace ccbuild {

std::string printf_string(const char* pattern, ...) {
  va_list args;
  va_start(args, pattern);
  va_list copy;
  va_copy(copy, args);
  const int needed = std::vsnprintf(nullptr, 0, pattern, copy);
  va_end(copy);
  std::string out(needed > 0 ? static_cast<std::size_t>(needed) : 0, '\0');
  if (needed > 0) std::vsnprintf(out.data(), out.size() + 1, pattern, args);
  va_end(args);
  return out;
}

std::string metres(double value_m, int decimals) {
  return printf_string("%.*f m", decimals, value_m);
}

std::string seconds(double value_s, int decimals) {
  return printf_string("%.*f s", decimals, value_s);
}

}  // namespace ccbuild
