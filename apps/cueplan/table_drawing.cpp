#include "table_drawing.hpp"
#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;

// Average advance of a DejaVu Sans glyph, in font sizes: enough to size boxes.
constexpr double kCharWidth = 0.56;
constexpr double kSubscriptScale = 0.75;
constexpr double kTickLength = 5.0;
constexpr double kOuter = 16.0;  // blank border around everything

constexpr const char* kInk = "#1a1a1a";
constexpr const char* kCloth = "#eaf3ec";
constexpr const char* kGrid = "#d3e3d7";
constexpr const char* kCushion = "#6f9a7c";
constexpr const char* kPocket = "#262626";
constexpr const char* kObstacle = "#b5b5b5";
constexpr const char* kTarget = "#009E73";
constexpr const char* kFaint = "#8c8c8c";
// The ball where it meets a cushion: a dashed "ghost ball".
constexpr const char* kContactBall =
    "fill=\"none\" stroke=\"#1a1a1a\" stroke-width=\"1.1\" "
    "stroke-dasharray=\"2.5 1.5\"";

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}



double text_width(std::string_view label, double font_size) {
  double width = 0.0;
  for (const TextRun& run : text_runs(label)) {
    const auto glyphs =
        std::count_if(run.text.begin(), run.text.end(), [](char c) { return (c & 0xC0) != 0x80; });
    width += static_cast<double>(glyphs) * kCharWidth * font_size *
             (run.subscript ? kSubscriptScale : 1.0);
  }
  return width;
}

// A <text> element; subscripts become lowered, smaller tspans (dy, which every
// renderer follows), and the text after one is raised back.
std::string text_element(double x, double y, std::string_view label, double font_size,
                         std::string_view anchor, std::string_view extra = {}) {
  std::string body;
  const double drop = 0.3 * font_size;
  bool lowered = false;
  for (const TextRun& run : text_runs(label)) {
    if (run.subscript) {
      body += "<tspan dy=\"" + num(lowered ? 0.0 : drop) + "\" font-size=\"" +
              num(font_size * kSubscriptScale) + "\">" + escape_xml(run.text) + "</tspan>";
      lowered = true;
    } else if (lowered) {
      // Renderers drop spaces at a tspan's edge: they become a horizontal offset.
      constexpr double kSpaceWidth = 0.32;  // of the font size, DejaVu Sans
      const size_t lead = std::min(run.text.find_first_not_of(' '), run.text.size());
      const std::string offset =
          lead > 0 ? " dx=\"" + num(static_cast<double>(lead) * kSpaceWidth * font_size) + "\""
                   : std::string();
      body += "<tspan dy=\"" + num(-drop) + "\"" + offset + ">" +
              escape_xml(run.text.substr(lead)) + "</tspan>";
      lowered = false;
    } else {
      body += escape_xml(run.text);
    }
  }
  std::string element = "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" +
                        num(font_size) + "\" text-anchor=\"" + std::string(anchor) + "\"";
  if (!extra.empty()) element += " " + std::string(extra);
  return element + ">" + body + "</text>\n";
}

std::string circle(double cx, double cy, double r, std::string_view attributes) {
  return "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"" + num(r) + "\" " +
         std::string(attributes) + "/>\n";
}

std::string line(double x1, double y1, double x2, double y2, std::string_view attributes = {}) {
  std::string element = "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) +
                        "\" y2=\"" + num(y2) + "\"";
  if (!attributes.empty()) element += " " + std::string(attributes);
  return element + "/>\n";
}

// Spacing of about `count` ticks over `span`: 1, 2, 2.5 or 5 times a power of ten.
double nice_step(double span, double count) {
  const double raw = span / count;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {1.0, 2.0, 2.5, 5.0})
    if (mantissa * decade >= raw * (1.0 - 1e-9)) return mantissa * decade;
  return 10.0 * decade;
}

// Ticks are multiples of 1, 2, 2.5 or 5 times a power of ten of at least 0.01 m here,
// so three decimals without their trailing zeros show them exactly ("1.5", "2").
std::string tick_label(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", value);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

// Table frame (m) to the drawing (px): x to the right, y up.
struct Frame {
  double left = 0.0;   // px of the nose x = 0
  double top = 0.0;    // px of the nose y = width
  double scale = 1.0;  // px per m
  double width = 0.0;  // m, the table's width (y extent)

  double x(double metres) const { return left + metres * scale; }
  double y(double metres) const { return top + (width - metres) * scale; }
};

// One entry of the legend: its symbol (drawn in a 26 x 14 box at its left) and text.
struct LegendEntry {
  std::string symbol;  // SVG elements with coordinates relative to the box's left middle
  std::string text;
};

// Small arrowheads halfway along every piece of path long enough to carry one, in the
// piece's colour, pointing the way the ball moves.
std::string direction_arrows(const DrawnPath& path, const Frame& f) {
  constexpr double kMinLength = 90.0;  // px of path a piece needs for an arrow
  constexpr int kSamples = 24;
  constexpr double kHead = 9.0;  // px from tip to base
  std::string svg;
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    // Arc length (px) at sample points, to find the half-way point.
    double length[kSamples + 1] = {0.0};
    phys::Vec2 previous = s.at(s.t0);
    for (int i = 1; i <= kSamples; ++i) {
      const phys::Vec2 p = s.at(s.t0 + dt * i / kSamples);
      length[i] = length[i - 1] + f.scale * std::hypot(p.x - previous.x, p.y - previous.y);
      previous = p;
    }
    if (length[kSamples] < kMinLength) continue;
    int i = 1;
    while (i < kSamples && length[i] < 0.5 * length[kSamples]) ++i;
    const double t = s.t0 + dt * i / kSamples;
    const phys::Vec2 tip = s.at(t);
    const double vx = s.v0.x + s.accel.x * (t - s.t0);
    const double vy = s.v0.y + s.accel.y * (t - s.t0);
    const double speed = std::hypot(vx, vy);
    if (!(speed > 0.0)) continue;
    // Direction in drawing axes (y down), and its normal.
    const double ux = vx / speed;
    const double uy = -vy / speed;
    const double x = f.x(tip.x) + 0.5 * kHead * ux;
    const double y = f.y(tip.y) + 0.5 * kHead * uy;
    const double bx = x - kHead * ux;
    const double by = y - kHead * uy;
    const double half = 0.4 * kHead;
    const char* colour = s.motion == phys::Motion::sliding ? kSlidingColour : kRollingColour;
    svg += "<path class=\"direction\" d=\"M" + num(x) + " " + num(y) + " L" + num(bx - half * uy) +
           " " + num(by + half * ux) + " L" + num(bx + half * uy) + " " + num(by - half * ux) +
           " Z\" fill=\"" + colour + "\" stroke=\"none\"/>\n";
  }
  return svg;
}

// The path of one ball: runs of equal motion, each one <path> of Bezier pieces. A
// quadratic in time is a parabola, which a quadratic Bezier draws exactly: the end
// points p(t0), p(t1) and the control point p(t0) + v0 (t1 - t0) / 2.
std::string path_elements(const DrawnPath& path, const Frame& f, const TableStyle& style) {
  std::string svg;
  std::string d;
  phys::Motion run = phys::Motion::resting;
  double last_x = NAN;
  double last_y = NAN;
  const auto flush = [&] {
    if (d.empty()) return;
    const bool sliding = run == phys::Motion::sliding;
    const std::string colour = path.faint ? kFaint : (sliding ? kSlidingColour : kRollingColour);
    const double width = path.faint ? 0.5 * style.line_width : style.line_width;
    svg += std::string("<path class=\"") + (sliding ? "sliding" : "rolling") + "\" d=\"" + d +
           "\" stroke=\"" + colour + "\" stroke-width=\"" + num(width) + "\"" +
           (path.faint ? " stroke-opacity=\"0.6\"" : "") + "/>\n";
    d.clear();
  };
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    if (s.motion != run) flush();
    run = s.motion;
    const phys::Vec2 start = s.at(s.t0);
    const phys::Vec2 end = s.at(s.t1);
    const phys::Vec2 control{start.x + 0.5 * dt * s.v0.x, start.y + 0.5 * dt * s.v0.y};
    const double sx = f.x(start.x);
    const double sy = f.y(start.y);
    if (d.empty() || std::abs(sx - last_x) > 0.01 || std::abs(sy - last_y) > 0.01)
      d += (d.empty() ? "M" : " M") + num(sx) + " " + num(sy);
    last_x = f.x(end.x);
    last_y = f.y(end.y);
    d += " Q" + num(f.x(control.x)) + " " + num(f.y(control.y)) + " " + num(last_x) + " " +
         num(last_y);
  }
  flush();
  if (!path.faint) svg += direction_arrows(path, f);
  return svg;
}

// Which kinds of thing the drawing shows, for its legend.
struct Shown {
  bool sliding = false, rolling = false, cushion = false, rest = false, pocketed = false,
       obstacle_contact = false;
};

// Cushion contacts (rings of the ball's radius, numbered in order) and the ball where
// the path ends (dark: at rest, pocketed or against an obstacle).
std::string path_markers(const DrawnPath& path, const phys::Scene& scene, const Frame& f,
                         const TableStyle& style, Shown* shown) {
  std::string svg;
  const double r = scene.radius() * f.scale;
  const double fs = style.font_size;
  int contact = 0;
  for (const phys::ShotEvent& e : path.events) {
    if (e.type != phys::EventType::cushion) continue;
    ++contact;
    shown->cushion = true;
    const double cx = f.x(e.position.x);
    const double cy = f.y(e.position.y);
    svg += circle(cx, cy, r, std::string("class=\"cushion-contact\" ") + kContactBall);
    // The number sits on the cushion band where the ball met it, outside the cloth.
    static constexpr double kOutwardX[4] = {0.0, 1.0, 0.0, -1.0};
    static constexpr double kOutwardY[4] = {1.0, 0.0, -1.0, 0.0};  // drawing y points down
    const int k = std::clamp(e.cushion, 0, 3);
    const double nose_x = k == 1 ? f.x(scene.length) : k == 3 ? f.x(0.0) : cx;
    const double nose_y = k == 0 ? f.y(0.0) : k == 2 ? f.y(scene.width) : cy;
    const double half_band = 0.5 * style.cushion_band * f.scale;
    svg += text_element(nose_x + kOutwardX[k] * half_band,
                        nose_y + kOutwardY[k] * half_band + 0.33 * 0.85 * fs,
                        std::to_string(contact), 0.85 * fs, "middle",
                        "class=\"cushion-number\" font-weight=\"bold\" fill=\"#ffffff\"");
  }
  if (!path.events.empty()) {
    const phys::ShotEvent& end = path.events.back();
    const bool at_rest = end.type == phys::EventType::rest;
    const bool in_pocket = end.type == phys::EventType::pocket;
    const bool on_obstacle = end.type == phys::EventType::obstacle;
    if (at_rest || in_pocket || on_obstacle) {
      const double cx = f.x(end.position.x);
      const double cy = f.y(end.position.y);
      svg += circle(cx, cy, r,
                    std::string("class=\"final-position\" fill=\"") + kInk +
                        "\" stroke=\"#ffffff\" stroke-width=\"0.8\"");
      if (in_pocket || on_obstacle) {
        const double a = 0.55 * r;  // a white cross: the shot ended without a rest
        svg += line(cx - a, cy - a, cx + a, cy + a, "stroke=\"#ffffff\" stroke-width=\"1.5\"");
        svg += line(cx - a, cy + a, cx + a, cy - a, "stroke=\"#ffffff\" stroke-width=\"1.5\"");
      }
      shown->rest = shown->rest || at_rest;
      shown->pocketed = shown->pocketed || in_pocket;
      shown->obstacle_contact = shown->obstacle_contact || on_obstacle;
    }
  }
  return svg;
}

}  // namespace

std::string render_table_svg(const TableDrawing& drawing, const TableStyle& style) {
  const phys::Scene& scene = drawing.scene;
  const double fs = style.font_size;
  const double s = style.pixels_per_metre;
  const double band = style.cushion_band * s;
  const double table_w = scene.length * s;
  const double table_h = scene.width * s;
  const double r = scene.radius() * s;

  // Ticks: the same metre spacing along both sides.
  const double step = nice_step(std::max(scene.length, scene.width), 8.0);
  std::vector<double> x_ticks;
  std::vector<double> y_ticks;
  for (int k = 0; k * step <= scene.length * (1.0 + 1e-9); ++k) x_ticks.push_back(k * step);
  for (int k = 0; k * step <= scene.width * (1.0 + 1e-9); ++k) y_ticks.push_back(k * step);
  double widest_y_label = 0.0;
  for (double v : y_ticks)
    widest_y_label = std::max(widest_y_label, text_width(tick_label(v), 0.9 * fs));

  // Vertical layout: title, caption, table with its ticks, legend.
  double y = kOuter;
  const double title_y = y + 1.1 * fs;
  if (!drawing.title.empty()) y += 1.6 * fs;
  const double caption_y = y + 1.0 * fs;
  y += static_cast<double>(drawing.caption.size()) * 1.4 * fs;
  y += 0.8 * fs;
  Frame f;
  f.scale = s;
  f.width = scene.width;
  f.left = kOuter + 1.3 * fs + widest_y_label + kTickLength + 6.0 + band;
  f.top = y + band;
  const double table_bottom = f.top + table_h + band;  // outer edge of the cushion band
  const double x_label_y = table_bottom + kTickLength + 2.6 * fs;
  const double legend_top = x_label_y + 1.0 * fs;
  const double table_right = f.left + table_w + band;

  // Everything drawn on the table, in layers.
  std::string body;

  // Cloth between the noses, with a light metre grid; the cushion band around it.
  body += "<rect class=\"cushion-band\" x=\"" + num(f.left - band) + "\" y=\"" + num(f.top - band) +
          "\" width=\"" + num(table_w + 2.0 * band) + "\" height=\"" + num(table_h + 2.0 * band) +
          "\" rx=\"" + num(0.3 * band) + "\" fill=\"" + kCushion +
          "\" stroke=\"#333333\" stroke-width=\"1\"/>\n";
  body += "<rect class=\"cloth\" x=\"" + num(f.left) + "\" y=\"" + num(f.top) + "\" width=\"" +
          num(table_w) + "\" height=\"" + num(table_h) + "\" fill=\"" + kCloth +
          "\" stroke=\"#2f4f3a\" stroke-width=\"1\"/>\n";
  body += std::string("<g class=\"grid\" stroke=\"") + kGrid + "\" stroke-width=\"1\">\n";
  for (double v : x_ticks)
    if (v > 0.0 && v < scene.length * (1.0 - 1e-9))
      body += line(f.x(v), f.top, f.x(v), f.top + table_h);
  for (double v : y_ticks)
    if (v > 0.0 && v < scene.width * (1.0 - 1e-9))
      body += line(f.left, f.y(v), f.left + table_w, f.y(v));
  body += "</g>\n";

  // Pockets: their capture circles, which reach over the cushion band.
  for (size_t i = 0; i < scene.pockets.size(); ++i) {
    const phys::Pocket& p = scene.pockets[i];
    body += circle(f.x(p.centre.x), f.y(p.centre.y), p.radius * s,
                   "class=\"pocket\" fill=\"" + std::string(kPocket) + "\"");
  }

  // Target zone: a circle of the tolerance, with a cross hair that stays visible when
  // the zone is smaller than a ball.
  if (drawing.target) {
    const double tx = f.x(drawing.target->centre.x);
    const double ty = f.y(drawing.target->centre.y);
    const double tr = drawing.target->radius * s;
    body +=
        circle(tx, ty, tr,
               "class=\"target-zone\" fill=\"" + std::string(kTarget) + "\" fill-opacity=\"0.18\"");
    const double arm = std::max(tr, r) + 7.0;
    const std::string hair =
        "class=\"target\" stroke=\"" + std::string(kTarget) + "\" stroke-width=\"1\"";
    body += line(tx - arm, ty, tx - 0.4 * tr, ty, hair);
    body += line(tx + 0.4 * tr, ty, tx + arm, ty, hair);
    body += line(tx, ty - arm, tx, ty - 0.4 * tr, hair);
    body += line(tx, ty + 0.4 * tr, tx, ty + arm, hair);
    body += text_element(tx + arm + 3.0, ty - 4.0, "target", 0.85 * fs, "start",
                         "fill=\"" + std::string(kTarget) + "\"");
  }

  // Obstacle balls, to scale.
  for (const phys::Vec2& o : scene.obstacles)
    body += circle(f.x(o.x), f.y(o.y), r,
                   "class=\"obstacle\" fill=\"" + std::string(kObstacle) +
                       "\" stroke=\"#4d4d4d\" stroke-width=\"1\"");

  // Paths, faint ones first, then their markers over every path.
  Shown shown;
  body +=
      "<g class=\"ball-paths\" fill=\"none\" stroke-linecap=\"round\" "
      "stroke-linejoin=\"round\">\n";
  for (bool faint : {true, false})
    for (const DrawnPath& path : drawing.paths)
      if (path.faint == faint) body += path_elements(path, f, style);
  body += "</g>\n";
  for (const DrawnPath& path : drawing.paths) {
    if (path.faint) continue;
    for (const phys::PathSegment& seg : path.segments) {
      shown.sliding = shown.sliding || seg.motion == phys::Motion::sliding;
      shown.rolling = shown.rolling || seg.motion == phys::Motion::rolling;
    }
  }

  // Dots, e.g. rest positions of many shots, over the paths.
  if (!drawing.dots.empty()) {
    body += "<g class=\"dots\">\n";
    for (const TableDot& dot : drawing.dots) {
      std::string attributes = "class=\"dot\" fill=\"" + dot.colour + "\"";
      if (!dot.outline.empty()) attributes += " stroke=\"" + dot.outline + "\" stroke-width=\"1\"";
      body += circle(f.x(dot.position.x), f.y(dot.position.y), dot.radius, attributes);
    }
    body += "</g>\n";
  }

  // The cue ball where it starts, under the markers of where the path goes.
  if (drawing.cue_ball)
    body += circle(f.x(drawing.cue_ball->x), f.y(drawing.cue_ball->y), r,
                   std::string("class=\"cue-ball\" fill=\"#ffffff\" stroke=\"") + kInk +
                       "\" stroke-width=\"1.3\"");
  for (const DrawnPath& path : drawing.paths)
    if (!path.faint) body += path_markers(path, scene, f, style, &shown);
  // The zone's edge over everything, so that a ball resting on it still shows it.
  if (drawing.target)
    body += circle(f.x(drawing.target->centre.x), f.y(drawing.target->centre.y),
                   drawing.target->radius * s,
                   "class=\"target-zone-edge\" fill=\"none\" stroke=\"" + std::string(kTarget) +
                       "\" stroke-width=\"1.2\" stroke-dasharray=\"3 2\"");

  // Metre ticks along the bottom and the left, outside the cushion band.
  std::string axes = "<g class=\"axes\" stroke=\"#333333\" stroke-width=\"1\">\n";
  for (double v : x_ticks) axes += line(f.x(v), table_bottom, f.x(v), table_bottom + kTickLength);
  for (double v : y_ticks) axes += line(f.left - band - kTickLength, f.y(v), f.left - band, f.y(v));
  axes += "</g>\n<g fill=\"#333333\">\n";
  for (double v : x_ticks)
    axes += text_element(f.x(v), table_bottom + kTickLength + 1.05 * fs, tick_label(v), 0.9 * fs,
                         "middle");
  for (double v : y_ticks)
    axes += text_element(f.left - band - kTickLength - 4.0, f.y(v) + 0.32 * fs, tick_label(v),
                         0.9 * fs, "end");
  axes += "</g>\n";
  axes += text_element(f.left + table_w / 2.0, x_label_y, "x (m)", fs, "middle");
  const double y_label_x = kOuter + 0.9 * fs;
  const double y_label_y = f.top + table_h / 2.0;
  axes += text_element(y_label_x, y_label_y, "y (m)", fs, "middle",
                       "transform=\"rotate(-90 " + num(y_label_x) + " " + num(y_label_y) + ")\"");

  // Legend: only what the drawing shows, in rows no wider than the table.
  std::vector<LegendEntry> entries;
  const auto stroke_symbol = [&](const char* colour) {
    return line(0.0, 0.0, 26.0, 0.0,
                std::string("stroke=\"") + colour + "\" stroke-width=\"" +
                    num(style.line_width + 0.5) + "\" stroke-linecap=\"round\"");
  };
  const double lr = std::min(r, 6.5);  // ball symbols in the legend
  const std::string ink = kInk;
  if (shown.sliding) entries.push_back({stroke_symbol(kSlidingColour), "sliding"});
  if (shown.rolling) entries.push_back({stroke_symbol(kRollingColour), "rolling"});
  const bool any_faint = std::any_of(drawing.paths.begin(), drawing.paths.end(),
                                     [](const DrawnPath& p) { return p.faint; });
  if (any_faint && !drawing.faint_legend.empty())
    entries.push_back({line(0.0, 0.0, 26.0, 0.0,
                            std::string("stroke=\"") + kFaint + "\" stroke-width=\"" +
                                num(0.5 * style.line_width + 0.5) +
                                "\" stroke-opacity=\"0.6\" stroke-linecap=\"round\""),
                       drawing.faint_legend});
  if (drawing.cue_ball)
    entries.push_back(
        {circle(13.0, 0.0, lr, "fill=\"#ffffff\" stroke=\"" + ink + "\" stroke-width=\"1.3\""),
         "cue ball"});
  if (shown.cushion)
    entries.push_back({circle(13.0, 0.0, lr, kContactBall),
                       "ball at a cushion contact (numbered on the cushion)"});
  if (shown.rest) entries.push_back({circle(13.0, 0.0, lr, "fill=\"" + ink + "\""), "at rest"});
  if (shown.pocketed || shown.obstacle_contact) {
    const double a = 0.55 * lr;
    entries.push_back(
        {circle(13.0, 0.0, lr, "fill=\"" + ink + "\"") +
             line(13.0 - a, -a, 13.0 + a, a, "stroke=\"#ffffff\" stroke-width=\"1.5\"") +
             line(13.0 - a, a, 13.0 + a, -a, "stroke=\"#ffffff\" stroke-width=\"1.5\""),
         shown.pocketed && shown.obstacle_contact ? "pocketed / obstacle hit"
         : shown.pocketed                         ? "pocketed"
                                                  : "obstacle hit"});
  }
  if (drawing.target) {
    char text[96];
    std::snprintf(text, sizeof text, "target zone (r = %.3g mm)", 1000.0 * drawing.target->radius);
    entries.push_back(
        {circle(13.0, 0.0, 6.0,
                "fill=\"" + std::string(kTarget) + "\" fill-opacity=\"0.18\" stroke=\"" + kTarget +
                    "\" stroke-width=\"1.2\" stroke-dasharray=\"3 2\""),
         text});
  }
  if (!scene.obstacles.empty())
    entries.push_back(
        {circle(13.0, 0.0, lr,
                "fill=\"" + std::string(kObstacle) + "\" stroke=\"#4d4d4d\" stroke-width=\"1\""),
         "obstacle ball"});
  if (!scene.pockets.empty()) {
    char text[96];
    std::snprintf(text, sizeof text, "pocket (capture r = %.3g mm)",
                  1000.0 * scene.pockets.front().radius);
    entries.push_back({circle(13.0, 0.0, 6.5, "fill=\"" + std::string(kPocket) + "\""), text});
  }

  const double legend_left = f.left - band;
  const double legend_right = std::max(table_right, legend_left + 420.0);
  const double row_height = 1.6 * fs;
  std::string legend = "<g class=\"legend\">\n";
  double lx = legend_left;
  double ly = legend_top + 0.8 * fs;
  int rows = entries.empty() ? 0 : 1;
  for (const LegendEntry& e : entries) {
    const double w = 26.0 + 6.0 + text_width(e.text, 0.95 * fs) + 20.0;
    if (lx > legend_left && lx + w > legend_right) {
      lx = legend_left;
      ly += row_height;
      ++rows;
    }
    legend += "<g transform=\"translate(" + num(lx) + " " + num(ly) + ")\">" + e.symbol + "</g>\n";
    legend += text_element(lx + 32.0, ly + 0.33 * 0.95 * fs, e.text, 0.95 * fs, "start");
    lx += w;
  }
  legend += "</g>\n";

  // The document: width for the table or the longest text line, whichever is wider.
  double width = table_right + kOuter;
  width = std::max(width, kOuter * 2.0 + text_width(drawing.title, 1.25 * fs));
  for (const std::string& c : drawing.caption)
    width = std::max(width, kOuter * 2.0 + text_width(c, 0.95 * fs));
  const double height = legend_top + static_cast<double>(rows) * row_height + kOuter;

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" +
         num(height) + "\" viewBox=\"0 0 " + num(width) + " " + num(height) + "\" font-family=\"" +
         escape_xml(style.font_family) + "\" fill=\"" + kInk + "\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  if (!drawing.title.empty())
    svg += text_element(kOuter, title_y, drawing.title, 1.25 * fs, "start", "font-weight=\"bold\"");
  for (size_t i = 0; i < drawing.caption.size(); ++i)
    svg += text_element(kOuter, caption_y + static_cast<double>(i) * 1.4 * fs, drawing.caption[i],
                        0.95 * fs, "start", "fill=\"#444444\"");
  svg += body + axes + legend + "</svg>\n";
  return svg;
}

}  // namespace cueplan::cli
