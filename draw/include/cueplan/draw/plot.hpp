// Line plots of one or more panels side by side (the paper's figures).
//
// Each panel has a framed plot area, "nice" ticks (1, 2, 2.5, 5 x 10^n) with light grid
// lines, axis labels that carry their units, a legend to the right of the plot area (so
// it never covers data) and any number of series. Text may write subscripts as k_{T}.
// Colours follow the Okabe-Ito palette, readable by colour-blind readers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/draw/picture.hpp"

namespace cueplan::draw {

struct PlotSeries {
  std::string label;      // legend entry
  std::vector<double> x;  // same length as y
  std::vector<double> y;  // a non-finite x or y breaks the line there
  bool dashed = false;
  std::string colour;  // "#rrggbb"; empty: the palette colour of its index
};

struct PlotAxis {
  std::string label;          // name and unit, e.g. "rebound speed (m/s)"
  std::optional<double> min;  // fixed end; otherwise from the data, rounded to a tick
  std::optional<double> max;
  std::optional<double> tick_step;  // fixed spacing; otherwise about six nice ticks
};

// A dashed vertical line across the plot area with a short label at its top.
struct PlotMarker {
  double x = 0.0;
  std::string label;
};

struct PlotPanel {
  std::string title;
  PlotAxis x_axis;
  PlotAxis y_axis;
  std::vector<PlotSeries> series;
  std::vector<PlotMarker> markers;
  std::string legend_title;  // e.g. "V_{0} (m/s)"; empty: none
};

struct PlotFigure {
  std::string title;
  std::string caption;            // under the title, wrapped; empty: none
  std::vector<PlotPanel> panels;  // drawn left to right
};

// Sizes in picture units (px).
struct PlotStyle {
  double plot_width = 400.0;
  double plot_height = 290.0;
  double font_size = 13.0;
  double line_width = 1.8;
};

// Colour of series `index` in the default palette, "#rrggbb".
const char* palette_colour(size_t index);

Picture plot_picture(const PlotFigure& figure, const PlotStyle& style = {});

}  // namespace cueplan::draw
