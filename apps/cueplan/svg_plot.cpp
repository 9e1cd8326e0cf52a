#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace cueplan::cli {

std::string escape_xml(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<TextRun> text_runs(std::string_view label) {
  std::vector<TextRun> runs;
  size_t i = 0;
  while (i < label.size()) {
    const size_t open = label.find("_{", i);
    const size_t close = open == std::string_view::npos ? open : label.find('}', open);
    if (close == std::string_view::npos) {
      runs.push_back({std::string(label.substr(i)), false});
      break;
    }
    if (open > i) runs.push_back({std::string(label.substr(i, open - i)), false});
    runs.push_back({std::string(label.substr(open + 2, close - open - 2)), true});
    i = close + 1;
  }
  return runs;
}

namespace {

// Average advance of a DejaVu Sans glyph, in font sizes: enough to size boxes.
constexpr double kCharWidth = 0.6;
constexpr double kSubscriptScale = 0.75;
constexpr double kTickLength = 5.0;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}


size_t code_points(std::string_view text) {
  return static_cast<size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

double text_width(std::string_view label, double font_size) {
  double width = 0.0;
  for (const TextRun& run : text_runs(label))
    width += static_cast<double>(code_points(run.text)) * kCharWidth * font_size *
             (run.subscript ? kSubscriptScale : 1.0);
  return width;
}

// The inside of a <text> element: subscripts as lowered, smaller tspans. Renderers
// drop spaces at tspan edges, so those become horizontal offsets (dx) instead.
std::string text_body(std::string_view label, double font_size) {
  constexpr double kSpaceWidth = 0.32;  // of the font size, DejaVu Sans
  const double drop = 0.3 * font_size;
  std::vector<TextRun> runs = text_runs(label);
  if (runs.size() == 1) return escape_xml(runs[0].text);
  std::string body;
  bool lowered = false;
  size_t pending_spaces = 0;  // stripped from the end of the previous run
  for (size_t i = 0; i < runs.size(); ++i) {
    std::string text = runs[i].text;
    const size_t lead = i == 0 ? 0 : std::min(text.find_first_not_of(' '), text.size());
    const size_t last = text.find_last_not_of(' ');
    const size_t trail = last == std::string::npos ? 0 : text.size() - 1 - last;
    text = text.substr(lead, text.size() - lead - (lead == text.size() ? 0 : trail));
    const double dx = static_cast<double>(pending_spaces + lead) * kSpaceWidth * font_size;
    pending_spaces = trail;
    const std::string offset = dx > 0.0 ? " dx=\"" + num(dx) + "\"" : "";
    if (runs[i].subscript) {
      body += "<tspan dy=\"" + num(lowered ? 0.0 : drop) + "\"" + offset + " font-size=\"" +
              num(font_size * kSubscriptScale) + "\">" + escape_xml(text) + "</tspan>";
      lowered = true;
    } else if (lowered || !offset.empty()) {
      body += "<tspan dy=\"" + num(lowered ? -drop : 0.0) + "\"" + offset + ">" + escape_xml(text) +
              "</tspan>";
      lowered = false;
    } else {
      body += escape_xml(text);
    }
  }
  return body;
}

std::string text_element(double x, double y, std::string_view label, double font_size,
                         std::string_view anchor, std::string_view extra = {}) {
  std::string element = "<text x=\"";
  element += num(x);
  element += "\" y=\"";
  element += num(y);
  element += "\" font-size=\"";
  element += num(font_size);
  element += "\" text-anchor=\"";
  element += anchor;
  element += '"';
  if (!extra.empty()) {
    element += ' ';
    element += extra;
  }
  element += '>';
  element += text_body(label, font_size);
  element += "</text>\n";
  return element;
}

// Tick positions along one axis and the range they span.
struct Ticks {
  double lo = 0.0;
  double hi = 1.0;
  std::vector<double> values;
  int decimals = 0;
};

double nice_step(double raw) {
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {1.0, 2.0, 2.5, 5.0})
    if (mantissa * decade >= raw * (1.0 - 1e-9)) return mantissa * decade;
  return 10.0 * decade;
}

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

  const double step = axis.tick_step.value_or(nice_step((hi - lo) / 5.0));
  Ticks t;
  t.lo = axis.min ? lo : std::floor(lo / step + 1e-9) * step;
  t.hi = axis.max ? hi : std::ceil(hi / step - 1e-9) * step;
  const double first = std::ceil(t.lo / step - 1e-9);
  for (double k = first;; k += 1.0) {
    double v = k * step;
    if (v > t.hi + 1e-9 * step) break;
    if (std::abs(v) < 1e-12 * step) v = 0.0;  // no "-0"
    t.values.push_back(v);
  }
  // Enough decimals to tell neighbouring ticks apart.
  const double exponent = std::floor(std::log10(step) + 1e-9);
  const double mantissa = step / std::pow(10.0, exponent);
  const bool half_step = std::abs(mantissa - std::round(mantissa)) > 1e-6;
  t.decimals = std::max(0, static_cast<int>(-exponent) + (half_step ? 1 : 0));
  return t;
}

std::string tick_label(double value, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  std::string s = buf;
  if (s.rfind("-", 0) == 0 && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  // A typographic minus reads better than a hyphen.
  if (!s.empty() && s[0] == '-') s.replace(0, 1, "\u2212");
  return s;
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

// Geometry of one panel within the figure.
struct PanelLayout {
  double left = 0.0;   // x of the plot area
  double top = 0.0;    // y of the plot area
  double width = 0.0;  // of the whole panel, legend included
  double legend_width = 0.0;
  Ticks x_ticks;
  Ticks y_ticks;
};

double series_legend_width(const PlotPanel& panel, double fs) {
  if (panel.series.empty()) return 0.0;
  double widest = text_width(panel.legend_title, fs);
  for (const PlotSeries& s : panel.series)
    widest = std::max(widest, 30.0 + text_width(s.label, fs));
  return widest + 20.0;
}

PanelLayout layout_panel(const PlotPanel& panel, const PlotStyle& style) {
  PanelLayout layout;
  Range xr;
  Range yr;
  for (const PlotSeries& s : panel.series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
  }
  for (const PlotMarker& m : panel.markers) xr.add(m.x);
  layout.x_ticks = make_ticks(panel.x_axis, xr.lo, xr.hi);
  layout.y_ticks = make_ticks(panel.y_axis, yr.lo, yr.hi);
  layout.legend_width = series_legend_width(panel, style.font_size);
  return layout;
}

// Room left of the plot area for the y tick labels and the y axis label.
double left_margin(const PanelLayout& layout, const PlotStyle& style) {
  double widest = 0.0;
  for (double v : layout.y_ticks.values)
    widest =
        std::max(widest, text_width(tick_label(v, layout.y_ticks.decimals), style.font_size * 0.9));
  return kTickLength + 6.0 + widest + 8.0 + 1.3 * style.font_size;
}

std::string series_path(const PlotSeries& s, const PanelLayout& l, const PlotStyle& style) {
  const auto px = [&](double x) {
    return l.left + (x - l.x_ticks.lo) / (l.x_ticks.hi - l.x_ticks.lo) * style.plot_width;
  };
  const auto py = [&](double y) {
    return l.top + (l.y_ticks.hi - y) / (l.y_ticks.hi - l.y_ticks.lo) * style.plot_height;
  };
  std::string d;
  bool pen_down = false;
  const size_t n = std::min(s.x.size(), s.y.size());
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      pen_down = false;
      continue;
    }
    d += pen_down ? " L" : " M";
    d += num(px(s.x[i])) + " " + num(py(s.y[i]));
    pen_down = true;
  }
  return d;
}

std::string render_panel(const PlotPanel& panel, const PanelLayout& l, size_t index,
                         const PlotStyle& style) {
  const double fs = style.font_size;
  const double w = style.plot_width;
  const double h = style.plot_height;
  const auto px = [&](double x) {
    return l.left + (x - l.x_ticks.lo) / (l.x_ticks.hi - l.x_ticks.lo) * w;
  };
  const auto py = [&](double y) {
    return l.top + (l.y_ticks.hi - y) / (l.y_ticks.hi - l.y_ticks.lo) * h;
  };
  std::string svg = "<g class=\"panel\">\n";

  // Panel title above the plot area.
  if (!panel.title.empty())
    svg += text_element(l.left + w / 2.0, l.top - 0.8 * fs, panel.title, 1.05 * fs, "middle",
                        "font-weight=\"bold\"");

  // Grid lines under everything else.
  svg += "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double v : l.x_ticks.values)
    svg += "<line x1=\"" + num(px(v)) + "\" y1=\"" + num(l.top) + "\" x2=\"" + num(px(v)) +
           "\" y2=\"" + num(l.top + h) + "\"/>\n";
  for (double v : l.y_ticks.values)
    svg += "<line x1=\"" + num(l.left) + "\" y1=\"" + num(py(v)) + "\" x2=\"" + num(l.left + w) +
           "\" y2=\"" + num(py(v)) + "\"/>\n";
  svg += "</g>\n";

  // Ticks and their labels.
  svg += "<g stroke=\"#333333\" stroke-width=\"1\">\n";
  for (double v : l.x_ticks.values)
    svg += "<line x1=\"" + num(px(v)) + "\" y1=\"" + num(l.top + h) + "\" x2=\"" + num(px(v)) +
           "\" y2=\"" + num(l.top + h + kTickLength) + "\"/>\n";
  for (double v : l.y_ticks.values)
    svg += "<line x1=\"" + num(l.left - kTickLength) + "\" y1=\"" + num(py(v)) + "\" x2=\"" +
           num(l.left) + "\" y2=\"" + num(py(v)) + "\"/>\n";
  svg += "</g>\n<g fill=\"#333333\">\n";
  for (double v : l.x_ticks.values)
    svg += text_element(px(v), l.top + h + kTickLength + 1.05 * fs,
                        tick_label(v, l.x_ticks.decimals), 0.9 * fs, "middle");
  for (double v : l.y_ticks.values)
    svg += text_element(l.left - kTickLength - 4.0, py(v) + 0.32 * fs,
                        tick_label(v, l.y_ticks.decimals), 0.9 * fs, "end");
  svg += "</g>\n";

  // Axis labels: x centred below, y rotated and centred on the left.
  svg += text_element(l.left + w / 2.0, l.top + h + kTickLength + 2.6 * fs, panel.x_axis.label, fs,
                      "middle");
  const double y_label_x = l.left - left_margin(l, style) + 1.0 * fs;
  const double y_label_y = l.top + h / 2.0;
  svg += text_element(y_label_x, y_label_y, panel.y_axis.label, fs, "middle",
                      "transform=\"rotate(-90 " + num(y_label_x) + " " + num(y_label_y) + ")\"");

  // Data, clipped to the plot area.
  const std::string clip_id = "plot-area-" + std::to_string(index);
  svg += "<clipPath id=\"" + clip_id + "\"><rect x=\"" + num(l.left) + "\" y=\"" + num(l.top) +
         "\" width=\"" + num(w) + "\" height=\"" + num(h) + "\"/></clipPath>\n";
  svg += "<g clip-path=\"url(#" + clip_id +
         ")\" fill=\"none\" stroke-linejoin=\"round\" "
         "stroke-linecap=\"round\">\n";
  for (const PlotMarker& m : panel.markers)
    svg += "<line x1=\"" + num(px(m.x)) + "\" y1=\"" + num(l.top) + "\" x2=\"" + num(px(m.x)) +
           "\" y2=\"" + num(l.top + h) +
           "\" stroke=\"#777777\" stroke-width=\"1\" stroke-dasharray=\"4 3\"/>\n";
  for (size_t i = 0; i < panel.series.size(); ++i) {
    const PlotSeries& s = panel.series[i];
    const std::string colour = s.colour.empty() ? palette_colour(i) : s.colour;
    svg += "<path d=\"" + series_path(s, l, style) + "\" stroke=\"" + colour +
           "\" stroke-width=\"" + num(style.line_width) + "\"" +
           (s.dashed ? " stroke-dasharray=\"7 4\"" : "") + "/>\n";
  }
  svg += "</g>\n";
  for (const PlotMarker& m : panel.markers)
    svg += text_element(px(m.x) + 4.0, l.top + 1.1 * fs, m.label, 0.85 * fs, "start",
                        "fill=\"#555555\"");

  // Frame over the data's ends.
  svg += "<rect x=\"" + num(l.left) + "\" y=\"" + num(l.top) + "\" width=\"" + num(w) +
         "\" height=\"" + num(h) + "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";

  // Legend to the right of the plot area.
  if (!panel.series.empty()) {
    const double x0 = l.left + w + 14.0;
    const double line_height = 1.45 * fs;
    const size_t lines = panel.series.size() + (panel.legend_title.empty() ? 0 : 1);
    const double box_height = static_cast<double>(lines) * line_height + 0.6 * fs;
    svg += "<rect x=\"" + num(x0) + "\" y=\"" + num(l.top) + "\" width=\"" + num(l.legend_width) +
           "\" height=\"" + num(box_height) +
           "\" rx=\"3\" fill=\"#ffffff\" stroke=\"#bbbbbb\" stroke-width=\"1\"/>\n";
    double y = l.top + 0.3 * fs + line_height / 2.0;
    if (!panel.legend_title.empty()) {
      svg += text_element(x0 + 10.0, y + 0.35 * fs, panel.legend_title, fs, "start",
                          "font-weight=\"bold\"");
      y += line_height;
    }
    for (size_t i = 0; i < panel.series.size(); ++i) {
      const PlotSeries& s = panel.series[i];
      const std::string colour = s.colour.empty() ? palette_colour(i) : s.colour;
      svg += "<line x1=\"" + num(x0 + 10.0) + "\" y1=\"" + num(y) + "\" x2=\"" + num(x0 + 34.0) +
             "\" y2=\"" + num(y) + "\" stroke=\"" + colour + "\" stroke-width=\"" +
             num(style.line_width + 0.4) + "\"" + (s.dashed ? " stroke-dasharray=\"7 4\"" : "") +
             "/>\n";
      svg += text_element(x0 + 40.0, y + 0.35 * fs, s.label, fs, "start");
      y += line_height;
    }
  }
  svg += "</g>\n";
  return svg;
}

}  // namespace

const char* palette_colour(size_t index) {
  // Okabe-Ito, without its yellow (too faint on white).
  static constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000"};
  return kPalette[index % (sizeof kPalette / sizeof kPalette[0])];
}

std::string render_svg(const PlotFigure& figure, const PlotStyle& style) {
  const double fs = style.font_size;
  const double outer = 16.0;

  // Heights: figure title and caption, then a row of panels.
  double top = outer;
  if (!figure.title.empty()) top += 1.5 * fs;
  if (!figure.caption.empty()) top += 1.4 * fs;
  const bool any_panel_title = std::any_of(figure.panels.begin(), figure.panels.end(),
                                           [](const PlotPanel& p) { return !p.title.empty(); });
  top += any_panel_title ? 2.4 * fs : 0.8 * fs;

  // Widths: each panel is its y margin, plot area and legend.
  std::vector<PanelLayout> layouts;
  double x = outer;
  for (const PlotPanel& panel : figure.panels) {
    PanelLayout l = layout_panel(panel, style);
    l.left = x + left_margin(l, style);
    l.top = top;
    const double legend = l.legend_width > 0.0 ? 14.0 + l.legend_width : 0.0;
    l.width = left_margin(l, style) + style.plot_width + legend;
    x += l.width + 24.0;
    layouts.push_back(std::move(l));
  }
  const double width = std::max(x - 24.0 + outer, 200.0);
  const double height = top + style.plot_height + kTickLength + 3.2 * fs + outer;

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" +
         num(height) + "\" viewBox=\"0 0 " + num(width) + " " + num(height) + "\" font-family=\"" +
         escape_xml(style.font_family) + "\" fill=\"#1a1a1a\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  double y = outer;
  if (!figure.title.empty()) {
    y += 1.1 * fs;
    svg += text_element(width / 2.0, y, figure.title, 1.25 * fs, "middle", "font-weight=\"bold\"");
  }
  if (!figure.caption.empty()) {
    y += 1.4 * fs;
    svg += text_element(width / 2.0, y, figure.caption, 0.95 * fs, "middle", "fill=\"#444444\"");
  }
  for (size_t i = 0; i < figure.panels.size(); ++i)
    svg += render_panel(figure.panels[i], layouts[i], i, style);
  svg += "</svg>\n";
  return svg;
}

}  // namespace cueplan::cli
