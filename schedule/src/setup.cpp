#include "ccbuild/schedule/setup.hpp"

#include <algorithm>

#include "ccbuild/floors/units.hpp"

namespace ccbuild::schedule {
namespace fs = std::filesystem;

std::vector<fs::path> Setup::files_read() const {
  std::vector<fs::path> out = building.files_read;
  if (machine) out.insert(out.end(), machine->files_read.begin(), machine->files_read.end());
  if (!material.source_file.empty()) out.emplace_back(material.source_file);
  if (!site_file.empty()) out.push_back(site_file);
  if (conditions && !conditions->file.empty()) out.push_back(conditions->file);
  if (std::find(out.begin(), out.end(), file) == out.end()) out.push_back(file);
  return out;
}

std::string Setup::length(double value_m, int decimals) const {
  return floors::length_text(value_m, building.units, decimals);
}

std::vector<std::string> Setup::unit_names() const {
  std::vector<std::string> names;
  if (climber)
    for (const auto& u : climber->units) names.push_back(u.name);
  return names;
}

std::string to_string(PlacedBy how) {
  switch (how) {
    case PlacedBy::kSite:
      return "site";
    case PlacedBy::kCentred:
      return "centred";
    case PlacedBy::kAsDrawn:
      break;
  }
  return "as drawn";
}

std::optional<PlacedBy> placed_by_named(const std::string& name) {
  for (PlacedBy how : {PlacedBy::kAsDrawn, PlacedBy::kSite, PlacedBy::kCentred})
    if (to_string(how) == name) return how;
  return std::nullopt;
}

}  // namespace ccbuild::schedule
