#include "ccbuild/common/atomic_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild {
namespace fs = std::filesystem;

void check_output_path(const fs::path& path, bool overwrite, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  for (const auto& input : inputs) {
    if (fs::exists(path, ec) && fs::equivalent(path, input, ec))
      throw InputError(path.string(), 0, "",
                       "output would overwrite an input file; choose another path");
  }
  if (fs::is_directory(path, ec))
    throw InputError(path.string(), 0, "", "output path is a directory, expected a file name");
  if (fs::exists(path, ec) && !overwrite)
    throw InputError(path.string(), 0, "", "output file exists; pass --force to overwrite it");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw InputError(path.string(), 0, "",
                     "output folder '" + parent.string() + "' does not exist");
}

void write_file_atomically(const fs::path& path, const std::string& content, bool overwrite,
                           const std::vector<fs::path>& inputs) {
  check_output_path(path, overwrite, inputs);
  const fs::path temp = path.string() + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path.string(), 0, "", "cannot create output file");
    out << content;
    out.flush();
    if (!out) {
      out.close();
      std::remove(temp.c_str());
      throw InputError(path.string(), 0, "", "cannot write output file (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    std::remove(temp.c_str());
    throw InputError(path.string(), 0, "",
                     "cannot move finished output into place: " + ec.message());
  }
}

}  // namespace ccbuild
