// A small SVG line-plot writer for figures of one or more panels side by side.
//
// Each panel has a framed plot area, "nice" ticks (1, 2, 2.5, 5 x 10^n) with light
// grid lines, axis labels that carry their units, a legend to the right of the plot
// area (so it never covers data) and any number of series. Text may write subscripts
// as `k_{T}`. Colours follow the Okabe-Ito palette, readable by colour-blind readers.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::cli {

// Text made safe inside SVG/XML markup (&, <, >, ").
std::string escape_xml(std::string_view text);

// A label split into plain and subscript runs: "k_{T}" -> "k", subscript "T".
struct TextRun {
  std::string text;
  bool subscript = false;
};
std::vector<TextRun> text_runs(std::string_view label);

struct PlotSeries {
  std::string label;      // legend entry
  std::vector<double> x;  // same length as y
  std::vector<double> y;  // a non-finite x or y breaks the line there
  bool dashed = false;
  std::string colour;  // e.g. "#0072B2"; empty: the palette colour of its index
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
  std::string caption;            // one line under the title; empty: none
  std::vector<PlotPanel> panels;  // drawn left to right
};

// Sizes in SVG user units (pixels at 100 %).
struct PlotStyle {
  double plot_width = 400.0;
  double plot_height = 290.0;
  double font_size = 13.0;
  double line_width = 1.8;
  std::string font_family = "DejaVu Sans, Helvetica, Arial, sans-serif";
};

// Colour of series `index` in the default palette.
const char* palette_colour(size_t index);

// The figure as a standalone SVG document.
std::string render_svg(const PlotFigure& figure, const PlotStyle& style = {});

}  // namespace cueplan::cli
