#include "ccbuild/floors/units.hpp"

#include <charconv>
#include <cmath>

#include "ccbuild/common/format.hpp"

namespace ccbuild::floors {

std::optional<LengthUnit> parse_length_unit(const std::string& text) {
  if (text == "m") return LengthUnit::kMeter;
  if (text == "ft") return LengthUnit::kFoot;
  return std::nullopt;
}

std::string to_string(LengthUnit unit) {
  return unit == LengthUnit::kFoot ? "ft" : "m";
}

double rounded(double value, int decimals, Towards towards) {
  const double scale = std::pow(10.0, decimals);
  switch (towards) {
    case Towards::kUp:
      return std::ceil((value - 1e-9) * scale) / scale;
    case Towards::kDown:
      return std::floor((value + 1e-9) * scale) / scale;
    case Towards::kNearest:
      break;
  }
  return value;  // printf rounds to the nearest
}

std::string length_text(double value_m, LengthUnit unit, int decimals, Towards towards) {
  return printf_string("%.*f %s", decimals, rounded(value_m / meters_per(unit), decimals, towards),
                       to_string(unit).c_str());
}

std::string fine_length_text(double value_m, LengthUnit unit) {
  if (unit == LengthUnit::kFoot) {
    const double inches = value_m / kMetersPerFoot * 12.0;
    return printf_string(std::abs(inches) < 1.0 ? "%.2f in" : "%.1f in", inches);
  }
  return printf_string(std::abs(value_m) < 0.01 ? "%.1f mm" : "%.0f mm", value_m * 1000.0);
}

std::string volume_unit(LengthUnit unit) {
  return unit == LengthUnit::kFoot ? "yd³" : "m³";
}

std::string volume_text(double value_m3, LengthUnit unit, int decimals) {
  return printf_string("%.*f %s", decimals, volume_in(value_m3, unit), volume_unit(unit).c_str());
}

std::string flow_text(double value_m3_s, LengthUnit unit, int decimals) {
  return printf_string("%.*f %s/h", decimals, volume_in(value_m3_s * 3600.0, unit),
                       volume_unit(unit).c_str());
}

std::string speed_text(double value_m_s, LengthUnit unit, int decimals, Towards towards) {
  return printf_string("%.*f %s/s", decimals,
                       rounded(length_in(value_m_s, unit), decimals, towards),
                       to_string(unit).c_str());
}

std::optional<double> parse_length_m(const std::string& text, LengthUnit default_unit) {
  std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return std::nullopt;
  std::size_t end = text.find_last_not_of(" \t") + 1;
  std::string body = text.substr(begin, end - begin);
  LengthUnit unit = default_unit;
  for (const auto& [suffix, u] :
       {std::pair{"ft", LengthUnit::kFoot}, std::pair{"m", LengthUnit::kMeter}}) {
    const std::string s(suffix);
    if (body.size() > s.size() && body.compare(body.size() - s.size(), s.size(), s) == 0) {
      body = body.substr(0, body.size() - s.size());
      while (!body.empty() && body.back() == ' ') body.pop_back();
      unit = u;
      break;
    }
  }
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (body.empty() || ec != std::errc() || ptr != body.data() + body.size() ||
      !std::isfinite(value))
    return std::nullopt;
  return value * meters_per(unit);
}

}  // namespace ccbuild::floors
