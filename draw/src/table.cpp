#include "cueplan/draw/table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

#include "canvas.hpp"
#include "cueplan/draw/spin_map.hpp"
#include "cueplan/problems/ball_names.hpp"
#include "label_placer.hpp"
#include "legend.hpp"
#include "palette.hpp"
#include "table_canvas.hpp"
#include "ticks.hpp"

namespace cueplan::draw {
namespace {

namespace phys = cueplan::physics;
using detail::Anchor;
using detail::Canvas;
using detail::Font;
using detail::Path;
using detail::Pen;
using detail::Point;
using detail::Text;
using detail::Typesetter;
using detail::VAnchor;

// The table picture is drawn in these stages, in this order (each a function below):
//   lay_out      scale, frame, text and canvas size, from the scene alone
//   titles       the title and the wrapped caption
//   table_bed    rail, cushions, cloth and its metre grid
//   markings     snooker's baulk line, D and spots, or the diamonds on the rails
//   pockets      holes and their jaws cut into the cushions
//   field        a quantity over the cloth, shaded, and its zone outlined
//   target_zone  the landing circle
//   paths        faint alternatives, then every ball's paths (offset where they retrace
//                an earlier one) with direction arrows
//   dots         markers the caller adds (a spin map's rest positions)
//   balls        ghosts at cushion contacts and where paths end, then each ball at its start
//   labels       ball names, stroke numbers, cushion numbers, "target": none overlapping
//   axes         metre ticks and labels
//   legend       only what the picture shows

constexpr double kOuter = 16.0;      // blank border (px)
constexpr double kTickLength = 5.0;  // px
constexpr double kMinWidth = 560.0;  // px, so that captions and legend have room

// Snooker's markings on a 3.569 x 1.778 m table (WPBSA): baulk line 737 mm from the
// bottom cushion's nose, D of radius 292 mm, black spot 324 mm from the top cushion.
constexpr double kSnookerLength = 3.569;
constexpr double kSnookerWidth = 1.778;
constexpr double kBaulkLine = 0.737;
constexpr double kDRadius = 0.292;
constexpr double kBlackSpot = 0.324;

constexpr Colour kCloth = Colour::hex("#e4efe6");
constexpr Colour kGrid = Colour::hex("#d0e2d4");
constexpr Colour kCushion = Colour::hex("#5f8f6e");
constexpr Colour kRail = Colour::hex("#7a5230");
constexpr Colour kMarking = Colour::hex("#a3c2ab");
constexpr Colour kDiamond = Colour::hex("#f3ead2");
constexpr Colour kPocket = Colour::hex("#111111");
constexpr Colour kPocketRim = Colour::hex("#4a3626");
constexpr Colour kObstacle = Colour::hex("#b5b5b5");

// Table frame (m) to the page (px): x to the right, y up.
struct Frame {
  double left = 0.0;   // px of the nose x = 0
  double top = 0.0;    // px of the nose y = width
  double scale = 1.0;  // px per m
  double width_m = 0.0;

  double x(double metres) const { return left + metres * scale; }
  double y(double metres) const { return top + (width_m - metres) * scale; }
  Point at(phys::Vec2 p) const { return {x(p.x), y(p.y)}; }
};

// What the picture shows, for its legend.
struct Shown {
  bool sliding = false, rolling = false, own_colour = false, faint = false, contact = false,
       ball_contact = false, rest = false,
       pocketed = false, obstacle_hit = false, strokes = false, grey_obstacles = false;
};

struct Layout {
  double length = 1.0, width = 1.0;  // m, the scene's, made finite
  Frame f;
  double cushion = 0.0, rail = 0.0;  // px
  double ball = 0.0;                 // px, a ball's radius as drawn
  Box cloth, outer;                  // the cloth; the rail's outer edge
  double step = 1.0;                 // m between ticks
  std::vector<double> x_ticks, y_ticks;
  Text title;
  std::vector<Text> caption;
  std::vector<double> caption_tops;
  double title_top = 0.0;
  double x_label_top = 0.0, legend_top = 0.0;
  double y_label_x = 0.0;
  double canvas_width = 0.0, canvas_height = 0.0;
  Shown shown;
  std::optional<detail::Legend> legend;
};

// A ball's drawn paths with the page offset each is drawn at.
struct PlacedPath {
  const DrawnBall* ball = nullptr;
  const DrawnPath* path = nullptr;
  Point offset;
  std::vector<Point> samples;  // px, offset applied
};

double finite_or(double v, double fallback) {
  return std::isfinite(v) && v > 0.0 ? v : fallback;
}

// ---------------------------------------------------------------------------
// Paths sampled on the page, for retrace detection and label avoidance.

std::vector<Point> sample_path(const DrawnPath& path, const Frame& f, double spacing_px) {
  std::vector<Point> points;
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    const phys::Vec2 a = s.at(s.t0);
    const phys::Vec2 b = s.at(s.t1);
    // The chord bounds a parabola's arc length from below; enough to pick the count.
    const double chord = f.scale * std::hypot(b.x - a.x, b.y - a.y);
    const double speed_px = f.scale * std::hypot(s.v0.x, s.v0.y) * dt;
    const int n =
        std::clamp(static_cast<int>(std::max(chord, 0.5 * speed_px) / spacing_px), 1, 400);
    for (int i = 0; i <= n; ++i) points.push_back(f.at(s.at(s.t0 + dt * i / n)));
  }
  return points;
}

// The sample points of the paths placed so far, in square cells of `near` px, to ask
// quickly whether a point lies within `near` of any of them.
class NearPoints {
 public:
  explicit NearPoints(double near) : near_(near) {}
  void add(const std::vector<Point>& points) {
    for (const Point& p : points) cells_[key(cell(p.x), cell(p.y))].push_back(p);
  }
  bool near(Point p) const {
    const int64_t cx = cell(p.x), cy = cell(p.y);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto found = cells_.find(key(cx + dx, cy + dy));
        if (found == cells_.end()) continue;
        for (const Point& q : found->second)
          if (std::hypot(p.x - q.x, p.y - q.y) < near_) return true;
      }
    return false;
  }
  // The fraction of `samples` within `near` of a point already added.
  double fraction_near(const std::vector<Point>& samples) const {
    if (samples.empty() || cells_.empty()) return 0.0;
    const auto close = std::count_if(samples.begin(), samples.end(), [&](Point p) { return near(p); });
    return static_cast<double>(close) / static_cast<double>(samples.size());
  }

 private:
  int64_t cell(double v) const { return static_cast<int64_t>(std::floor(v / near_)); }
  static int64_t key(int64_t x, int64_t y) { return x * 1'000'003 + y; }
  double near_;
  std::unordered_map<int64_t, std::vector<Point>> cells_;
};

// Where each non-faint path is drawn: a path that retraces an earlier one over more
// than a fifth of its length is moved sideways (perpendicular to its first direction)
// by the smallest offset that clears it.
std::vector<PlacedPath> place_paths(const TableScene& scene, const Layout& l, double line_width) {
  std::vector<PlacedPath> placed;
  NearPoints drawn(1.5 * line_width + 1.0);
  for (const DrawnBall& ball : scene.balls) {
    for (const DrawnPath& path : ball.paths) {
      if (path.faint) continue;
      PlacedPath p{&ball, &path, {0.0, 0.0}, sample_path(path, l.f, 3.0)};
      if (drawn.fraction_near(p.samples) > 0.2) {
        // The first direction of travel, on the page.
        Point dir{1.0, 0.0};
        for (const phys::PathSegment& s : path.segments) {
          const double v = std::hypot(s.v0.x, s.v0.y);
          if (v > 0.0) {
            dir = {s.v0.x / v, -s.v0.y / v};
            break;
          }
        }
        const Point normal{-dir.y, dir.x};
        std::vector<Point> best_samples = p.samples;
        Point best_offset{0.0, 0.0};
        double best_fraction = INFINITY;
        for (int k = 1; k <= 4 && best_fraction > 0.05; ++k) {
          for (double side : {1.0, -1.0}) {
            const double d = side * k * 2.5 * line_width;
            std::vector<Point> moved = p.samples;
            for (Point& q : moved) q = {q.x + d * normal.x, q.y + d * normal.y};
            const double fraction = drawn.fraction_near(moved);
            if (fraction < best_fraction) {
              best_fraction = fraction;
              best_offset = {d * normal.x, d * normal.y};
              best_samples = std::move(moved);
            }
          }
        }
        p.offset = best_offset;
        p.samples = std::move(best_samples);
      }
      drawn.add(p.samples);
      placed.push_back(std::move(p));
    }
  }
  return placed;
}

// ---------------------------------------------------------------------------
// The field's shades and the zone's outline (stage field and the legend).
constexpr int kFieldLevels = 20;     // shades of the field (runs of equal shade merge)
constexpr double kFieldAlpha = 0.7;  // over the cloth
// Opaque: the viridis shade laid over the cloth at kFieldAlpha (translucent cells would
// show seams where they meet).
Colour field_colour(int level) {
  const Colour v = viridis(level / double(kFieldLevels));
  const auto mix = [](double a, double b) { return (1.0 - kFieldAlpha) * a + kFieldAlpha * b; };
  return Colour{mix(kCloth.r, v.r), mix(kCloth.g, v.g), mix(kCloth.b, v.b), 1.0};
}
Colour zone_ink() { return Colour::hex("#ffffff"); }

// Symbols shared by the table and its legend.

void draw_ball(Canvas& c, double x, double y, double r, Colour colour, const char* role) {
  c.fill_and_stroke(
      Path().circle(x, y, r), colour,
      Pen{detail::darker(colour, colour.r + colour.g + colour.b > 2.4 ? 0.6 : 0.45), 1.0}, role);
  if (r >= 5.0)  // a highlight, as light falls on a ball
    c.fill(Path().circle(x - 0.35 * r, y - 0.38 * r, 0.28 * r), detail::white().with_alpha(0.55),
           "");
}

// A pool ball as players know it: the number on a white disc at its middle, a stripe
// (9-15) white with a band of its colour across it. Below 5 px of radius the number is
// left out (it could not be read), the band kept.
void draw_pool_ball(Canvas& c, const Typesetter& type, double x, double y, double r,
                    const DrawnBall& ball, const char* role) {
  const Colour white = detail::white();
  const Pen edge{detail::darker(ball.striped ? white : ball.colour,
                                ball.striped || ball.colour.r + ball.colour.g + ball.colour.b > 2.4
                                    ? 0.6
                                    : 0.45),
                 1.0};
  if (ball.striped) {
    c.fill(Path().circle(x, y, r), white, role);
    c.clip(Path().circle(x, y, r));
    const double half = 0.55 * r;  // the band: about half the ball's height
    c.fill(Path().rect(x - r, y - half, 2.0 * r, 2.0 * half), ball.colour, "ball-stripe");
    c.unclip();
    c.stroke(Path().circle(x, y, r), edge, "");
  } else {
    c.fill_and_stroke(Path().circle(x, y, r), ball.colour, edge, role);
  }
  if (r >= 5.0 && ball.number > 0) {
    const double disc = 0.52 * r;
    c.fill(Path().circle(x, y, disc), white, "ball-number-disc");
    const Text t = type.set(std::to_string(ball.number),
                            Font{std::max(0.8 * r * (ball.number >= 10 ? 0.78 : 0.95), 4.0), true});
    c.text(t, x, y, {0.5, VAnchor::middle}, detail::ink(), "ball-number");
  }
  if (r >= 5.0)  // a highlight, as light falls on a ball
    c.fill(Path().circle(x - 0.42 * r, y - 0.45 * r, 0.2 * r), white.with_alpha(0.5), "");
}

void draw_ghost(Canvas& c, double x, double y, double r, Colour colour, const char* role) {
  c.fill_and_stroke(Path().circle(x, y, r), colour.with_alpha(0.35),
                    Pen{detail::darker(colour, colour.r + colour.g + colour.b > 2.4 ? 0.7 : 0.35),
                        1.3,
                        {3.0, 2.0}},
                    role);
}

void draw_cross(Canvas& c, double x, double y, double r, const char* role) {
  const double a = 0.55 * r;
  Pen pen{detail::ink(), 1.6};
  pen.cap = detail::LineCap::round;
  c.stroke(Path()
               .move_to(x - a, y - a)
               .line_to(x + a, y + a)
               .move_to(x - a, y + a)
               .line_to(x + a, y - a),
           pen, role);
}

void draw_contact_ring(Canvas& c, double x, double y, double r, const char* role) {
  c.stroke(Path().circle(x, y, r), Pen{detail::ink().with_alpha(0.75), 1.1, {2.5, 1.5}}, role);
}

void draw_target(Canvas& c, double x, double y, double r, double arm, const char* role) {
  c.fill(Path().circle(x, y, r), detail::target_green().with_alpha(0.18), role);
  const Pen hair{detail::target_green(), 1.0};
  c.stroke(Path()
               .move_to(x - arm, y)
               .line_to(x - 0.4 * r, y)
               .move_to(x + 0.4 * r, y)
               .line_to(x + arm, y)
               .move_to(x, y - arm)
               .line_to(x, y - 0.4 * r)
               .move_to(x, y + 0.4 * r)
               .line_to(x, y + arm),
           hair, "");
}

void draw_target_edge(Canvas& c, double x, double y, double r, const char* role) {
  c.stroke(Path().circle(x, y, r), Pen{detail::target_green(), 1.2, {3.0, 2.0}}, role);
}

void draw_pocket_hole(Canvas& c, double x, double y, double r, const char* role) {
  c.fill_and_stroke(Path().circle(x, y, r), kPocket,
                    Pen{kPocketRim, std::clamp(0.18 * r, 1.2, 3.0)}, role);
}

Pen path_pen(Colour colour, double width) {
  Pen pen{colour, width};
  pen.cap = detail::LineCap::round;
  pen.round_join = true;
  return pen;
}

// ---------------------------------------------------------------------------
// Stage: lay_out

void find_shown(const TableScene& scene, Shown* shown) {
  for (const DrawnBall& ball : scene.balls)
    for (const DrawnPath& path : ball.paths) {
      if (path.faint) {
        shown->faint = shown->faint || !path.segments.empty();
        continue;
      }
      for (const phys::PathSegment& s : path.segments) {
        if (path.colour) {
          shown->own_colour = true;
          continue;
        }
        shown->sliding = shown->sliding || s.motion == phys::Motion::sliding;
        shown->rolling = shown->rolling || s.motion == phys::Motion::rolling;
      }
      for (const phys::ShotEvent& e : path.events) {
        shown->contact = shown->contact || e.type == phys::EventType::cushion;
        shown->ball_contact = shown->ball_contact || e.type == phys::EventType::ball_contact;
        shown->rest = shown->rest || e.type == phys::EventType::rest;
        shown->pocketed = shown->pocketed || e.type == phys::EventType::pocket;
        shown->obstacle_hit = shown->obstacle_hit || e.type == phys::EventType::obstacle;
      }
      shown->strokes = shown->strokes || path.stroke > 0;
    }
}

std::vector<detail::LegendEntry> legend_entries(const TableScene& scene, const Layout& l,
                                                const TableStyle& style, const Typesetter& type) {
  using detail::LegendEntry;
  std::vector<LegendEntry> entries;
  const double lr = std::min(l.ball, 6.5);
  const auto stroke_symbol = [&](Colour colour, double width) {
    return [colour, width](Canvas& c, double x, double y) {
      c.stroke(Path().move_to(x - 13.0, y).line_to(x + 13.0, y), path_pen(colour, width),
               "legend-symbol");
    };
  };
  const Shown& s = l.shown;
  if (s.sliding)
    entries.push_back({stroke_symbol(sliding_colour(), style.line_width + 0.5), "sliding"});
  if (s.rolling)
    entries.push_back({stroke_symbol(rolling_colour(), style.line_width + 0.5), "rolling"});
  if (s.own_colour)
    entries.push_back({[w = style.line_width](Canvas& c, double x, double y) {
                         const Colour grey = Colour::hex("#9a9a9a");
                         Pen dashed = path_pen(grey, w);
                         dashed.dash = {4.0, 3.0};
                         dashed.cap = detail::LineCap::butt;
                         c.stroke(Path().move_to(x - 13.0, y).line_to(x, y), dashed, "legend-symbol");
                         c.stroke(Path().move_to(x, y).line_to(x + 13.0, y), path_pen(grey, w),
                                  "legend-symbol");
                       },
                       "an object ball's path, in its colour (dashed while it slides)"});
  if (s.faint && !scene.faint_legend.empty())
    entries.push_back(
        {stroke_symbol(detail::faint_grey().with_alpha(0.7), 0.5 * style.line_width + 0.5),
         scene.faint_legend});
  if (s.strokes)
    entries.push_back(
        {[one = type.set("1", Font{0.7 * style.font_size, true})](Canvas& c, double x, double y) {
           c.fill(Path().circle(x, y, 6.5), detail::ink(), "legend-symbol");
           c.text(one, x, y, {0.5, VAnchor::middle}, detail::white(), "");
         },
         "stroke number, at the stroke's start"});
  if (s.contact || s.ball_contact)
    entries.push_back(
        {[lr](Canvas& c, double x, double y) { draw_contact_ring(c, x, y, lr, "legend-symbol"); },
         !s.ball_contact ? "ball at a cushion contact (numbered on the cushion)"
         : !s.contact    ? "ball where it strikes another"
                         : "ball at a contact (cushion contacts numbered on the cushion)"});
  if (s.rest)
    entries.push_back({[lr](Canvas& c, double x, double y) {
                         draw_ghost(c, x, y, lr, detail::white(), "legend-symbol");
                       },
                       "where it comes to rest"});
  if (s.pocketed || s.obstacle_hit)
    entries.push_back({[lr](Canvas& c, double x, double y) {
                         draw_ghost(c, x, y, lr, detail::white(), "legend-symbol");
                         draw_cross(c, x, y, lr, "legend-symbol");
                       },
                       s.pocketed && s.obstacle_hit ? "pocketed / stopped against a ball"
                       : s.pocketed                 ? "pocketed"
                                                    : "stopped against a ball"});
  if (!scene.dots.empty() && !scene.dots_legend.empty()) {
    const TableDot dot = scene.dots.back();  // drawn last, on top
    entries.push_back({[dot](Canvas& c, double x, double y) {
                         c.fill(Path().circle(x, y, dot.radius + 0.5), dot.colour, "legend-symbol");
                         if (dot.outline)
                           c.stroke(Path().circle(x, y, dot.radius + 0.5), Pen{*dot.outline, 1.0},
                                    "legend-symbol");
                       },
                       scene.dots_legend});
  }
  if (scene.field && scene.field->shade && !scene.field->shade_legend.empty())
    entries.push_back({[](Canvas& c, double x, double y) {
                         for (int k = 0; k < 5; ++k)
                           c.fill(Path().rect(x - 12.5 + 5.0 * k, y - 5.0, 5.0, 10.0),
                                  field_colour((k + 1) * kFieldLevels / 5), "legend-symbol");
                       },
                       scene.field->shade_legend});
  if (scene.field && scene.field->outline_level && !scene.field->outline_legend.empty())
    entries.push_back({[](Canvas& c, double x, double y) {
                         const Path box = Path().rect(x - 10.0, y - 6.0, 20.0, 12.0);
                         c.stroke(box, Pen{detail::ink(), 3.2}, "legend-symbol");
                         c.stroke(box, Pen{zone_ink(), 1.6}, "legend-symbol");
                       },
                       scene.field->outline_legend});
  if (scene.target)
    entries.push_back({[](Canvas& c, double x, double y) {
                         draw_target(c, x, y, 6.0, 6.0, "legend-symbol");
                         draw_target_edge(c, x, y, 6.0, "legend-symbol");
                       },
                       fmt::format("target zone (r = {:.3g} mm)", 1000.0 * scene.target->radius)});
  if (s.grey_obstacles)
    entries.push_back({[lr](Canvas& c, double x, double y) {
                         draw_ball(c, x, y, lr, kObstacle, "legend-symbol");
                       },
                       "obstacle ball"});
  if (!scene.scene.pockets.empty())
    entries.push_back(
        {[](Canvas& c, double x, double y) { draw_pocket_hole(c, x, y, 6.0, "legend-symbol"); },
         scene.scene.pockets.front().jaws
             ? fmt::format("pocket (jaws to scale; a ball whose centre enters the hole, "
                           "r = {:.3g} mm, drops)",
                           1000.0 * scene.scene.pockets.front().jaws->shape.hole_radius)
             : fmt::format("pocket (a ball whose centre enters r = {:.3g} mm drops)",
                           1000.0 * scene.scene.pockets.front().radius)});
  return entries;
}

bool ball_stands_on(const TableScene& scene, phys::Vec2 p) {
  const double tol = 1e-6 * std::max(1.0, scene.scene.radius());
  return std::any_of(scene.balls.begin(), scene.balls.end(), [&](const DrawnBall& b) {
    return std::abs(b.start.x - p.x) <= tol && std::abs(b.start.y - p.y) <= tol;
  });
}

Layout lay_out(const TableScene& scene, const TableStyle& style, const Typesetter& type) {
  Layout l;
  const double fs = style.font_size;
  l.length = finite_or(scene.scene.length, 1.0);
  l.width = finite_or(scene.scene.width, 1.0);

  // Scale: the preferred one unless the table's long side would leave its range.
  const double long_side = std::max(l.length, l.width);
  double scale = finite_or(style.pixels_per_metre, 300.0);
  if (long_side * scale > style.max_table_side) scale = style.max_table_side / long_side;
  if (long_side * scale < style.min_table_side) scale = style.min_table_side / long_side;
  l.f.scale = scale;
  l.f.width_m = l.width;
  l.cushion = std::clamp(0.04 * scale, 6.0, 16.0);
  l.rail = std::clamp(0.07 * scale, 9.0, 26.0);
  l.ball = std::max(finite_or(scene.scene.radius(), 0.0) * scale, 2.5);

  // Ticks: about eight along the long side.
  l.step = detail::nice_step(long_side / 8.0);
  l.x_ticks = detail::multiples(l.step, 0.0, l.length);
  l.y_ticks = detail::multiples(l.step, 0.0, l.width);
  const Font tick_font{0.9 * fs};
  double widest_y = 0.0;
  for (double v : l.y_ticks)
    widest_y = std::max(widest_y, type.set(detail::tick_label(v, l.step), tick_font).width());
  const double last_x_half =
      l.x_ticks.empty()
          ? 0.0
          : 0.5 * type.set(detail::tick_label(l.x_ticks.back(), l.step), tick_font).width();

  // Across: y axis label, tick labels, ticks, rail, cushion, cloth, cushion, rail.
  const double band = l.cushion + l.rail;
  l.y_label_x = kOuter + 0.6 * fs;
  const double outer_left = kOuter + 1.4 * fs + widest_y + 4.0 + kTickLength;
  l.f.left = outer_left + band;
  const double outer_right = l.f.left + l.length * scale + band;
  const double right_margin = std::max(kOuter, last_x_half + 4.0 - band + kOuter);
  l.canvas_width = std::max(outer_right + right_margin, kMinWidth);
  const double text_width = l.canvas_width - 2.0 * kOuter;

  // Down: title, caption, table, ticks, x label, legend.
  double y = kOuter;
  if (!scene.title.empty()) {
    l.title = type.set(scene.title, Font{1.25 * fs, true}, text_width);
    l.title_top = y;
    y += l.title.height() + 0.3 * fs;
  }
  for (const std::string& line : scene.caption) {
    l.caption.push_back(type.set(line, Font{0.95 * fs}, text_width));
    l.caption_tops.push_back(y);
    y += l.caption.back().height() + 0.15 * fs;
  }
  y += 0.6 * fs;
  l.f.top = y + band;
  l.outer = {outer_left, y, outer_right, y + l.width * scale + 2.0 * band};
  l.cloth = {l.f.left, l.f.top, l.f.left + l.length * scale, l.f.top + l.width * scale};
  y = l.outer.bottom + kTickLength + 2.0 + type.set("0", tick_font).height();
  l.x_label_top = y + 0.2 * fs;
  y = l.x_label_top + type.set("x (m)", Font{fs}).height() + 0.7 * fs;
  l.legend_top = y;

  find_shown(scene, &l.shown);
  for (const phys::Vec2& o : scene.scene.obstacles)
    l.shown.grey_obstacles = l.shown.grey_obstacles || !ball_stands_on(scene, o);
  l.legend.emplace(type, legend_entries(scene, l, style, type), Font{0.95 * fs}, text_width);
  y += l.legend->height();
  l.canvas_height = y + kOuter;
  return l;
}

// ---------------------------------------------------------------------------
// Stage: titles

void titles(Canvas& c, const Layout& l) {
  if (l.title.height() > 0.0)
    c.text(l.title, kOuter, l.title_top, detail::kTopLeft, detail::ink(), "title");
  for (size_t i = 0; i < l.caption.size(); ++i)
    c.text(l.caption[i], kOuter, l.caption_tops[i], detail::kTopLeft, detail::muted(), "caption");
}

// ---------------------------------------------------------------------------
// Stage: table_bed

void table_bed(Canvas& c, const Layout& l) {
  const Box& o = l.outer;
  const double corner = 0.6 * l.rail;
  Path rail;
  rail.move_to(o.left + corner, o.top)
      .line_to(o.right - corner, o.top)
      .arc(o.right - corner, o.top + corner, corner, -0.5 * std::numbers::pi, 0.0)
      .line_to(o.right, o.bottom - corner)
      .arc(o.right - corner, o.bottom - corner, corner, 0.0, 0.5 * std::numbers::pi)
      .line_to(o.left + corner, o.bottom)
      .arc(o.left + corner, o.bottom - corner, corner, 0.5 * std::numbers::pi, std::numbers::pi)
      .line_to(o.left, o.top + corner)
      .arc(o.left + corner, o.top + corner, corner, std::numbers::pi, 1.5 * std::numbers::pi)
      .close();
  c.fill_and_stroke(rail, kRail, Pen{detail::darker(kRail, 0.4), 1.0}, "rail");
  const Box cushion = l.cloth.grown(l.cushion);
  c.fill(Path().rect(cushion.left, cushion.top, cushion.width(), cushion.height()), kCushion,
         "cushion");
  c.fill_and_stroke(Path().rect(l.cloth.left, l.cloth.top, l.cloth.width(), l.cloth.height()),
                    kCloth, Pen{detail::darker(kCushion, 0.3), 1.0}, "cloth");
  Path grid;
  for (double v : l.x_ticks)
    if (v > 0.0 && v < l.length * (1.0 - 1e-9))
      grid.move_to(l.f.x(v), l.cloth.top).line_to(l.f.x(v), l.cloth.bottom);
  for (double v : l.y_ticks)
    if (v > 0.0 && v < l.width * (1.0 - 1e-9))
      grid.move_to(l.cloth.left, l.f.y(v)).line_to(l.cloth.right, l.f.y(v));
  if (!grid.empty()) c.stroke(grid, Pen{kGrid, 1.0}, "grid");
}

// ---------------------------------------------------------------------------
// Stage: markings

void snooker_markings(Canvas& c, const Layout& l) {
  const double sx = l.length / kSnookerLength;
  const double sy = l.width / kSnookerWidth;
  const double baulk = kBaulkLine * sx;
  const double d_radius = kDRadius * sy;
  const double mid = 0.5 * l.width;
  const Pen line{kMarking, 1.2};
  c.stroke(Path().move_to(l.f.x(baulk), l.cloth.top).line_to(l.f.x(baulk), l.cloth.bottom), line,
           "baulk-line");
  // The D: the half circle on the baulk side of the line (page angles, y down).
  c.stroke(Path()
               .move_to(l.f.x(baulk), l.f.y(mid - d_radius))
               .arc(l.f.x(baulk), l.f.y(mid), d_radius * l.f.scale, 0.5 * std::numbers::pi,
                    1.5 * std::numbers::pi),
           line, "d");
  // Yellow on the D's right seen from baulk (low y), green on its left, brown between;
  // blue at the centre, pink halfway to the top cushion, black near it.
  const phys::Vec2 spots[6] = {
      {baulk, mid - d_radius}, {baulk, mid + d_radius}, {baulk, mid},
      {0.5 * l.length, mid},   {0.75 * l.length, mid},  {l.length - kBlackSpot * sx, mid}};
  const double r = std::clamp(0.006 * l.f.scale, 1.4, 3.0);
  for (const phys::Vec2& s : spots)
    c.fill(Path().circle(l.f.x(s.x), l.f.y(s.y), r), detail::darker(kMarking, 0.25), "spot");
}

void diamonds(Canvas& c, const Layout& l, const phys::Scene& scene) {
  const double mid_band = l.cushion + 0.5 * l.rail;  // px outside the nose
  const double half = std::clamp(0.3 * l.rail, 2.5, 5.0);
  const auto near_pocket = [&](phys::Vec2 p) {
    return std::any_of(scene.pockets.begin(), scene.pockets.end(), [&](const phys::Pocket& k) {
      // A jawed corner pocket stands where its cushion lines meet, half a mouth beyond
      // the mouth's centre (a capture circle's place).
      phys::Vec2 at = k.centre;
      if (k.jaws && k.jaws->cushion[0] != k.jaws->cushion[1])
        at = {k.centre.x + 0.5 * k.jaws->shape.mouth * k.jaws->inward.x,
              k.centre.y + 0.5 * k.jaws->shape.mouth * k.jaws->inward.y};
      return std::hypot(at.x - p.x, at.y - p.y) < 0.5 * l.step + k.radius;
    });
  };
  const auto diamond = [&](double x, double y, bool along_x) {
    const double a = along_x ? half : 0.6 * half;
    const double b = along_x ? 0.6 * half : half;
    c.fill(Path().polygon({{x - a, y}, {x, y - b}, {x + a, y}, {x, y + b}}), kDiamond, "diamond");
  };
  for (int k = 1; k < 8; ++k) {
    const double x = k * l.length / 8.0;
    if (!near_pocket({x, 0.0})) diamond(l.f.x(x), l.cloth.bottom + mid_band, true);
    if (!near_pocket({x, l.width})) diamond(l.f.x(x), l.cloth.top - mid_band, true);
  }
  for (int k = 1; k < 4; ++k) {
    const double y = k * l.width / 4.0;
    diamond(l.cloth.left - mid_band, l.f.y(y), false);
    diamond(l.cloth.right + mid_band, l.f.y(y), false);
  }
}

void markings(Canvas& c, const Layout& l, const TableScene& scene) {
  const TableMarkings m =
      scene.markings == TableMarkings::automatic ? markings_for(scene.scene) : scene.markings;
  if (m == TableMarkings::snooker) snooker_markings(c, l);
  if (m == TableMarkings::diamonds) diamonds(c, l, scene.scene);
}

// ---------------------------------------------------------------------------
// Stage: pockets

double pocket_radius_px(const phys::Pocket& p, const Layout& l) {
  return std::max(finite_or(p.radius, 0.0) * l.f.scale, 3.0);
}

// Where a pocket opens: the page direction from the cloth into it (a corner's diagonal,
// a side pocket's normal) and whether it is a corner. A pocket away from every nose
// opens nowhere (zero direction).
struct Mouth {
  Point out;
  bool corner = false;
};

Mouth mouth_of(const phys::Pocket& p, const Layout& l) {
  const double near = std::max(finite_or(p.radius, 0.0), 1e-9 * l.length);
  const double ox = std::abs(p.centre.x) <= near              ? -1.0
                    : std::abs(p.centre.x - l.length) <= near ? 1.0
                                                              : 0.0;
  const double oy = std::abs(p.centre.y) <= near             ? 1.0
                    : std::abs(p.centre.y - l.width) <= near ? -1.0
                                                             : 0.0;
  const double n = std::hypot(ox, oy);
  if (n == 0.0) return {};
  return {{ox / n, oy / n}, ox != 0.0 && oy != 0.0};
}

// A pocket as a player sees it: the cushion's jaws cut back to a mouth, the hole behind
// the nose in the rail, and on the cloth the dashed circle within which a ball's centre
// drops (the capture circle the simulator uses).
//
// A jawed pocket is drawn as the simulator sees it: the cushion cut back along its two
// facings from the rounded points, the hole (hole_radius, shelf beyond the mouth), and
// the points' roundings and facings outlined.
void jawed_pocket(Canvas& c, const Layout& l, const phys::PocketJaws& j) {
  const Box& o = l.outer;
  const Box band = l.cloth.grown(l.cushion);
  const double far = 2.0 * (l.cushion + l.rail) / l.f.scale + j.shape.hole_radius * 4.0;  // m
  const auto add = [](phys::Vec2 a, double s, phys::Vec2 d) {
    return phys::Vec2{a.x + s * d.x, a.y + s * d.y};
  };
  c.clip(Path().rect(band.left, band.top, band.width(), band.height()));
  std::vector<Point> channel;
  for (int side = 0; side < 2; ++side) {
    const int k = side == 0 ? 0 : 1;
    const phys::Vec2 end = add(j.facing_start[k], j.facing_length[k] + far, j.facing_dir[k]);
    if (side == 0) {
      channel.push_back(l.f.at(j.nose_tangent[0]));
      channel.push_back(l.f.at(j.corner[0]));
      channel.push_back(l.f.at(end));
    } else {
      channel.push_back(l.f.at(end));
      channel.push_back(l.f.at(j.corner[1]));
      channel.push_back(l.f.at(j.nose_tangent[1]));
    }
  }
  c.fill(Path().polygon(channel), kCloth, "pocket-jaws");
  c.unclip();
  c.clip(Path().rect(o.left, o.top, o.width(), o.height()));
  const Point hole = l.f.at(j.hole_centre);
  draw_pocket_hole(c, hole.x, hole.y, std::max(j.shape.hole_radius * l.f.scale, 2.0), "pocket");
  const Pen edge{detail::darker(kCushion, 0.45), 1.0};
  for (int k = 0; k < 2; ++k) {
    const Point a = l.f.at(j.facing_start[k]);
    const Point b = l.f.at(add(j.facing_start[k], j.facing_length[k], j.facing_dir[k]));
    c.stroke(Path().move_to(a.x, a.y).line_to(b.x, b.y), edge, "pocket-facing");
    const Point pc = l.f.at(j.point_centre[k]);
    c.stroke(Path().circle(pc.x, pc.y, std::max(j.shape.point_radius * l.f.scale, 0.8)), edge,
             "pocket-point");
  }
  c.unclip();
}

void pockets(Canvas& c, const Layout& l, const phys::Scene& scene) {
  for (const phys::Pocket& p : scene.pockets)
    if (p.jaws) jawed_pocket(c, l, *p.jaws);
  const Box& o = l.outer;
  const Box band = l.cloth.grown(l.cushion);
  c.clip(Path().rect(band.left, band.top, band.width(), band.height()));
  for (const phys::Pocket& p : scene.pockets) {
    if (p.jaws) continue;
    const Mouth m = mouth_of(p, l);
    if (m.out.x == 0.0 && m.out.y == 0.0) continue;
    const Point at = l.f.at(p.centre);
    const double r = pocket_radius_px(p, l);
    const double reach = 2.0 * (l.cushion + l.rail + r);
    std::vector<Point> jaws;
    if (m.corner) {
      // The two noses meet at `at`; the jaws run parallel to the diagonal, a throat
      // narrower than the hole.
      const double a = 1.1 * r;
      const Point along_x{-m.out.x * std::numbers::sqrt2, 0.0};  // from the corner along a nose
      const Point along_y{0.0, -m.out.y * std::numbers::sqrt2};
      const Point px{at.x + a * along_x.x, at.y};
      const Point py{at.x, at.y + a * along_y.y};
      jaws = {px,
              {px.x + reach * m.out.x, px.y + reach * m.out.y},
              {py.x + reach * m.out.x, py.y + reach * m.out.y},
              py,
              at};
    } else {
      // A side pocket: the mouth as wide as the hole at the nose, narrowing behind it.
      const Point along{m.out.y, -m.out.x};
      const double a = r;
      const double b = 0.75 * r;
      jaws = {{at.x - a * along.x, at.y - a * along.y},
              {at.x - b * along.x + reach * m.out.x, at.y - b * along.y + reach * m.out.y},
              {at.x + b * along.x + reach * m.out.x, at.y + b * along.y + reach * m.out.y},
              {at.x + a * along.x, at.y + a * along.y}};
    }
    c.fill(Path().polygon(jaws), kCloth, "pocket-jaws");
  }
  c.unclip();
  // The holes, behind the noses and within the table's outer edge.
  c.clip(Path().rect(o.left, o.top, o.width(), o.height()));
  for (const phys::Pocket& p : scene.pockets) {
    if (p.jaws) continue;
    const Mouth m = mouth_of(p, l);
    const Point at = l.f.at(p.centre);
    const double r = pocket_radius_px(p, l);
    const double back = m.corner ? 0.55 * r : 0.45 * r;
    draw_pocket_hole(c, at.x + back * m.out.x, at.y + back * m.out.y, r, "pocket");
  }
  c.unclip();
  c.clip(Path().rect(l.cloth.left, l.cloth.top, l.cloth.width(), l.cloth.height()));
  for (const phys::Pocket& p : scene.pockets) {
    if (p.jaws) continue;
    const Point at = l.f.at(p.centre);
    c.stroke(Path().circle(at.x, at.y, pocket_radius_px(p, l)),
             Pen{kPocket.with_alpha(0.45), 1.0, {2.0, 2.0}}, "pocket-capture");
  }
  c.unclip();
}

// ---------------------------------------------------------------------------
// Stage: field


void field(Canvas& c, const Layout& l, const TableScene& scene) {
  if (!scene.field) return;
  const TableField& f = *scene.field;
  if (f.columns <= 0 || f.rows <= 0 || f.values.size() != size_t(f.columns) * size_t(f.rows)) return;
  const auto at = [&](int i, int j) { return finite_or(f.values[size_t(j) * size_t(f.columns) + size_t(i)], 0.0); };
  c.clip(Path().rect(l.cloth.left, l.cloth.top, l.cloth.width(), l.cloth.height()));
  if (f.shade) {
    // Each row's runs of one shade as one rectangle; 0 is left as cloth.
    for (int j = 0; j < f.rows; ++j) {
      int i = 0;
      while (i < f.columns) {
        const int level = int(std::lround(std::clamp(at(i, j), 0.0, 1.0) * kFieldLevels));
        int e = i + 1;
        while (e < f.columns && int(std::lround(std::clamp(at(e, j), 0.0, 1.0) * kFieldLevels)) == level) ++e;
        if (level > 0) {
          const double x0 = l.f.x(i * f.cell), x1 = l.f.x(e * f.cell);
          const double y0 = l.f.y((j + 1) * f.cell), y1 = l.f.y(j * f.cell);
          c.fill(Path().rect(x0 - 0.25, y0 - 0.5, x1 - x0 + 0.5, y1 - y0 + 0.5), field_colour(level), "field");
        }
        i = e;
      }
    }
  }
  if (f.outline_level) {
    // The zone's edge: every cell side between a cell in it and one out of it (or the
    // grid's border), drawn dark under white so that it reads on any shade.
    const double level = *f.outline_level;
    const auto in = [&](int i, int j) {
      return i >= 0 && j >= 0 && i < f.columns && j < f.rows && at(i, j) >= level;
    };
    Path edge;
    for (int j = 0; j < f.rows; ++j)
      for (int i = 0; i < f.columns; ++i) {
        if (!in(i, j)) continue;
        const double x0 = l.f.x(i * f.cell), x1 = l.f.x((i + 1) * f.cell);
        const double y0 = l.f.y((j + 1) * f.cell), y1 = l.f.y(j * f.cell);
        if (!in(i - 1, j)) edge.move_to(x0, y0).line_to(x0, y1);
        if (!in(i + 1, j)) edge.move_to(x1, y0).line_to(x1, y1);
        if (!in(i, j - 1)) edge.move_to(x0, y1).line_to(x1, y1);
        if (!in(i, j + 1)) edge.move_to(x0, y0).line_to(x1, y0);
      }
    c.stroke(edge, Pen{detail::ink(), 3.2}, "zone-edge");
    c.stroke(edge, Pen{zone_ink(), 1.6}, "zone-edge");
  }
  c.unclip();
}

// ---------------------------------------------------------------------------
// Stage: target_zone

void target_zone(Canvas& c, const Layout& l, const TableScene& scene) {
  if (!scene.target) return;
  const Point at = l.f.at(scene.target->centre);
  const double r = std::max(finite_or(scene.target->radius, 0.0) * l.f.scale, 2.0);
  draw_target(c, at.x, at.y, r, std::max(r, l.ball) + 7.0, "target-zone");
}

// ---------------------------------------------------------------------------
// Stage: paths

// A path's runs of equal motion, each one Path of Bezier pieces. A quadratic in time is a
// parabola, which a quadratic Bezier draws exactly: the end points p(t0), p(t1) and the
// control point p(t0) + v0 (t1 - t0) / 2.
void draw_path(Canvas& c, const DrawnPath& path, const Frame& f, Point offset,
               const TableStyle& style) {
  Path run;
  phys::Motion motion = phys::Motion::resting;
  Point last{NAN, NAN};
  const auto flush = [&] {
    if (run.empty()) return;
    if (path.faint) {
      c.stroke(run, path_pen(detail::faint_grey().with_alpha(0.6), 0.5 * style.line_width),
               "path-faint");
    } else if (path.colour) {
      const bool sliding = motion == phys::Motion::sliding;
      c.stroke(run, path_pen(detail::ink().with_alpha(0.55), style.line_width + 1.5),
               "path-ball-edge");
      Pen pen = path_pen(*path.colour, style.line_width);
      if (sliding) {
        pen.dash = {3.0 * style.line_width, 2.0 * style.line_width};
        pen.cap = detail::LineCap::butt;
      }
      c.stroke(run, pen, sliding ? "path-ball-sliding" : "path-ball-rolling");
    } else {
      const bool sliding = motion == phys::Motion::sliding;
      c.stroke(run, path_pen(sliding ? sliding_colour() : rolling_colour(), style.line_width),
               sliding ? "path-sliding" : "path-rolling");
    }
    run = Path();
  };
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    if (s.motion != motion) flush();
    motion = s.motion;
    const phys::Vec2 a = s.at(s.t0);
    const phys::Vec2 b = s.at(s.t1);
    const phys::Vec2 control{a.x + 0.5 * dt * s.v0.x, a.y + 0.5 * dt * s.v0.y};
    const Point start{f.x(a.x) + offset.x, f.y(a.y) + offset.y};
    if (run.empty() || std::abs(start.x - last.x) > 0.01 || std::abs(start.y - last.y) > 0.01) {
      if (!run.empty()) flush();
      run.move_to(start.x, start.y);
    }
    last = {f.x(b.x) + offset.x, f.y(b.y) + offset.y};
    run.quad_to(f.x(control.x) + offset.x, f.y(control.y) + offset.y, last.x, last.y);
  }
  flush();
}

// Small arrowheads halfway along every piece long enough to carry one, pointing the way
// the ball moves.
void direction_arrows(Canvas& c, const DrawnPath& path, const Frame& f, Point offset) {
  const auto colour_of = [&](phys::Motion m) {
    if (path.colour) return *path.colour;
    return m == phys::Motion::sliding ? sliding_colour() : rolling_colour();
  };
  constexpr double kMinLength = 90.0;  // px of path a piece needs for an arrow
  constexpr int kSamples = 24;
  constexpr double kHead = 9.0;  // px from tip to base
  for (const phys::PathSegment& s : path.segments) {
    const double dt = s.t1 - s.t0;
    if (!(dt > 0.0)) continue;
    double length[kSamples + 1] = {0.0};
    phys::Vec2 previous = s.at(s.t0);
    for (int i = 1; i <= kSamples; ++i) {
      const phys::Vec2 p = s.at(s.t0 + dt * i / kSamples);
      length[i] = length[i - 1] + f.scale * std::hypot(p.x - previous.x, p.y - previous.y);
      previous = p;
    }
    if (length[kSamples] < kMinLength) continue;
    int i = 1;
    // A path moved beside an earlier one carries its arrows a third of the way along,
    // clear of the earlier path's, which sit halfway.
    const double along = offset.x == 0.0 && offset.y == 0.0 ? 0.5 : 0.3;
    while (i < kSamples && length[i] < along * length[kSamples]) ++i;
    const double t = s.t0 + dt * i / kSamples;
    const phys::Vec2 tip = s.at(t);
    const double vx = s.v0.x + s.accel.x * (t - s.t0);
    const double vy = s.v0.y + s.accel.y * (t - s.t0);
    const double speed = std::hypot(vx, vy);
    if (!(speed > 0.0)) continue;
    const double ux = vx / speed, uy = -vy / speed;  // page axes
    const double x = f.x(tip.x) + offset.x + 0.5 * kHead * ux;
    const double y = f.y(tip.y) + offset.y + 0.5 * kHead * uy;
    const double bx = x - kHead * ux, by = y - kHead * uy;
    const double half = 0.4 * kHead;
    c.fill(Path().polygon(
               {{x, y}, {bx - half * uy, by + half * ux}, {bx + half * uy, by - half * ux}}),
           colour_of(s.motion), "direction");
  }
}

void paths(Canvas& c, const Layout& l, const TableScene& scene,
           const std::vector<PlacedPath>& placed, const TableStyle& style) {
  for (const DrawnBall& ball : scene.balls)
    for (const DrawnPath& path : ball.paths)
      if (path.faint) draw_path(c, path, l.f, {0.0, 0.0}, style);
  for (const PlacedPath& p : placed) draw_path(c, *p.path, l.f, p.offset, style);
  for (const PlacedPath& p : placed) direction_arrows(c, *p.path, l.f, p.offset);
}

// ---------------------------------------------------------------------------
// Stage: dots

void dots(Canvas& c, const Layout& l, const TableScene& scene) {
  for (const TableDot& d : scene.dots) {
    const Point at = l.f.at(d.position);
    if (d.outline)
      c.fill_and_stroke(Path().circle(at.x, at.y, d.radius), d.colour, Pen{*d.outline, 1.0}, "dot");
    else
      c.fill(Path().circle(at.x, at.y, d.radius), d.colour, "dot");
  }
}

// ---------------------------------------------------------------------------
// Stage: balls

void balls(Canvas& c, const Layout& l, const TableScene& scene,
           const std::vector<PlacedPath>& placed, const Typesetter& type) {
  for (const PlacedPath& p : placed)
    for (const phys::ShotEvent& e : p.path->events)
      if (e.type == phys::EventType::cushion || e.type == phys::EventType::ball_contact) {
        const Point at = l.f.at(e.position);
        draw_contact_ring(c, at.x, at.y, l.ball,
                          e.type == phys::EventType::cushion ? "cushion-contact" : "ball-contact");
      }
  // Where each movement ends: a ghost of the ball, crossed when it did not come to rest.
  for (const PlacedPath& p : placed) {
    if (p.path->events.empty()) continue;
    const phys::ShotEvent& end = p.path->events.back();
    if (end.type != phys::EventType::rest && end.type != phys::EventType::pocket &&
        end.type != phys::EventType::obstacle)
      continue;
    const Point at = l.f.at(end.position);
    draw_ghost(c, at.x, at.y, l.ball, p.ball->colour,
               end.type == phys::EventType::rest ? "rest" : "end");
    if (end.type != phys::EventType::rest) draw_cross(c, at.x, at.y, l.ball, "end-cross");
  }
  for (const phys::Vec2& o : scene.scene.obstacles)
    if (!ball_stands_on(scene, o)) {
      const Point at = l.f.at(o);
      draw_ball(c, at.x, at.y, l.ball, kObstacle, "ball");
    }
  for (const DrawnBall& b : scene.balls) {
    const Point at = l.f.at(b.start);
    if (b.number > 0 || b.striped)
      draw_pool_ball(c, type, at.x, at.y, l.ball, b, "ball");
    else
      draw_ball(c, at.x, at.y, l.ball, b.colour, "ball");
  }
}

// ---------------------------------------------------------------------------
// Stage: labels

// The cushion a contact sits on and the page direction out of the cloth there.
Point outward(int cushion) {
  switch (cushion) {
    case 0: return {0.0, 1.0};  // y = 0 is at the bottom of the page
    case 1: return {1.0, 0.0};
    case 2: return {0.0, -1.0};
    default: return {-1.0, 0.0};
  }
}

void labels(Canvas& c, const Layout& l, const TableScene& scene,
            const std::vector<PlacedPath>& placed, const TableStyle& style,
            const Typesetter& type) {
  const double fs = style.font_size;
  detail::LabelPlacer placer(l.outer.grown(-1.0));
  const auto avoid_disc = [&](Point p, double r) {
    placer.avoid({p.x - r, p.y - r, p.x + r, p.y + r});
  };
  for (const DrawnBall& b : scene.balls) avoid_disc(l.f.at(b.start), l.ball + 1.0);
  for (const phys::Vec2& o : scene.scene.obstacles) avoid_disc(l.f.at(o), l.ball + 1.0);
  for (const phys::Pocket& p : scene.scene.pockets)
    avoid_disc(l.f.at(p.centre), pocket_radius_px(p, l));
  for (const PlacedPath& p : placed) {
    if (!p.path->events.empty()) avoid_disc(l.f.at(p.path->events.back().position), l.ball + 1.0);
    for (size_t i = 0; i < p.samples.size(); i += 2)
      avoid_disc(p.samples[i], 0.5 * style.line_width + 1.0);
  }
  if (scene.target)
    avoid_disc(l.f.at(scene.target->centre),
               std::max(scene.target->radius * l.f.scale, l.ball) + 7.0);
  for (const TableDot& d : scene.dots) avoid_disc(l.f.at(d.position), d.radius);

  // Cushion numbers on the cushion band, each where its contact met the cushion (slid
  // along the band when another number sits there).
  const Font number_font{0.8 * fs, true};
  const double band_middle = 0.5 * l.cushion;
  for (const PlacedPath& p : placed) {
    const bool several =
        std::count_if(p.ball->paths.begin(), p.ball->paths.end(),
                      [](const DrawnPath& d) { return !d.faint && d.stroke > 0; }) > 1;
    int contact = 0;
    for (const phys::ShotEvent& e : p.path->events) {
      if (e.type != phys::EventType::cushion) continue;
      ++contact;
      const std::string label =
          several ? fmt::format("{}\u00b7{}", p.path->stroke, contact) : std::to_string(contact);
      const Text t = type.set(label, number_font);
      const Point n = outward(std::clamp(e.cushion, 0, 3));
      const Point at = l.f.at(e.position);
      Point centre{
          n.x != 0.0 ? (n.x > 0 ? l.cloth.right : l.cloth.left) + n.x * band_middle : at.x,
          n.y != 0.0 ? (n.y > 0 ? l.cloth.bottom : l.cloth.top) + n.y * band_middle : at.y};
      // Slide along the cushion until the number is clear of the others.
      const Point along{std::abs(n.y), std::abs(n.x)};
      const double step = (along.x != 0.0 ? t.width() : t.height()) + 2.0;
      Box chosen = detail::text_box(t, centre.x, centre.y, {0.5, VAnchor::middle});
      for (int k = 0; k < 12; ++k) {
        const double shift = (k % 2 == 0 ? 1.0 : -1.0) * ((k + 1) / 2) * step;
        const Box b = detail::text_box(t, centre.x + along.x * shift, centre.y + along.y * shift,
                                       {0.5, VAnchor::middle});
        const bool free = std::none_of(placer.labels().begin(), placer.labels().end(),
                                       [&](const Box& o) { return o.overlaps(b); });
        if (free && b.inside(l.outer)) {
          chosen = b;
          break;
        }
      }
      placer.take(chosen);
      c.text(t, chosen.left, chosen.top, detail::kTopLeft, detail::white(), "cushion-number");
    }
  }

  // Stroke numbers, in a dark disc beside where each stroke starts.
  const Font badge_font{0.85 * fs, true};
  for (const PlacedPath& p : placed) {
    if (p.path->stroke <= 0 || p.samples.empty()) continue;
    const Text t = type.set(std::to_string(p.path->stroke), badge_font);
    const double r = 0.5 * std::max(t.width(), t.height()) + 2.0;
    const Point start = p.samples.front();
    const Box b = placer.place(start.x, start.y, 2.0 * r, 2.0 * r, l.ball + 3.0);
    const double cx = 0.5 * (b.left + b.right), cy = 0.5 * (b.top + b.bottom);
    c.fill(Path().circle(cx, cy, r), detail::ink(), "stroke-badge");
    c.text(t, cx, cy, {0.5, VAnchor::middle}, detail::white(), "stroke-number");
  }

  // Ball names, then the target's.
  const Font name_font{0.85 * fs};
  for (const DrawnBall& b : scene.balls) {
    if (b.name.empty()) continue;
    const Text t = type.set(b.name, name_font);
    const Point at = l.f.at(b.start);
    const Box box = placer.place(at.x, at.y, t.width(), t.height(), l.ball + 3.0);
    c.text(t, box.left, box.top, detail::kTopLeft, detail::ink(), "label");
  }
  if (scene.target) {
    const Text t = type.set("target", name_font);
    const Point at = l.f.at(scene.target->centre);
    const double r = std::max(scene.target->radius * l.f.scale, l.ball) + 7.0;
    const Box box = placer.place(at.x, at.y, t.width(), t.height(), r + 2.0);
    c.text(t, box.left, box.top, detail::kTopLeft, detail::target_green(), "label");
  }
}

// ---------------------------------------------------------------------------
// Stage: axes

void axes(Canvas& c, const Layout& l, const TableStyle& style, const Typesetter& type) {
  const double fs = style.font_size;
  const Pen pen{detail::axis_grey(), 1.0};
  Path ticks;
  for (double v : l.x_ticks)
    ticks.move_to(l.f.x(v), l.outer.bottom).line_to(l.f.x(v), l.outer.bottom + kTickLength);
  for (double v : l.y_ticks)
    ticks.move_to(l.outer.left - kTickLength, l.f.y(v)).line_to(l.outer.left, l.f.y(v));
  c.stroke(ticks, pen, "tick");
  const Font tick_font{0.9 * fs};
  for (double v : l.x_ticks)
    c.text(type.set(detail::tick_label(v, l.step), tick_font), l.f.x(v),
           l.outer.bottom + kTickLength + 2.0, {0.5, VAnchor::top}, detail::axis_grey(),
           "tick-label");
  for (double v : l.y_ticks)
    c.text(type.set(detail::tick_label(v, l.step), tick_font), l.outer.left - kTickLength - 4.0,
           l.f.y(v), {1.0, VAnchor::middle}, detail::axis_grey(), "tick-label");
  c.text(type.set("x (m)", Font{fs}), 0.5 * (l.cloth.left + l.cloth.right), l.x_label_top,
         {0.5, VAnchor::top}, detail::ink(), "axis-label");
  c.text(type.set("y (m)", Font{fs}), l.y_label_x, 0.5 * (l.cloth.top + l.cloth.bottom),
         {0.5, VAnchor::middle}, detail::ink(), "axis-label", 90.0);
}

// ---------------------------------------------------------------------------
// Stage: legend

void legend(Canvas& c, const Layout& l) {
  l.legend->draw(c, kOuter, l.legend_top);
}

}  // namespace

Colour other_ball_colour() { return Colour::hex("#e8d9b0"); }

Colour sliding_colour() {
  return Colour::hex("#D55E00");
}
Colour rolling_colour() {
  return Colour::hex("#0072B2");
}

std::optional<Colour> ball_colour(std::string_view name) {
  struct Named {
    const char* name;
    const char* colour;
  };
  static constexpr Named kColours[] = {
      {"cue ball", "#fbfbf5"}, {"white", "#fbfbf5"}, {"red", "#c8102e"},  {"yellow", "#f4d000"},
      {"green", "#1f7a3a"},    {"brown", "#7b4a21"}, {"blue", "#1f4fbf"}, {"pink", "#f28cb5"},
      {"black", "#151515"},    {"1", "#f4d000"},     {"2", "#1f4fbf"},    {"3", "#c8102e"},
      {"4", "#5b2a86"},        {"5", "#f07c00"},     {"6", "#1f7a3a"},    {"7", "#7b1e1e"},
      {"8", "#151515"},        {"9", "#f4d000"},     {"10", "#1f4fbf"},   {"11", "#c8102e"},
      {"12", "#5b2a86"},       {"13", "#f07c00"},    {"14", "#1f7a3a"},   {"15", "#7b1e1e"}};
  for (const Named& n : kColours)
    if (name == n.name) return Colour::hex(n.colour);
  // A colour numbered to tell balls of one colour apart: "red1", "red_12", "red 3".
  const size_t stem = name.find_last_not_of("0123456789");
  if (stem != std::string_view::npos && stem + 1 < name.size() && !std::isdigit(static_cast<unsigned char>(name[0]))) {
    std::string_view base = name.substr(0, stem + 1);
    if (base.back() == '_' || base.back() == ' ' || base.back() == '-') base.remove_suffix(1);
    for (const Named& n : kColours)
      if (base == n.name && !std::isdigit(static_cast<unsigned char>(n.name[0])))
        return Colour::hex(n.colour);
  }
  return std::nullopt;
}

TableMarkings markings_for(const phys::Scene& scene) {
  const bool snooker_size = std::abs(scene.length - kSnookerLength) < 1e-6 &&
                            std::abs(scene.width - kSnookerWidth) < 1e-6;
  if (snooker_size) return TableMarkings::snooker;
  const double ratio = scene.length / scene.width;
  if (std::abs(ratio - 2.0) < 0.02) return TableMarkings::diamonds;
  return TableMarkings::none;
}

DrawnBall named_ball(const std::string& name, phys::Vec2 start) {
  DrawnBall b{name, ball_colour(name).value_or(other_ball_colour()), start, {}};
  const problems::BallIdentity id = problems::identify_ball(name);
  const bool pool = id.kind == problems::BallKind::pool_solid ||
                    id.kind == problems::BallKind::pool_eight ||
                    id.kind == problems::BallKind::pool_stripe;
  if (pool) {
    b.number = id.number;
    b.striped = id.striped;
    if (const std::optional<Colour> c = ball_colour(std::to_string(id.number))) b.colour = *c;
  }
  return b;
}

TableScene problem_table(const problems::Problem& problem) {
  TableScene t;
  t.scene = problem.scene;
  if (problem.has_target) t.target = TargetZone{problem.target, problem.tolerance};
  t.balls.push_back({"cue ball", *ball_colour("cue ball"), problem.cue_ball, {}});
  for (const phys::ObjectBall& b : problem.scene.balls) t.balls.push_back(named_ball(b.name, b.position));
  for (size_t i = 0; i < problem.scene.obstacles.size(); ++i) {
    if (i < problem.obstacle_names.size()) {
      const std::string& name = problem.obstacle_names[i];
      DrawnBall named = named_ball(name, problem.scene.obstacles[i]);
      if (!ball_colour(name) && named.number == 0) named.colour = *ball_colour("red");
      t.balls.push_back(std::move(named));
      continue;
    }
    t.balls.push_back(
        {fmt::format("obstacle {}", i + 1), *ball_colour("red"), problem.scene.obstacles[i], {}});
  }
  return t;
}

namespace detail {

std::shared_ptr<Canvas> draw_table(const TableScene& scene, const TableStyle& style,
                                   const Typesetter& type) {
  const Layout l = lay_out(scene, style, type);
  auto canvas = std::make_shared<Canvas>(l.canvas_width, l.canvas_height);
  Canvas& c = *canvas;
  c.fill(Path().rect(0.0, 0.0, c.width(), c.height()), white(), "background");
  const std::vector<PlacedPath> placed = place_paths(scene, l, style.line_width);
  titles(c, l);
  table_bed(c, l);
  markings(c, l, scene);
  pockets(c, l, scene.scene);
  field(c, l, scene);
  target_zone(c, l, scene);
  paths(c, l, scene, placed, style);
  dots(c, l, scene);
  balls(c, l, scene, placed, type);
  if (scene.target) {
    const Point at = l.f.at(scene.target->centre);
    draw_target_edge(c, at.x, at.y, std::max(finite_or(scene.target->radius, 0.0) * l.f.scale, 2.0),
                     "target-edge");
  }
  labels(c, l, scene, placed, style, type);
  axes(c, l, style, type);
  legend(c, l);
  return canvas;
}

}  // namespace detail

Picture table_picture(const TableScene& scene, const TableStyle& style) {
  const Typesetter type;
  std::string description;
  for (const std::string& line : scene.caption)
    description += (description.empty() ? "" : "\n") + line;
  return Picture(detail::draw_table(scene, style, type), scene.title, description);
}

}  // namespace cueplan::draw
