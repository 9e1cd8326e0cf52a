// Tests of the command line's reusable output helpers: CSV text and the SVG plot writer.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv.hpp"
#include "svg_plot.hpp"

namespace cueplan::cli {
namespace {

TEST(Csv, NumbersReadBackExactly) {
  for (double x : {0.1, 1.0 / 3.0, -2.5e-17, 6.02214076e23, 0.0})
    EXPECT_EQ(parse_number(format_number(x)).value(), x) << format_number(x);
  EXPECT_EQ(format_number(NAN), "nan");
  EXPECT_TRUE(std::isnan(parse_number("nan").value()));
}

TEST(Csv, ParseNumberTakesOnlyWholeNumbers) {
  EXPECT_EQ(parse_number(" +1.5 ").value(), 1.5);
  EXPECT_FALSE(parse_number("1.5x").has_value());
  EXPECT_FALSE(parse_number("").has_value());
  EXPECT_FALSE(parse_number("fast").has_value());
}

TEST(Csv, QuotedFieldsSurviveARoundTrip) {
  const std::vector<std::string> fields = {"plain", "with, comma", "say \"hi\"", ""};
  std::string line = csv_line(fields);
  ASSERT_EQ(line.back(), '\n');
  line.pop_back();
  EXPECT_EQ(split_csv_line(line), fields);
  EXPECT_EQ(csv_quoted("a\"b"), "\"a\"\"b\"");
}

TEST(Csv, TableRowsMustMatchTheHeader) {
  CsvTable table({"x", "y"});
  table.add_numbers({1.0, 2.5});
  EXPECT_EQ(table.to_string(), "x,y\n1,2.5\n");
  EXPECT_THROW(table.add_numbers({1.0}), std::logic_error);
}

PlotFigure two_panel_figure() {
  PlotSeries line;
  line.label = "k_{T} < 1 & more";
  line.x = {0.0, 1.0, NAN, 2.0, 3.0};
  line.y = {0.0, 1.0, 1.5, 2.0, 1.0};
  PlotPanel panel;
  panel.title = "Panel";
  panel.x_axis.label = "x (m)";
  panel.y_axis.label = "y (m/s)";
  panel.series = {line};
  PlotFigure figure;
  figure.title = "Title";
  figure.panels = {panel, panel};
  return figure;
}

TEST(SvgPlot, EscapesTextAndWritesSubscripts) {
  const std::string svg = render_svg(two_panel_figure());
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("&lt; 1 &amp; more"), std::string::npos);
  EXPECT_EQ(svg.find("_{"), std::string::npos);
  EXPECT_NE(svg.find("<tspan"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(SvgPlot, NonFiniteValuesBreakTheLine) {
  const std::string svg = render_svg(two_panel_figure());
  // Two panels, each path starting twice: once before the NaN, once after it.
  size_t moves = 0;
  for (size_t at = svg.find("<path d=\" M"); at != std::string::npos;
       at = svg.find("<path d=\" M", at + 1)) {
    const std::string path = svg.substr(at, svg.find("/>", at) - at);
    for (size_t m = path.find(" M"); m != std::string::npos; m = path.find(" M", m + 1)) ++moves;
  }
  EXPECT_EQ(moves, 4u);
}

TEST(SvgPlot, ClipPathsAreUniquePerPanel) {
  const std::string svg = render_svg(two_panel_figure());
  EXPECT_NE(svg.find("id=\"plot-area-0\""), std::string::npos);
  EXPECT_NE(svg.find("id=\"plot-area-1\""), std::string::npos);
}

}  // namespace
}  // namespace cueplan::cli
