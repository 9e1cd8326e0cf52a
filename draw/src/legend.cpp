#include "legend.hpp"

#include <algorithm>

#include "palette.hpp"

namespace cueplan::draw::detail {

Legend::Legend(const Typesetter& type, std::vector<LegendEntry> entries, Font font, double width,
               bool one_per_row) {
  constexpr double kTextGap = 6.0;    // symbol to text
  constexpr double kEntryGap = 20.0;  // between entries of a row
  const double row_height = 1.6 * font.size;
  double x = 0.0;
  double row_middle = 0.5 * row_height;
  for (LegendEntry& e : entries) {
    Text text = type.set(e.text, font, std::max(40.0, width - kLegendSymbolWidth - kTextGap));
    const double w = kLegendSymbolWidth + kTextGap + text.width();
    if (x > 0.0 && (one_per_row || x + w > width)) {
      x = 0.0;
      row_middle += std::max(row_height, placed_.back().text.height() + 0.5 * font.size);
    }
    used_width_ = std::max(used_width_, x + w);
    placed_.push_back({std::move(e), std::move(text), x, row_middle});
    x += w + kEntryGap;
  }
  if (!placed_.empty())
    height_ = row_middle + std::max(0.5 * row_height, 0.5 * placed_.back().text.height());
}

void Legend::draw(Canvas& canvas, double left, double top) const {
  for (const Placed& p : placed_) {
    const double y = top + p.y;
    p.entry.symbol(canvas, left + p.x + 0.5 * kLegendSymbolWidth, y);
    canvas.text(p.text, left + p.x + kLegendSymbolWidth + 6.0, y, {0.0, VAnchor::middle}, ink(),
                "legend-text");
  }
}

}  // namespace cueplan::draw::detail
