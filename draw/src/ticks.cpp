#include "ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cueplan::draw::detail {

double nice_step(double raw) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {1.0, 2.0, 2.5, 5.0})
    if (mantissa * decade >= raw * (1.0 - 1e-9)) return mantissa * decade;
  return 10.0 * decade;
}

std::vector<double> multiples(double step, double lo, double hi) {
  std::vector<double> values;
  if (!(step > 0.0) || !(hi >= lo)) return values;
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last && values.size() < 1000; k += 1.0)
    values.push_back(k == 0.0 ? 0.0 : k * step);
  return values;
}

std::string tick_label(double value, double step) {
  const double exponent = std::floor(std::log10(step) + 1e-9);
  const double mantissa = step / std::pow(10.0, exponent);
  const bool half_step = std::abs(mantissa - std::round(mantissa)) > 1e-6;  // 2.5
  std::string text;
  if (std::abs(value) < 1e-9 * step) {
    text = "0";
  } else if (exponent >= 6.0 || exponent <= -4.0) {
    // value = m x 10^e with e the step's exponent.
    const double m = value / std::pow(10.0, exponent);
    text = fmt::format("{:.{}f}\u00d710^{{{}}}", m, half_step ? 1 : 0, static_cast<int>(exponent));
  } else {
    const int decimals = std::max(0, static_cast<int>(-exponent) + (half_step ? 1 : 0));
    text = fmt::format("{:.{}f}", value, decimals);
  }
  // A typographic minus reads better than a hyphen.
  return text[0] == '-' ? "\u2212" + text.substr(1) : text;
}

}  // namespace cueplan::draw::detail
