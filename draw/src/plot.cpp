#include "cueplan/draw/plot.hpp"

#include <algorithm>
#include <cmath>

#include "canvas.hpp"
#include "palette.hpp"
#include "ticks.hpp"

namespace cueplan::draw {
namespace {

using detail::Canvas;
using detail::Font;
using detail::Path;
using detail::Pen;
using detail::Text;
using detail::Typesetter;
using detail::VAnchor;

// A figure is drawn in these stages: lay_out (ticks of every panel, text, sizes), titles,
// then per panel: grid, ticks, axis labels, data (clipped to the plot area), markers,
// frame and legend.

constexpr double kTickLength = 5.0;
constexpr double kOuter = 16.0;
constexpr double kPanelGap = 24.0;

// Tick positions along one axis and the range they span.
struct Ticks {
  double lo = 0.0;
  double hi = 1.0;
  double step = 1.0;
  std::vector<double> values;
};

Ticks make_ticks(const PlotAxis& axis, double data_lo, double data_hi) {
  if (!std::isfinite(data_lo) || !std::isfinite(data_hi)) {
    data_lo = 0.0;
    data_hi = 1.0;
  }
  double lo = axis.min.value_or(data_lo);
  double hi = axis.max.value_or(data_hi);
  if (!(hi > lo)) {
    const double half = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    if (!axis.min) lo -= half;
    if (!axis.max || !(axis.max.value() > lo)) hi = lo + 2.0 * half;
  }
  // A little room so curves do not run along the frame, without crossing zero.
  const double pad = 0.03 * (hi - lo);
  if (!axis.min) lo = lo >= 0.0 ? std::max(0.0, lo - pad) : lo - pad;
  if (!axis.max) hi = hi <= 0.0 ? std::min(0.0, hi + pad) : hi + pad;
  Ticks t;
  t.step = axis.tick_step.value_or(detail::nice_step((hi - lo) / 5.0));
  t.lo = axis.min ? lo : std::floor(lo / t.step + 1e-9) * t.step;
  t.hi = axis.max ? hi : std::ceil(hi / t.step - 1e-9) * t.step;
  t.values = detail::multiples(t.step, t.lo, t.hi);
  return t;
}

struct Range {
  double lo = INFINITY;
  double hi = -INFINITY;
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// One panel laid out: its ticks, its text and where its plot area sits.
struct PanelLayout {
  double left = 0.0, top = 0.0;  // the plot area's corner
  double margin = 0.0;           // room left of the plot area for labels
  double legend_width = 0.0, legend_height = 0.0;
  double width = 0.0;  // the whole panel
  Ticks x_ticks, y_ticks;
  std::vector<Text> x_labels, y_labels;
  Text title, x_name, y_name, legend_title;
  std::vector<Text> series_labels, marker_labels;
  double x_label_height = 0.0;  // of the x tick labels
};

PanelLayout lay_out_panel(const PlotPanel& panel, const PlotStyle& style, const Typesetter& type) {
  const double fs = style.font_size;
  PanelLayout l;
  Range xr, yr;
  for (const PlotSeries& s : panel.series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
  }
  for (const PlotMarker& m : panel.markers) xr.add(m.x);
  l.x_ticks = make_ticks(panel.x_axis, xr.lo, xr.hi);
  l.y_ticks = make_ticks(panel.y_axis, yr.lo, yr.hi);
  const Font tick_font{0.9 * fs};
  double widest = 0.0;
  for (double v : l.x_ticks.values)
    l.x_labels.push_back(type.set(detail::tick_label(v, l.x_ticks.step), tick_font));
  for (double v : l.y_ticks.values) {
    l.y_labels.push_back(type.set(detail::tick_label(v, l.y_ticks.step), tick_font));
    widest = std::max(widest, l.y_labels.back().width());
  }
  l.x_label_height = l.x_labels.empty() ? 1.2 * tick_font.size : l.x_labels.front().height();
  l.title = type.set(panel.title, Font{1.05 * fs, true}, style.plot_width);
  l.x_name = type.set(panel.x_axis.label, Font{fs}, style.plot_width);
  l.y_name = type.set(panel.y_axis.label, Font{fs}, style.plot_height);
  l.margin = kTickLength + 4.0 + widest + 8.0 + l.y_name.height();
  for (const PlotMarker& m : panel.markers)
    l.marker_labels.push_back(type.set(m.label, Font{0.85 * fs}));
  if (!panel.series.empty()) {
    double w = 0.0;
    if (!panel.legend_title.empty()) {
      l.legend_title = type.set(panel.legend_title, Font{fs, true});
      w = l.legend_title.width();
    }
    for (const PlotSeries& s : panel.series) {
      l.series_labels.push_back(type.set(s.label, Font{fs}));
      w = std::max(w, 30.0 + l.series_labels.back().width());
    }
    l.legend_width = w + 20.0;
    const size_t lines = panel.series.size() + (panel.legend_title.empty() ? 0 : 1);
    l.legend_height = static_cast<double>(lines) * 1.45 * fs + 0.6 * fs;
  }
  l.width = l.margin + style.plot_width + (l.legend_width > 0.0 ? 14.0 + l.legend_width : 0.0);
  return l;
}

void draw_panel(Canvas& c, const PlotPanel& panel, const PanelLayout& l, const PlotStyle& style) {
  const double fs = style.font_size;
  const double w = style.plot_width, h = style.plot_height;
  const auto px = [&](double x) {
    return l.left + (x - l.x_ticks.lo) / (l.x_ticks.hi - l.x_ticks.lo) * w;
  };
  const auto py = [&](double y) {
    return l.top + (l.y_ticks.hi - y) / (l.y_ticks.hi - l.y_ticks.lo) * h;
  };

  if (!panel.title.empty())
    c.text(l.title, l.left + 0.5 * w, l.top - 0.5 * fs, {0.5, VAnchor::bottom}, detail::ink(),
           "panel-title");

  // Grid lines under everything else, then ticks and their labels.
  Path grid, ticks;
  for (double v : l.x_ticks.values) {
    grid.move_to(px(v), l.top).line_to(px(v), l.top + h);
    ticks.move_to(px(v), l.top + h).line_to(px(v), l.top + h + kTickLength);
  }
  for (double v : l.y_ticks.values) {
    grid.move_to(l.left, py(v)).line_to(l.left + w, py(v));
    ticks.move_to(l.left - kTickLength, py(v)).line_to(l.left, py(v));
  }
  c.stroke(grid, Pen{Colour::hex("#e3e3e3"), 1.0}, "grid");
  c.stroke(ticks, Pen{detail::axis_grey(), 1.0}, "tick");
  for (size_t i = 0; i < l.x_labels.size(); ++i)
    c.text(l.x_labels[i], px(l.x_ticks.values[i]), l.top + h + kTickLength + 2.0,
           {0.5, VAnchor::top}, detail::axis_grey(), "tick-label");
  for (size_t i = 0; i < l.y_labels.size(); ++i)
    c.text(l.y_labels[i], l.left - kTickLength - 4.0, py(l.y_ticks.values[i]),
           {1.0, VAnchor::middle}, detail::axis_grey(), "tick-label");

  // Axis names: x centred below, y turned and centred on the left.
  c.text(l.x_name, l.left + 0.5 * w, l.top + h + kTickLength + 2.0 + l.x_label_height + 0.3 * fs,
         {0.5, VAnchor::top}, detail::ink(), "axis-label");
  c.text(l.y_name, l.left - l.margin + 0.5 * l.y_name.height(), l.top + 0.5 * h,
         {0.5, VAnchor::middle}, detail::ink(), "axis-label", 90.0);

  // Data, clipped to the plot area.
  c.clip(Path().rect(l.left, l.top, w, h));
  for (const PlotMarker& m : panel.markers)
    c.stroke(Path().move_to(px(m.x), l.top).line_to(px(m.x), l.top + h),
             Pen{Colour::hex("#777777"), 1.0, {4.0, 3.0}}, "marker");
  for (size_t i = 0; i < panel.series.size(); ++i) {
    const PlotSeries& s = panel.series[i];
    Path line;
    bool pen_down = false;
    const size_t n = std::min(s.x.size(), s.y.size());
    for (size_t k = 0; k < n; ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) {
        pen_down = false;
        continue;
      }
      pen_down ? line.line_to(px(s.x[k]), py(s.y[k])) : line.move_to(px(s.x[k]), py(s.y[k]));
      pen_down = true;
    }
    Pen pen{Colour::hex(s.colour.empty() ? palette_colour(i) : s.colour), style.line_width,
            s.dashed ? std::vector<double>{7.0, 4.0} : std::vector<double>{}};
    pen.cap = detail::LineCap::round;
    pen.round_join = true;
    if (!line.empty()) c.stroke(line, pen, "series");
  }
  c.unclip();
  for (size_t i = 0; i < panel.markers.size(); ++i)
    c.text(l.marker_labels[i], px(panel.markers[i].x) + 4.0, l.top + 0.4 * fs, detail::kTopLeft,
           Colour::hex("#555555"), "marker-label");

  // The frame over the data's ends, and the legend to the right of the plot area.
  c.stroke(Path().rect(l.left, l.top, w, h), Pen{detail::axis_grey(), 1.0}, "frame");
  if (panel.series.empty()) return;
  const double x0 = l.left + w + 14.0;
  const double line_height = 1.45 * fs;
  c.fill_and_stroke(Path().rect(x0, l.top, l.legend_width, l.legend_height), detail::white(),
                    Pen{Colour::hex("#bbbbbb"), 1.0}, "legend");
  double y = l.top + 0.3 * fs + 0.5 * line_height;
  if (!panel.legend_title.empty()) {
    c.text(l.legend_title, x0 + 10.0, y, {0.0, VAnchor::middle}, detail::ink(), "legend-text");
    y += line_height;
  }
  for (size_t i = 0; i < panel.series.size(); ++i) {
    const PlotSeries& s = panel.series[i];
    c.stroke(
        Path().move_to(x0 + 10.0, y).line_to(x0 + 34.0, y),
        Pen{Colour::hex(s.colour.empty() ? palette_colour(i) : s.colour), style.line_width + 0.4,
            s.dashed ? std::vector<double>{7.0, 4.0} : std::vector<double>{}},
        "legend-symbol");
    c.text(l.series_labels[i], x0 + 40.0, y, {0.0, VAnchor::middle}, detail::ink(), "legend-text");
    y += line_height;
  }
}

}  // namespace

const char* palette_colour(size_t index) {
  // Okabe-Ito, without its yellow (too faint on white).
  static constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000"};
  return kPalette[index % (sizeof kPalette / sizeof kPalette[0])];
}

Picture plot_picture(const PlotFigure& figure, const PlotStyle& style) {
  const Typesetter type;
  const double fs = style.font_size;
  std::vector<PanelLayout> layouts;
  double x = kOuter;
  for (const PlotPanel& panel : figure.panels) {
    layouts.push_back(lay_out_panel(panel, style, type));
    layouts.back().left = x + layouts.back().margin;
    x += layouts.back().width + kPanelGap;
  }
  const double width = std::max(x - kPanelGap + kOuter, 200.0);

  // Heights: the figure's title and caption, then a row of panels.
  double top = kOuter;
  const Text title =
      type.set(figure.title, Font{1.25 * fs, true}, width - 2.0 * kOuter, detail::Align::centre);
  const Text caption =
      type.set(figure.caption, Font{0.95 * fs}, width - 2.0 * kOuter, detail::Align::centre);
  const double title_top = top;
  if (!figure.title.empty()) top += title.height() + 0.2 * fs;
  const double caption_top = top;
  if (!figure.caption.empty()) top += caption.height();
  double panel_title = 0.0;
  for (const PanelLayout& l : layouts) panel_title = std::max(panel_title, l.title.height());
  top += panel_title > 0.0 ? panel_title + 1.0 * fs : 0.8 * fs;
  double x_name = 0.0;
  for (PanelLayout& l : layouts) {
    l.top = top;
    x_name = std::max(x_name, l.x_label_height + 0.3 * fs + l.x_name.height());
  }
  const double height =
      top + std::max(style.plot_height, 0.0) + kTickLength + 2.0 + x_name + kOuter;

  auto canvas = std::make_shared<Canvas>(width, height);
  Canvas& c = *canvas;
  c.fill(Path().rect(0.0, 0.0, c.width(), c.height()), detail::white(), "background");
  if (!figure.title.empty())
    c.text(title, kOuter, title_top, detail::kTopLeft, detail::ink(), "title");
  if (!figure.caption.empty())
    c.text(caption, kOuter, caption_top, detail::kTopLeft, detail::muted(), "caption");
  for (size_t i = 0; i < figure.panels.size(); ++i)
    draw_panel(c, figure.panels[i], layouts[i], style);
  return Picture(std::move(canvas), figure.title, figure.caption);
}

}  // namespace cueplan::draw
