// Tick spacing and tick labels shared by the table's metre ticks, the plots' axes and the
// spin map's disc.
#pragma once

#include <string>
#include <vector>

namespace cueplan::draw::detail {

// The smallest 1, 2, 2.5 or 5 times a power of ten at or above `raw` (> 0).
double nice_step(double raw);

// Multiples of `step` from `lo` to `hi` (both included within a rounding), with an exact 0.
std::vector<double> multiples(double step, double lo, double hi);

// A tick's label with just enough decimals to tell ticks `step` apart, a typographic
// minus, and powers of ten ("2.5\u00d710^{8}") once the numbers grow past six digits or
// fall below a thousandth.
std::string tick_label(double value, double step);

}  // namespace cueplan::draw::detail
