#include "ccbuild/rules/age_clock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ccbuild::rules {

double AgeClock::at(double t_s) const {
  if (points_.empty()) return t_s;
  const auto it = std::upper_bound(points_.begin(), points_.end(), t_s,
                                   [](double t, const Breakpoint& p) { return t < p.t_s; });
  const Breakpoint& p = it == points_.begin() ? points_.front() : *(it - 1);
  return p.e_s + p.rate * (t_s - p.t_s);
}

double AgeClock::after(double from_s, double age_s) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (age_s <= 0.0) return from_s;
  if (!std::isfinite(age_s)) return kInf;
  if (points_.empty()) return from_s + age_s;
  const double target = at(from_s) + age_s;
  // The first breakpoint at which the age has reached the target: the time lies in the
  // stretch before it (or after the last breakpoint).
  const auto it = std::lower_bound(points_.begin(), points_.end(), target,
                                   [](const Breakpoint& p, double e) { return p.e_s < e; });
  const std::size_t i = static_cast<std::size_t>(it - points_.begin());
  const Breakpoint& p = points_[i == 0 ? 0 : i - 1];
  if (p.rate <= 0.0) return i == 0 ? from_s : kInf;
  return std::max(from_s, p.t_s + (target - p.e_s) / p.rate);
}

std::string AgeClock::text() const {
  std::string out;
  char line[96];
  for (const Breakpoint& p : points_) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.t_s, p.e_s, p.rate);
    out += line;
  }
  return out;
}

AgeClock AgeClock::parse(const std::string& text) {
  std::vector<Breakpoint> points;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    Breakpoint p;
    std::string rest;
    if (!(fields >> p.t_s >> p.e_s >> p.rate) || (fields >> rest) || !std::isfinite(p.t_s) ||
        !std::isfinite(p.e_s) || !std::isfinite(p.rate) || p.rate < 0.0 ||
        (!points.empty() && p.t_s < points.back().t_s))
      throw std::invalid_argument("line " + std::to_string(n) +
                                  ": expected \"t_s e_s rate\" (finite, rate >= 0, times "
                                  "increasing), got \"" +
                                  line.substr(0, 80) + "\"");
    points.push_back(p);
  }
  return AgeClock(std::move(points));
}

}  // namespace ccbuild::rules
