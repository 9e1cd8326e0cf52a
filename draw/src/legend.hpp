// A legend laid out in rows: each entry a small symbol and its text, entries wrapped to
// rows no wider than the legend's width. Used by the table and the spin map.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "canvas.hpp"

namespace cueplan::draw::detail {

struct LegendEntry {
  // Draws the symbol centred on (x, y) within a box kSymbolWidth wide.
  std::function<void(Canvas&, double x, double y)> symbol;
  std::string text;
};

inline constexpr double kLegendSymbolWidth = 26.0;

class Legend {
 public:
  // Entries flow left to right and wrap at `width`; one entry per row when `one_per_row`.
  Legend(const Typesetter& type, std::vector<LegendEntry> entries, Font font, double width,
         bool one_per_row = false);
  double height() const { return height_; }
  double width() const { return used_width_; }
  void draw(Canvas& canvas, double left, double top) const;

 private:
  struct Placed {
    LegendEntry entry;
    Text text;
    double x = 0.0, y = 0.0;  // of the symbol's left edge and the row's middle
  };
  std::vector<Placed> placed_;
  double height_ = 0.0;
  double used_width_ = 0.0;
};

}  // namespace cueplan::draw::detail
