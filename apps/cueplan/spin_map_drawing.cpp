#include "spin_map_drawing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <string_view>

#include "raster_image.hpp"
#include "svg_plot.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;

constexpr double kSpinPerTipOffset = 2.5;  // k = 2.5 d / R (PHYSICS.md, "Cue strike")
constexpr double kOuter = 16.0;            // blank border (px)
constexpr double kPanelGap = 36.0;         // between the disc panel and the table panel
constexpr double kDiscSize = 440.0;        // px across the cells of the disc
constexpr double kPixelsPerMetre = 260.0;  // the table panel's scale

constexpr const char* kInk = "#1a1a1a";
constexpr const char* kMuted = "#444444";
constexpr const char* kWrongCushions = "#c6c6c6";
constexpr const char* kObstacleCell = "#7a7a7a";
constexpr const char* kNoResult = "#f0f0f0";
constexpr const char* kHatch = "#3a3a3a";
constexpr const char* kOutline = "#000000";
constexpr const char* kTargetColour = "#009E73";  // as table_drawing's target zone

// Viridis (matplotlib) at eleven evenly spaced points; linear in between.
constexpr std::array<std::array<int, 3>, 11> kViridis = {{{68, 1, 84},
                                                          {72, 36, 117},
                                                          {65, 68, 135},
                                                          {53, 95, 141},
                                                          {42, 120, 142},
                                                          {33, 145, 140},
                                                          {34, 168, 132},
                                                          {68, 191, 112},
                                                          {122, 209, 81},
                                                          {189, 223, 38},
                                                          {253, 231, 37}}};

std::string hex_colour(double r, double g, double b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(r)),
                static_cast<int>(std::lround(g)), static_cast<int>(std::lround(b)));
  return buf;
}

std::string viridis(double t) {
  t = std::clamp(t, 0.0, 1.0) * 10.0;
  const size_t i = std::min<size_t>(9, static_cast<size_t>(t));
  const double f = t - static_cast<double>(i);
  const auto& a = kViridis[i];
  const auto& b = kViridis[i + 1];
  return hex_colour(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]));
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string format(const char* pattern, double a) {
  char buf[128];
  std::snprintf(buf, sizeof buf, pattern, a);
  return buf;
}

std::string mm_label(double mm) { return format("%.4g", mm); }

std::string cushions_allowed(const prob::Limits& limits) {
  return limits.cushions_min == limits.cushions_max
             ? std::to_string(limits.cushions_min)
             : std::to_string(limits.cushions_min) + " to " + std::to_string(limits.cushions_max);
}

// ---------------------------------------------------------------------------
// What the picture shows, independent of SVG or PNG.

// Cells of the disc: where each grid spin sits and how it is filled.
struct Cell {
  size_t index = 0;      // into map.points
  int row = 0, col = 0;  // col 0 at the left (most left spin), row 0 at the bottom
  SpinCellKind kind = SpinCellKind::distance;
  std::string colour;  // fill, for every kind but pocketed (hatched)
};

int grid_index(double k, const plan::SpinMap& map) {
  const double half = 0.5 * (map.grid - 1);
  return static_cast<int>(std::lround(k / map.spin_max * half + half));
}

std::string cell_colour(SpinCellKind kind, double miss, const MissColourScale& scale) {
  switch (kind) {
    case SpinCellKind::distance:
      return scale.colour(miss);
    case SpinCellKind::wrong_cushions:
      return kWrongCushions;
    case SpinCellKind::pocketed:
      return "#ffffff";
    case SpinCellKind::obstacle:
      return kObstacleCell;
    case SpinCellKind::no_result:
      return kNoResult;
  }
  return kNoResult;
}

// A legend row: a swatch drawn by the backend and its text.
enum class Swatch { landing, wrong_cushions, pocketed, obstacle, no_result, marked, miscue };
struct LegendRow {
  Swatch swatch;
  std::string text;
};

// Positions of everything, in px, for a given text size (SVG and PNG use their own).
struct Metrics {
  double font = 13.0;       // px, body text
  double char_width = 7.3;  // px per character of body text (average)
  double title_font = 16.0;
  double title_char = 9.0;
  bool rotated_text = true;  // the disc's vertical axis label runs up its left side
};

struct Layout {
  double width = 0.0, height = 0.0;
  double title_y = 0.0;
  double caption_y = 0.0, line = 0.0;
  double disc_title_y = 0.0;
  double disc_left = 0.0, disc_top = 0.0;  // the square of the cells
  double cx = 0.0, cy = 0.0, scale = 0.0, cell = 0.0, radius_px = 0.0;
  double tick_step = 0.25;  // d/R between ticks
  double x_label_y = 0.0;
  double bar_left = 0.0, bar_top = 0.0, bar_width = 0.0, bar_height = 14.0;
  double bar_label_y = 0.0;
  double legend_top = 0.0, legend_row = 0.0;
  double table_left = 0.0, table_top = 0.0;

  double x(double right) const { return cx + right * scale; }
  double y(double up) const { return cy - up * scale; }
};

struct Figure {
  const SpinMapPicture* picture = nullptr;
  MissColourScale scale;
  std::vector<Cell> cells;
  std::vector<LegendRow> legend;
  std::vector<std::string> caption;
  std::string disc_title;
  std::string bar_label;
};

Figure figure_of(const SpinMapPicture& picture) {
  Figure f;
  f.picture = &picture;
  const plan::SpinMap& map = picture.map;
  const prob::Problem& problem = picture.problem;
  f.scale = miss_colour_scale(map, problem);
  int counts[5] = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < map.points.size(); ++i) {
    const plan::SpinMapPoint& p = map.points[i];
    Cell c;
    c.index = i;
    c.col = grid_index(p.sidespin_k, map);
    c.row = grid_index(p.topspin_k, map);
    c.kind = classify(p, problem.limits);
    c.colour = cell_colour(c.kind, p.miss_distance, f.scale);
    ++counts[static_cast<int>(c.kind)];
    f.cells.push_back(c);
  }
  const auto spins = [](int n) {
    return " (" + std::to_string(n) + (n == 1 ? " spin)" : " spins)");
  };
  f.legend.push_back(
      {Swatch::landing, "lands: at rest within " + mm_label(1000.0 * problem.tolerance) +
                            " mm after " + cushions_allowed(problem.limits) +
                            (problem.limits.cushions_max == 1 ? " cushion" : " cushions") +
                            ", outlined" + spins(map.landing)});
  if (counts[static_cast<int>(SpinCellKind::wrong_cushions)] > 0)
    f.legend.push_back(
        {Swatch::wrong_cushions,
         "at rest after a cushion count not allowed (allowed: " + cushions_allowed(problem.limits) +
             ")" + spins(counts[static_cast<int>(SpinCellKind::wrong_cushions)])});
  if (counts[static_cast<int>(SpinCellKind::pocketed)] > 0)
    f.legend.push_back(
        {Swatch::pocketed, "pocketed" + spins(counts[static_cast<int>(SpinCellKind::pocketed)])});
  if (counts[static_cast<int>(SpinCellKind::obstacle)] > 0)
    f.legend.push_back(
        {Swatch::obstacle, "stops against an obstacle ball" +
                               spins(counts[static_cast<int>(SpinCellKind::obstacle)])});
  if (counts[static_cast<int>(SpinCellKind::no_result)] > 0)
    f.legend.push_back(
        {Swatch::no_result, "no outcome (event limit or impact failure)" +
                                spins(counts[static_cast<int>(SpinCellKind::no_result)])});
  if (picture.marked_shot) f.legend.push_back({Swatch::marked, "the planner's spin"});
  f.legend.push_back({Swatch::miscue, "spin limit: tip offset " +
                                          format("%.3g", map.spin_max / kSpinPerTipOffset) +
                                          " R (k = " + format("%.3g", map.spin_max) + ")"});
  f.disc_title = "Tip offset on the cue ball (fraction of its radius R)";
  f.bar_label = "miss distance from the target (mm, log scale)";
  return f;
}

// A nice tick step (d/R) for the disc's axes.
double disc_tick_step(double radius) {
  for (double step : {0.05, 0.1, 0.125, 0.25, 0.5, 1.0})
    if (radius / step <= 3.0 + 1e-9) return step;
  return 1.0;
}

std::string tick_text(double v) {
  std::string s = format("%.3f", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

double longest(const std::vector<std::string>& lines) {
  size_t n = 0;
  for (const std::string& s : lines) n = std::max(n, s.size());
  return static_cast<double>(n);
}

// The layout for text of the given metrics and a table panel of the given size (px).
Layout layout_of(const Figure& f, const Metrics& m, double table_width, double table_height) {
  const plan::SpinMap& map = f.picture->map;
  Layout l;
  l.line = 1.45 * m.font;
  double y = kOuter;
  l.title_y = y + m.title_font;
  y += 1.7 * m.title_font;
  l.caption_y = y + m.font;
  y += static_cast<double>(f.caption.size()) * l.line + 0.6 * m.font;

  const double panels_top = y;
  l.disc_title_y = y + m.font;
  y += 2.0 * m.font;
  if (!m.rotated_text) y += 1.4 * m.font;  // a line for the vertical axis label
  // Tick labels on the left of the disc.
  const double tick_label_width = 5.0 * m.char_width + 8.0;
  l.disc_left = kOuter + 1.6 * m.font + tick_label_width;
  l.disc_top = y;
  const double radius_d = map.spin_max / kSpinPerTipOffset;
  const double step_d = 2.0 * radius_d / (map.grid - 1);
  l.scale = kDiscSize / (2.0 * radius_d + step_d);
  l.cell = step_d * l.scale;
  l.cx = l.disc_left + 0.5 * kDiscSize;
  l.cy = l.disc_top + 0.5 * kDiscSize;
  l.radius_px = radius_d * l.scale;
  l.tick_step = disc_tick_step(radius_d);
  y += kDiscSize + 6.0 + 1.3 * m.font;  // ticks and their labels
  l.x_label_y = y + m.font;
  y += 2.2 * m.font;

  l.bar_left = l.disc_left;
  l.bar_width = kDiscSize;
  l.bar_top = y;
  y += l.bar_height + 4.0 + 1.2 * m.font;  // bar and tick labels
  l.bar_label_y = y + m.font;
  y += 2.0 * m.font;

  l.legend_top = y;
  l.legend_row = 1.6 * m.font;
  y += static_cast<double>(f.legend.size()) * l.legend_row;

  double left_right = l.disc_left + kDiscSize;
  left_right = std::max(
      left_right, l.disc_left + 34.0 + m.char_width * [&] {
        size_t n = 0;
        for (const LegendRow& r : f.legend) n = std::max(n, r.text.size());
        return static_cast<double>(n);
      }());
  left_right =
      std::max(left_right, kOuter + m.char_width * static_cast<double>(f.disc_title.size()));
  l.table_left = left_right + kPanelGap;
  l.table_top = panels_top;

  l.width = std::max({l.table_left + table_width + kOuter,
                      2.0 * kOuter + m.title_char * static_cast<double>(f.picture->title.size()),
                      2.0 * kOuter + m.char_width * longest(f.caption)});
  l.height = std::max(y, panels_top + table_height) + kOuter;
  return l;
}

// The landing region's boundary: cell edges between a landing spin and one that is not.
struct Edge {
  double x1, y1, x2, y2;
};

std::vector<Edge> landing_outline(const Figure& f, const Layout& l) {
  const plan::SpinMap& map = f.picture->map;
  const int n = map.grid;
  std::vector<char> lands(static_cast<size_t>(n) * static_cast<size_t>(n), 0);
  const auto at = [&](int row, int col) -> char {
    if (row < 0 || col < 0 || row >= n || col >= n) return 0;
    return lands[static_cast<size_t>(row) * static_cast<size_t>(n) + static_cast<size_t>(col)];
  };
  for (const Cell& c : f.cells)
    if (map.points[c.index].lands)
      lands[static_cast<size_t>(c.row) * static_cast<size_t>(n) + static_cast<size_t>(c.col)] = 1;
  std::vector<Edge> edges;
  const double h = 0.5 * l.cell;
  for (const Cell& c : f.cells) {
    if (!at(c.row, c.col)) continue;
    const plan::SpinMapPoint& p = map.points[c.index];
    const double x = l.x(p.tip_right);
    const double y = l.y(p.tip_up);
    if (!at(c.row + 1, c.col)) edges.push_back({x - h, y - h, x + h, y - h});
    if (!at(c.row - 1, c.col)) edges.push_back({x - h, y + h, x + h, y + h});
    if (!at(c.row, c.col - 1)) edges.push_back({x - h, y - h, x - h, y + h});
    if (!at(c.row, c.col + 1)) edges.push_back({x + h, y - h, x + h, y + h});
  }
  return edges;
}

// Rest positions as dots, the farthest first so that the landing ones end on top.
std::vector<size_t> dot_order(const Figure& f) {
  const plan::SpinMap& map = f.picture->map;
  std::vector<size_t> order(map.points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const auto key = [&](size_t i) {
      const plan::SpinMapPoint& p = map.points[i];
      return p.lands ? -1.0 : std::isfinite(p.miss_distance) ? p.miss_distance : 1e9;
    };
    return key(a) > key(b);
  });
  return order;
}

// The colour bar's ticks: where each sits (px), its label and the label's anchor (0 start,
// 0.5 middle, 1 end). Labels that would touch a neighbour's are left empty; the first
// (the tolerance, written "<= 20" with `at_most`) and the last always stay.
struct BarTick {
  double x = 0.0;
  std::string label;
  double anchor = 0.5;
};

std::vector<BarTick> bar_ticks(const Figure& f, const Layout& l, double char_width,
                               const std::string& at_most) {
  const std::vector<double> values = f.scale.ticks_mm();
  std::vector<BarTick> ticks;
  for (size_t i = 0; i < values.size(); ++i) {
    BarTick t;
    t.x = l.bar_left + l.bar_width * f.scale.position(values[i]);
    t.label = (i == 0 ? at_most : "") + mm_label(values[i]);
    t.anchor = i == 0 ? 0.0 : i + 1 == values.size() ? 1.0 : 0.5;
    ticks.push_back(t);
  }
  const auto left = [&](const BarTick& t) {
    return t.x - t.anchor * char_width * static_cast<double>(t.label.size());
  };
  const auto right = [&](const BarTick& t) {
    return t.x + (1.0 - t.anchor) * char_width * static_cast<double>(t.label.size());
  };
  const double gap = char_width;
  double kept_right = ticks.empty() ? 0.0 : right(ticks.front());
  for (size_t i = 1; i + 1 < ticks.size(); ++i) {
    if (left(ticks[i]) > kept_right + gap && right(ticks[i]) < left(ticks.back()) - gap)
      kept_right = right(ticks[i]);
    else
      ticks[i].label.clear();
  }
  return ticks;
}

// ---------------------------------------------------------------------------
// SVG


// A <text> element; `k_{T}` becomes a lowered, smaller T.
std::string svg_text(double x, double y, std::string_view label, double size,
                     std::string_view anchor = "start", std::string_view extra = {}) {
  std::string body;
  size_t i = 0;
  while (i < label.size()) {
    const size_t open = label.find("_{", i);
    const size_t close = open == std::string_view::npos ? open : label.find('}', open);
    if (close == std::string_view::npos) {
      body += escape_xml(label.substr(i));
      break;
    }
    body += escape_xml(label.substr(i, open - i));
    body += "<tspan dy=\"" + num(0.3 * size) + "\" font-size=\"" + num(0.75 * size) + "\">" +
            escape_xml(label.substr(open + 2, close - open - 2)) + "</tspan><tspan dy=\"" +
            num(-0.3 * size) + "\"></tspan>";
    i = close + 1;
  }
  std::string element = "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) +
                        "\" text-anchor=\"" + std::string(anchor) + "\"";
  if (!extra.empty()) element += " " + std::string(extra);
  return element + ">" + body + "</text>\n";
}

std::string svg_rect(double x, double y, double w, double h, std::string_view attributes) {
  return "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" +
         num(h) + "\" " + std::string(attributes) + "/>\n";
}

std::string svg_circle(double cx, double cy, double r, std::string_view attributes) {
  return "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"" + num(r) + "\" " +
         std::string(attributes) + "/>\n";
}

std::string svg_line(double x1, double y1, double x2, double y2, std::string_view attributes) {
  return "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" +
         num(y2) + "\" " + std::string(attributes) + "/>\n";
}

std::string svg_swatch(Swatch s, double x, double y, double size) {
  switch (s) {
    case Swatch::landing:
      return svg_rect(x, y - 0.5 * size, size, size,
                      std::string("fill=\"") + viridis(1.0) + "\" stroke=\"" + kOutline +
                          "\" stroke-width=\"2\"");
    case Swatch::wrong_cushions:
      return svg_rect(x, y - 0.5 * size, size, size,
                      std::string("fill=\"") + kWrongCushions + "\"");
    case Swatch::pocketed:
      return svg_rect(x, y - 0.5 * size, size, size,
                      "fill=\"url(#pocketed-hatch)\" stroke=\"#999999\" stroke-width=\"0.5\"");
    case Swatch::obstacle:
      return svg_rect(x, y - 0.5 * size, size, size, std::string("fill=\"") + kObstacleCell + "\"");
    case Swatch::no_result:
      return svg_rect(
          x, y - 0.5 * size, size, size,
          std::string("fill=\"") + kNoResult + "\" stroke=\"#999999\" stroke-width=\"0.5\"");
    case Swatch::marked:
      return svg_circle(x + 0.5 * size, y, 0.4 * size,
                        "fill=\"none\" stroke=\"#ffffff\" stroke-width=\"4\"") +
             svg_circle(x + 0.5 * size, y, 0.4 * size,
                        std::string("fill=\"none\" stroke=\"") + kInk + "\" stroke-width=\"2\"");
    case Swatch::miscue:
      return svg_line(
          x, y, x + size, y,
          std::string("stroke=\"") + kInk + "\" stroke-width=\"1.5\" stroke-dasharray=\"4 3\"");
  }
  return {};
}

// The table panel: table_drawing's SVG, with the grid spins' rest positions as dots.
std::string table_panel_svg(const Figure& f) {
  const SpinMapPicture& picture = *f.picture;
  const prob::Problem& problem = picture.problem;
  TableDrawing d;
  d.title = "Where each spin stops (dots coloured as their cells)";
  d.caption.push_back("Table " + format("%.4g", problem.scene.length) + " \u00d7 " +
                      format("%.4g", problem.scene.width) + " m between the cushion noses; " +
                      std::to_string(picture.map.points.size()) + " spins");
  d.scene = problem.scene;
  d.cue_ball = problem.cue_ball;
  d.target = TargetZone{problem.target, problem.tolerance};
  for (const DrawnPath& p : picture.sample_paths) d.paths.push_back(p);
  if (picture.shot_path) d.paths.push_back(*picture.shot_path);
  d.faint_legend = "paths of a few grid spins";
  for (size_t i : dot_order(f)) {
    const plan::SpinMapPoint& p = picture.map.points[i];
    const Cell& c = f.cells[i];
    TableDot dot;
    dot.position = p.final_position;
    dot.colour = c.kind == SpinCellKind::pocketed ? kHatch : c.colour;
    dot.radius = p.lands ? 3.5 : 2.6;
    dot.outline = p.lands ? kOutline : std::string();
    d.dots.push_back(dot);
  }
  TableStyle style;
  style.pixels_per_metre = kPixelsPerMetre;
  return render_table_svg(d, style);
}

double svg_attribute(const std::string& svg, const std::string& name) {
  const size_t tag = svg.find("<svg ");
  const size_t at = svg.find(" " + name + "=\"", tag);
  if (tag == std::string::npos || at == std::string::npos) return 0.0;
  return std::atof(svg.c_str() + at + name.size() + 3);
}

}  // namespace

SpinCellKind classify(const plan::SpinMapPoint& point, const prob::Limits& limits) {
  switch (point.outcome) {
    case phys::ShotStatus::rest:
      return point.cushion_hits >= limits.cushions_min && point.cushion_hits <= limits.cushions_max
                 ? SpinCellKind::distance
                 : SpinCellKind::wrong_cushions;
    case phys::ShotStatus::pocketed:
      return SpinCellKind::pocketed;
    case phys::ShotStatus::hit_obstacle:
      return SpinCellKind::obstacle;
    default:
      return SpinCellKind::no_result;
  }
}

double MissColourScale::position(double miss_mm) const {
  if (!(miss_mm > near_mm)) return 0.0;
  return std::clamp(std::log(miss_mm / near_mm) / std::log(far_mm / near_mm), 0.0, 1.0);
}

std::string MissColourScale::colour(double miss_m) const {
  return viridis(1.0 - position(1000.0 * miss_m));
}

std::vector<double> MissColourScale::ticks_mm() const {
  std::vector<double> ticks = {near_mm};
  for (double decade = std::pow(10.0, std::floor(std::log10(near_mm))); decade <= far_mm;
       decade *= 10.0)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * decade;
      // Skip values that would crowd the tolerance's label.
      if (v > near_mm * 1.6 && v <= far_mm * (1.0 + 1e-9)) ticks.push_back(v);
    }
  return ticks;
}

MissColourScale miss_colour_scale(const plan::SpinMap& map, const prob::Problem& problem) {
  MissColourScale s;
  s.near_mm = 1000.0 * problem.tolerance;
  double largest = 0.0;
  for (const plan::SpinMapPoint& p : map.points)
    if (classify(p, problem.limits) == SpinCellKind::distance)
      largest = std::max(largest, 1000.0 * p.miss_distance);
  largest = std::max(largest, 10.0 * s.near_mm);
  // The next 1-2-5 value up.
  const double decade = std::pow(10.0, std::floor(std::log10(largest)));
  s.far_mm = 10.0 * decade;
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= largest * (1.0 - 1e-12)) {
      s.far_mm = m * decade;
      break;
    }
  return s;
}

std::vector<size_t> sparse_subset(const plan::SpinMap& map, int per_side) {
  std::vector<size_t> chosen;
  if (map.grid < 2 || per_side < 2) return chosen;
  const int step = std::max(1, static_cast<int>(std::lround((map.grid - 1.0) / (per_side - 1.0))));
  const int centre = (map.grid - 1) / 2;
  for (size_t i = 0; i < map.points.size(); ++i) {
    const int row = grid_index(map.points[i].topspin_k, map);
    const int col = grid_index(map.points[i].sidespin_k, map);
    if ((row - centre) % step == 0 && (col - centre) % step == 0) chosen.push_back(i);
  }
  return chosen;
}

std::string render_spin_map_svg(const SpinMapPicture& picture) {
  Figure f = figure_of(picture);
  f.caption = picture.caption;
  const Metrics m;  // 13 px text
  const std::string table = table_panel_svg(f);
  const double table_width = svg_attribute(table, "width");
  const double table_height = svg_attribute(table, "height");
  const Layout l = layout_of(f, m, table_width, table_height);
  const plan::SpinMap& map = picture.map;

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(l.width) + "\" height=\"" +
         num(l.height) + "\" viewBox=\"0 0 " + num(l.width) + " " + num(l.height) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" fill=\"" + kInk + "\">\n";
  svg +=
      "<defs><pattern id=\"pocketed-hatch\" width=\"5\" height=\"5\" "
      "patternUnits=\"userSpaceOnUse\" "
      "patternTransform=\"rotate(45)\"><rect width=\"5\" height=\"5\" fill=\"#ffffff\"/>"
      "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"5\" stroke=\"" +
      std::string(kHatch) + "\" stroke-width=\"2\"/></pattern></defs>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  svg += svg_text(kOuter, l.title_y, picture.title, m.title_font, "start", "font-weight=\"bold\"");
  for (size_t i = 0; i < f.caption.size(); ++i)
    svg += svg_text(kOuter, l.caption_y + static_cast<double>(i) * l.line, f.caption[i],
                    0.95 * m.font, "start", std::string("fill=\"") + kMuted + "\"");

  // The disc: title, cells, the landing outline, the limit circle, the centre cross.
  svg += svg_text(kOuter, l.disc_title_y, f.disc_title, m.font, "start", "font-weight=\"bold\"");
  svg += "<g class=\"spin-cells\" shape-rendering=\"crispEdges\">\n";
  for (const Cell& c : f.cells) {
    const plan::SpinMapPoint& p = map.points[c.index];
    const std::string fill =
        c.kind == SpinCellKind::pocketed ? std::string("url(#pocketed-hatch)") : c.colour;
    char tip[160];
    std::snprintf(tip, sizeof tip, "<title>k_T %.3f, k_S %.3f: %s</title>", p.topspin_k,
                  p.sidespin_k,
                  std::isfinite(p.miss_distance)
                      ? format("%.1f mm from the target", 1000.0 * p.miss_distance).c_str()
                      : phys::to_string(p.outcome));
    svg += "<rect class=\"cell\" x=\"" + num(l.x(p.tip_right) - 0.5 * l.cell) + "\" y=\"" +
           num(l.y(p.tip_up) - 0.5 * l.cell) + "\" width=\"" + num(l.cell) + "\" height=\"" +
           num(l.cell) + "\" fill=\"" + fill + "\">" + tip + "</rect>\n";
  }
  svg += "</g>\n";
  std::string outline;
  for (const Edge& e : landing_outline(f, l))
    outline += "M" + num(e.x1) + " " + num(e.y1) + " L" + num(e.x2) + " " + num(e.y2) + " ";
  if (!outline.empty())
    svg += "<path class=\"landing-outline\" d=\"" + outline + "\" fill=\"none\" stroke=\"" +
           kOutline + "\" stroke-width=\"2.2\" stroke-linecap=\"square\"/>\n";
  svg += svg_circle(l.cx, l.cy, l.radius_px,
                    std::string("class=\"miscue-limit\" fill=\"none\" stroke=\"") + kInk +
                        "\" stroke-width=\"1.5\" stroke-dasharray=\"4 3\"");
  const double arm = std::max(6.0, 0.6 * l.cell);
  svg += svg_line(l.cx - arm, l.cy, l.cx + arm, l.cy,
                  "class=\"centre\" stroke=\"#ffffff\" stroke-width=\"3\"");
  svg += svg_line(l.cx, l.cy - arm, l.cx, l.cy + arm, "stroke=\"#ffffff\" stroke-width=\"3\"");
  svg += svg_line(l.cx - arm, l.cy, l.cx + arm, l.cy,
                  std::string("stroke=\"") + kInk + "\" stroke-width=\"1.2\"");
  svg += svg_line(l.cx, l.cy - arm, l.cx, l.cy + arm,
                  std::string("stroke=\"") + kInk + "\" stroke-width=\"1.2\"");
  if (picture.marked_shot) {
    const double mx = l.x(picture.marked_shot->sidespin_k / kSpinPerTipOffset);
    const double my = l.y(picture.marked_shot->topspin_k / kSpinPerTipOffset);
    const double r = std::max(5.0, 0.45 * l.cell);
    svg += svg_circle(mx, my, r,
                      "class=\"planned-spin\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"4\"");
    svg += svg_circle(mx, my, r,
                      std::string("fill=\"none\" stroke=\"") + kInk + "\" stroke-width=\"2\"");
  }

  // Axes: ticks in d/R below and left of the disc.
  const double radius_d = map.spin_max / kSpinPerTipOffset;
  const double bottom = l.disc_top + kDiscSize;
  const double left = l.disc_left;
  std::string axes = "<g class=\"axes\" stroke=\"#333333\" stroke-width=\"1\">\n";
  axes += svg_line(l.x(-radius_d), bottom + 2.0, l.x(radius_d), bottom + 2.0, "");
  axes += svg_line(left - 2.0, l.y(-radius_d), left - 2.0, l.y(radius_d), "");
  const int ticks = static_cast<int>(std::floor(radius_d / l.tick_step + 1e-9));
  for (int k = -ticks; k <= ticks; ++k) {
    const double v = k * l.tick_step;
    axes += svg_line(l.x(v), bottom + 2.0, l.x(v), bottom + 7.0, "");
    axes += svg_line(left - 7.0, l.y(v), left - 2.0, l.y(v), "");
  }
  axes += "</g>\n<g fill=\"#333333\">\n";
  for (int k = -ticks; k <= ticks; ++k) {
    const double v = k * l.tick_step;
    axes += svg_text(l.x(v), bottom + 8.0 + m.font, tick_text(v), 0.9 * m.font, "middle");
    axes += svg_text(left - 10.0, l.y(v) + 0.32 * m.font, tick_text(v), 0.9 * m.font, "end");
  }
  axes += "</g>\n";
  axes +=
      svg_text(l.cx, l.x_label_y, "tip right of centre, d/R  (left < 0 < right)", m.font, "middle");
  const double ylx = kOuter + 0.9 * m.font;
  axes += svg_text(ylx, l.cy, "tip above centre, d/R  (draw < 0 < follow)", m.font, "middle",
                   "transform=\"rotate(-90 " + num(ylx) + " " + num(l.cy) + ")\"");
  svg += axes;

  // Colour bar of the miss distance, near the target on the left.
  std::string bar = "<g class=\"colour-bar\" shape-rendering=\"crispEdges\">\n";
  constexpr int kBarSteps = 110;
  for (int i = 0; i < kBarSteps; ++i) {
    const double t = (i + 0.5) / kBarSteps;
    bar +=
        svg_rect(l.bar_left + l.bar_width * i / kBarSteps, l.bar_top, l.bar_width / kBarSteps + 0.4,
                 l.bar_height, "fill=\"" + viridis(1.0 - t) + "\"");
  }
  bar += "</g>\n";
  bar += svg_rect(l.bar_left, l.bar_top, l.bar_width, l.bar_height,
                  "fill=\"none\" stroke=\"#333333\" stroke-width=\"0.8\"");
  for (const BarTick& t : bar_ticks(f, l, 0.56 * 0.85 * m.font, "\u2264 ")) {
    bar += svg_line(t.x, l.bar_top + l.bar_height, t.x, l.bar_top + l.bar_height + 4.0,
                    "stroke=\"#333333\" stroke-width=\"1\"");
    if (!t.label.empty())
      bar += svg_text(t.x, l.bar_top + l.bar_height + 4.0 + m.font, t.label, 0.85 * m.font,
                      t.anchor == 0.0   ? "start"
                      : t.anchor == 1.0 ? "end"
                                        : "middle");
  }
  bar += svg_text(l.bar_left, l.bar_label_y,
                  f.bar_label + ", at or beyond " + mm_label(f.scale.far_mm) + " mm: darkest",
                  0.9 * m.font, "start");
  svg += bar;

  // Legend rows.
  std::string legend = "<g class=\"legend\">\n";
  for (size_t i = 0; i < f.legend.size(); ++i) {
    const double y = l.legend_top + (static_cast<double>(i) + 0.5) * l.legend_row;
    legend += svg_swatch(f.legend[i].swatch, l.disc_left, y, 13.0);
    legend += svg_text(l.disc_left + 22.0, y + 0.33 * m.font, f.legend[i].text, 0.92 * m.font);
  }
  legend += "</g>\n";
  svg += legend;

  // The table panel, nested as its own SVG document.
  std::string nested = table.substr(table.find("<svg "));
  nested.replace(
      0, 5,
      "<svg class=\"table-panel\" x=\"" + num(l.table_left) + "\" y=\"" + num(l.table_top) + "\" ");
  svg += nested;
  svg += "</svg>\n";
  return svg;
}

// ---------------------------------------------------------------------------
// PNG: the same layout, rasterised, with text in the raster's pixel font.

namespace {

constexpr int kTextScale = 2;  // pixel font: 12 px per character, 14 px capitals

Metrics png_metrics() {
  Metrics m;
  m.font = 14.0;
  m.char_width = 6.0 * kTextScale;
  m.title_font = 16.0;
  m.title_char = 6.0 * kTextScale;
  m.rotated_text = false;
  return m;
}

// The table panel in the raster: cloth, cushion band, pockets, target zone, obstacles,
// paths, dots and the cue ball, with metre ticks and a short legend.
struct PngTable {
  double band = 0.06 * kPixelsPerMetre;
  double left = 0.0, top = 0.0;      // px of the nose x = 0 / y = width
  double width = 0.0, height = 0.0;  // px of the whole panel
  double title_y = 0.0, legend_y = 0.0;
  double length_m = 0.0, width_m = 0.0;
  double x(double m) const { return left + m * kPixelsPerMetre; }
  double y(double m) const { return top + (width_m - m) * kPixelsPerMetre; }
};

const char* kTableTitle = "Where each spin stops (dots coloured as their cells), m";
PngTable png_table_size(const prob::Problem& problem, const Metrics& m) {
  PngTable t;
  t.length_m = problem.scene.length;
  t.width_m = problem.scene.width;
  t.title_y = m.font;
  const double tick_labels = 4.0 * m.char_width + 10.0;
  t.left = tick_labels + t.band;
  t.top = 2.0 * m.font + t.band;
  const double bottom = t.top + t.width_m * kPixelsPerMetre + t.band;
  t.legend_y = bottom + 10.0 + 2.2 * m.font;
  t.width = std::max(t.left + t.length_m * kPixelsPerMetre + t.band,
                     m.char_width * static_cast<double>(std::string_view(kTableTitle).size()));
  t.height = t.legend_y + 1.6 * m.font + 2.0 * m.font;  // two legend rows
  return t;
}

void png_path(Raster& image, const DrawnPath& path, const PngTable& t, double ox, double oy) {
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    const Rgb colour =
        path.faint
            ? parse_colour("#8c8c8c")
            : parse_colour(s.motion == phys::Motion::sliding ? kSlidingColour : kRollingColour);
    const double width = path.faint ? 1.0 : 2.0;
    const double opacity = path.faint ? 0.6 : 1.0;
    const phys::Vec2 a = s.at(s.t0);
    const phys::Vec2 b = s.at(s.t1);
    const double px_length = kPixelsPerMetre * std::hypot(b.x - a.x, b.y - a.y);
    const int pieces = std::clamp(static_cast<int>(px_length / 6.0), 1, 200);
    phys::Vec2 prev = a;
    for (int i = 1; i <= pieces; ++i) {
      const phys::Vec2 p = s.at(s.t0 + dt * i / pieces);
      image.line(ox + t.x(prev.x), oy + t.y(prev.y), ox + t.x(p.x), oy + t.y(p.y), width, colour,
                 opacity);
      prev = p;
    }
  }
}

void png_table(Raster& image, const Figure& f, const PngTable& t, double ox, double oy,
               const Metrics& m) {
  const SpinMapPicture& picture = *f.picture;
  const prob::Problem& problem = picture.problem;
  const phys::Scene& scene = problem.scene;
  const Rgb ink = parse_colour(kInk);
  const double s = kPixelsPerMetre;
  image.text(ox, oy + t.title_y, kTableTitle, kTextScale, ink);
  // Cushion band, cloth, metre grid.
  image.fill_rect(ox + t.left - t.band, oy + t.top - t.band, t.length_m * s + 2.0 * t.band,
                  t.width_m * s + 2.0 * t.band, parse_colour("#6f9a7c"));
  image.fill_rect(ox + t.left, oy + t.top, t.length_m * s, t.width_m * s, parse_colour("#eaf3ec"));
  const Rgb grid = parse_colour("#d3e3d7");
  for (double v = 0.5; v < t.length_m - 1e-9; v += 0.5)
    image.line(ox + t.x(v), oy + t.top, ox + t.x(v), oy + t.top + t.width_m * s, 1.0, grid);
  for (double v = 0.5; v < t.width_m - 1e-9; v += 0.5)
    image.line(ox + t.left, oy + t.y(v), ox + t.left + t.length_m * s, oy + t.y(v), 1.0, grid);
  for (const phys::Pocket& p : scene.pockets)
    image.fill_circle(ox + t.x(p.centre.x), oy + t.y(p.centre.y), p.radius * s,
                      parse_colour("#262626"));
  // Target zone.
  const Rgb target = parse_colour(kTargetColour);
  image.fill_circle(ox + t.x(problem.target.x), oy + t.y(problem.target.y), problem.tolerance * s,
                    target, 0.25);
  // Obstacles.
  for (const phys::Vec2& o : scene.obstacles) {
    image.fill_circle(ox + t.x(o.x), oy + t.y(o.y), scene.radius() * s, parse_colour("#b5b5b5"));
    image.stroke_circle(ox + t.x(o.x), oy + t.y(o.y), scene.radius() * s, 1.0,
                        parse_colour("#4d4d4d"));
  }
  // Paths, dots, then the cue ball and the zone's edge.
  for (const DrawnPath& p : picture.sample_paths) png_path(image, p, t, ox, oy);
  if (picture.shot_path) png_path(image, *picture.shot_path, t, ox, oy);
  for (size_t i : dot_order(f)) {
    const plan::SpinMapPoint& p = picture.map.points[i];
    const Cell& c = f.cells[i];
    const double x = ox + t.x(p.final_position.x);
    const double y = oy + t.y(p.final_position.y);
    const Rgb fill = parse_colour(c.kind == SpinCellKind::pocketed ? kHatch : c.colour);
    if (p.lands) {
      image.fill_circle(x, y, 4.5, parse_colour(kOutline));
      image.fill_circle(x, y, 3.5, fill);
    } else {
      image.fill_circle(x, y, 2.6, fill);
    }
  }
  const double cue_r = scene.radius() * s;
  image.fill_circle(ox + t.x(problem.cue_ball.x), oy + t.y(problem.cue_ball.y), cue_r,
                    {255, 255, 255});
  image.stroke_circle(ox + t.x(problem.cue_ball.x), oy + t.y(problem.cue_ball.y), cue_r, 1.3, ink);
  image.stroke_circle(ox + t.x(problem.target.x), oy + t.y(problem.target.y), problem.tolerance * s,
                      1.2, target, 1.0, 3.0);
  // Ticks every half metre along the bottom and the left.
  const double bottom = oy + t.top + t.width_m * s + t.band;
  const Rgb grey = parse_colour("#333333");
  for (int k = 0; k * 0.5 <= t.length_m + 1e-9; ++k) {
    const double x = ox + t.x(0.5 * k);
    image.line(x, bottom, x, bottom + 5.0, 1.0, grey);
    image.text(x, bottom + 7.0 + m.font, tick_text(0.5 * k), kTextScale, grey, 0.5);
  }
  for (int k = 0; k * 0.5 <= t.width_m + 1e-9; ++k) {
    const double y = oy + t.y(0.5 * k);
    image.line(ox + t.left - t.band - 5.0, y, ox + t.left - t.band, y, 1.0, grey);
    image.text(ox + t.left - t.band - 8.0, y + 0.5 * Raster::cap_height(kTextScale),
               tick_text(0.5 * k), kTextScale, grey, 1.0);
  }
  // Legend in two rows: the balls and the zone; the paths.
  const double row_gap = 1.6 * m.font;
  double lx = ox + t.left - t.band;
  double ly = oy + t.legend_y;
  image.fill_circle(lx + 7.0, ly - 5.0, 6.0, {255, 255, 255});
  image.stroke_circle(lx + 7.0, ly - 5.0, 6.0, 1.3, ink);
  lx += image.text(lx + 20.0, ly, "cue ball", kTextScale, ink) + 44.0;
  image.fill_circle(lx + 7.0, ly - 5.0, 6.0, target, 0.25);
  image.stroke_circle(lx + 7.0, ly - 5.0, 6.0, 1.2, target, 1.0, 3.0);
  lx +=
      image.text(lx + 20.0, ly, "target zone (r = " + mm_label(1000.0 * problem.tolerance) + " mm)",
                 kTextScale, ink) +
      44.0;
  image.fill_circle(lx + 7.0, ly - 5.0, 6.0, parse_colour("#262626"));
  image.text(lx + 20.0, ly, "pocket", kTextScale, ink);
  lx = ox + t.left - t.band;
  ly += row_gap;
  if (!picture.sample_paths.empty()) {
    image.line(lx, ly - 5.0, lx + 26.0, ly - 5.0, 1.5, parse_colour("#8c8c8c"), 0.8);
    lx += image.text(lx + 32.0, ly, "paths of a few grid spins", kTextScale, ink) + 76.0;
  }
  if (picture.shot_path) {
    image.line(lx, ly - 5.0, lx + 12.0, ly - 5.0, 2.0, parse_colour(kSlidingColour));
    image.line(lx + 14.0, ly - 5.0, lx + 26.0, ly - 5.0, 2.0, parse_colour(kRollingColour));
    image.text(lx + 32.0, ly, "the planner's stroke: sliding, rolling", kTextScale, ink);
  }
}

void png_swatch(Raster& image, Swatch s, double x, double y, double size) {
  const double top = y - 0.5 * size;
  const Rgb ink = parse_colour(kInk);
  switch (s) {
    case Swatch::landing:
      image.fill_rect(x - 1.0, top - 1.0, size + 2.0, size + 2.0, parse_colour(kOutline));
      image.fill_rect(x + 1.0, top + 1.0, size - 2.0, size - 2.0, parse_colour(viridis(1.0)));
      break;
    case Swatch::wrong_cushions:
      image.fill_rect(x, top, size, size, parse_colour(kWrongCushions));
      break;
    case Swatch::pocketed:
      image.fill_rect(x, top, size, size, {255, 255, 255});
      image.hatch_rect(x, top, size, size, 4.0, parse_colour(kHatch));
      break;
    case Swatch::obstacle:
      image.fill_rect(x, top, size, size, parse_colour(kObstacleCell));
      break;
    case Swatch::no_result:
      image.fill_rect(x, top, size, size, parse_colour(kNoResult));
      break;
    case Swatch::marked:
      image.stroke_circle(x + 0.5 * size, y, 0.4 * size, 4.0, {255, 255, 255});
      image.stroke_circle(x + 0.5 * size, y, 0.4 * size, 2.0, ink);
      break;
    case Swatch::miscue:
      image.line(x, y, x + 5.0, y, 1.5, ink);
      image.line(x + 8.0, y, x + size, y, 1.5, ink);
      break;
  }
}

}  // namespace

std::string render_spin_map_png(const SpinMapPicture& picture) {
  Figure f = figure_of(picture);
  // The pixel font has no "\u2264"-style glyphs beyond its set; captions are plain text.
  f.caption = picture.caption;
  const Metrics m = png_metrics();
  const PngTable table = png_table_size(picture.problem, m);
  const Layout l = layout_of(f, m, table.width, table.height);
  const plan::SpinMap& map = picture.map;
  Raster image(static_cast<int>(std::ceil(l.width)), static_cast<int>(std::ceil(l.height)));
  const Rgb ink = parse_colour(kInk);
  const Rgb muted = parse_colour(kMuted);
  const Rgb grey = parse_colour("#333333");

  image.text(kOuter, l.title_y, picture.title, kTextScale, ink);
  image.text(kOuter + 1.0, l.title_y, picture.title, kTextScale, ink);  // bold
  for (size_t i = 0; i < f.caption.size(); ++i)
    image.text(kOuter, l.caption_y + static_cast<double>(i) * l.line, f.caption[i], kTextScale,
               muted);

  // The disc.
  image.text(kOuter, l.disc_title_y, f.disc_title, kTextScale, ink);
  for (const Cell& c : f.cells) {
    const plan::SpinMapPoint& p = map.points[c.index];
    const double x = l.x(p.tip_right) - 0.5 * l.cell;
    const double y = l.y(p.tip_up) - 0.5 * l.cell;
    // Whole pixels, so neighbouring cells meet without seams.
    const double x0 = std::round(x), y0 = std::round(y);
    const double w = std::round(x + l.cell) - x0, h = std::round(y + l.cell) - y0;
    if (c.kind == SpinCellKind::pocketed) {
      image.fill_rect(x0, y0, w, h, {255, 255, 255});
      image.hatch_rect(x0, y0, w, h, 4.0, parse_colour(kHatch));
    } else {
      image.fill_rect(x0, y0, w, h, parse_colour(c.colour));
    }
  }
  for (const Edge& e : landing_outline(f, l))
    image.line(std::round(e.x1), std::round(e.y1), std::round(e.x2), std::round(e.y2), 2.2,
               parse_colour(kOutline));
  image.stroke_circle(l.cx, l.cy, l.radius_px, 1.5, ink, 1.0, 4.0);
  const double arm = std::max(6.0, 0.6 * l.cell);
  image.line(l.cx - arm, l.cy, l.cx + arm, l.cy, 3.0, {255, 255, 255});
  image.line(l.cx, l.cy - arm, l.cx, l.cy + arm, 3.0, {255, 255, 255});
  image.line(l.cx - arm, l.cy, l.cx + arm, l.cy, 1.2, ink);
  image.line(l.cx, l.cy - arm, l.cx, l.cy + arm, 1.2, ink);
  if (picture.marked_shot) {
    const double mx = l.x(picture.marked_shot->sidespin_k / kSpinPerTipOffset);
    const double my = l.y(picture.marked_shot->topspin_k / kSpinPerTipOffset);
    const double r = std::max(5.0, 0.45 * l.cell);
    image.stroke_circle(mx, my, r, 4.0, {255, 255, 255});
    image.stroke_circle(mx, my, r, 2.0, ink);
  }

  // Axes.
  const double radius_d = map.spin_max / kSpinPerTipOffset;
  const double bottom = l.disc_top + kDiscSize;
  const double left = l.disc_left;
  image.line(l.x(-radius_d), bottom + 2.0, l.x(radius_d), bottom + 2.0, 1.0, grey);
  image.line(left - 2.0, l.y(-radius_d), left - 2.0, l.y(radius_d), 1.0, grey);
  const int ticks = static_cast<int>(std::floor(radius_d / l.tick_step + 1e-9));
  for (int k = -ticks; k <= ticks; ++k) {
    const double v = k * l.tick_step;
    image.line(l.x(v), bottom + 2.0, l.x(v), bottom + 7.0, 1.0, grey);
    image.line(left - 7.0, l.y(v), left - 2.0, l.y(v), 1.0, grey);
    image.text(l.x(v), bottom + 8.0 + m.font, tick_text(v), kTextScale, grey, 0.5);
    image.text(left - 10.0, l.y(v) + 0.5 * Raster::cap_height(kTextScale), tick_text(v), kTextScale,
               grey, 1.0);
  }
  image.text(l.cx, l.x_label_y, "tip right of centre, d/R  (left < 0 < right)", kTextScale, ink,
             0.5);
  // The vertical axis label, written above the disc's left edge (no rotated text).
  image.text(kOuter, l.disc_title_y + 1.4 * m.font, "up: tip above centre, d/R (draw < 0 < follow)",
             kTextScale, muted);

  // Colour bar.
  constexpr int kBarSteps = 110;
  for (int i = 0; i < kBarSteps; ++i) {
    const double t = (i + 0.5) / kBarSteps;
    const double x0 = std::round(l.bar_left + l.bar_width * i / kBarSteps);
    const double x1 = std::round(l.bar_left + l.bar_width * (i + 1) / kBarSteps);
    image.fill_rect(x0, l.bar_top, x1 - x0, l.bar_height, parse_colour(viridis(1.0 - t)));
  }
  for (const BarTick& t : bar_ticks(f, l, m.char_width, "<=")) {
    image.line(t.x, l.bar_top + l.bar_height, t.x, l.bar_top + l.bar_height + 4.0, 1.0, grey);
    image.text(t.x, l.bar_top + l.bar_height + 4.0 + m.font, t.label, kTextScale, grey, t.anchor);
  }
  image.text(l.bar_left, l.bar_label_y, f.bar_label, kTextScale, ink);

  // Legend rows.
  for (size_t i = 0; i < f.legend.size(); ++i) {
    const double y = l.legend_top + (static_cast<double>(i) + 0.5) * l.legend_row;
    png_swatch(image, f.legend[i].swatch, l.disc_left, y, 14.0);
    image.text(l.disc_left + 24.0, y + 0.5 * Raster::cap_height(kTextScale), f.legend[i].text,
               kTextScale, ink);
  }

  png_table(image, f, table, l.table_left, l.table_top, m);
  return encode_png(image);
}

}  // namespace cueplan::cli
