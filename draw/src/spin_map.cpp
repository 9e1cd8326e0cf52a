#include "cueplan/draw/spin_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "canvas.hpp"
#include "legend.hpp"
#include "palette.hpp"
#include "table_canvas.hpp"
#include "ticks.hpp"

namespace cueplan::draw {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using detail::Canvas;
using detail::Font;
using detail::Path;
using detail::Pen;
using detail::Point;
using detail::Text;
using detail::Typesetter;
using detail::VAnchor;

// The spin map is drawn in these stages, in this order:
//   lay_out       the table panel first (its size sets the picture's), then the disc
//                 panel's rows: title, note, disc, axes, colour bar, legend
//   titles        title and wrapped caption
//   disc          cells clipped to the spin-limit disc, pocketed ones hatched, the
//                 landing outline, the limit circle, the centre, the planner's spin
//   disc_axes     tick offsets d/R and the axis names
//   colour_bar    the miss-distance scale and its ticks
//   legend        one row per kind of cell shown
//   table_panel   the table with every spin's rest position

constexpr double kSpinPerTipOffset = 2.5;  // k = 2.5 d / R (PHYSICS.md, "Cue strike")
constexpr double kOuter = 16.0;            // blank border (px)
constexpr double kPanelGap = 36.0;         // between the disc panel and the table panel
constexpr double kDiscSize = 440.0;        // px across the cells of the disc
constexpr double kFont = 13.0;
constexpr double kBarHeight = 14.0;

constexpr Colour kWrongCushions = Colour::hex("#c6c6c6");
constexpr Colour kObstacleCell = Colour::hex("#7a7a7a");
constexpr Colour kNoResult = Colour::hex("#f0f0f0");
constexpr Colour kNoPot = Colour::hex("#d6604d");  // outside viridis and the greys
constexpr Colour kHatch = Colour::hex("#3a3a3a");
constexpr Colour kOutline = Colour::hex("#000000");

// Viridis (matplotlib) at eleven evenly spaced points.
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

std::string mm_label(double mm) {
  return fmt::format("{:.4g}", mm);
}

std::string cushions_allowed(const prob::Limits& limits) {
  return limits.cushions_min == limits.cushions_max
             ? std::to_string(limits.cushions_min)
             : fmt::format("{} to {}", limits.cushions_min, limits.cushions_max);
}

int grid_index(double k, const plan::SpinMap& map) {
  const double half = 0.5 * (map.grid - 1);
  return static_cast<int>(std::lround(k / map.spin_max * half + half));
}

// A grid square of the disc: the spin it shows (an index into map.points) and how.
struct Cell {
  int point = -1;    // -1: no grid spin here
  bool rim = false;  // no spin of its own, but inside the disc: shows its nearest spin's
  SpinCellKind kind = SpinCellKind::distance;
  Colour colour;
};

Colour cell_colour(SpinCellKind kind, double miss, const MissColourScale& scale) {
  switch (kind) {
    case SpinCellKind::distance: return scale.colour(miss);
    case SpinCellKind::wrong_cushions: return kWrongCushions;
    case SpinCellKind::pocketed: return detail::white();
    case SpinCellKind::obstacle: return kObstacleCell;
    case SpinCellKind::no_result: return kNoResult;
    case SpinCellKind::no_pot: return kNoPot;
  }
  return kNoResult;
}

enum class Swatch { landing, wrong_cushions, pocketed, obstacle, no_result, no_pot, marked, miscue };

struct Disc {
  double left = 0.0, top = 0.0;  // the square of the cells
  double cx = 0.0, cy = 0.0, scale = 0.0, cell = 0.0, radius_px = 0.0;
  double radius_d = 0.0;    // d/R of the spin limit
  double tick_step = 0.25;  // d/R between ticks

  double x(double right) const { return cx + right * scale; }
  double y(double up) const { return cy - up * scale; }
};

struct Layout {
  MissColourScale scale;
  std::vector<Cell> cells;  // grid x grid, row 0 at the bottom
  int grid = 0;
  Disc disc;
  Text title;
  std::vector<Text> caption;
  std::vector<double> caption_tops;
  double title_top = 0.0;
  Text disc_title, note;
  double disc_title_top = 0.0, note_top = 0.0;
  double x_label_top = 0.0, y_label_x = 0.0;
  double bar_left = 0.0, bar_top = 0.0, bar_width = kDiscSize;
  double bar_label_top = 0.0;
  double legend_top = 0.0;
  std::optional<detail::Legend> legend;
  int success_samples = 0;  // > 0: the cells show the success under noise
  std::shared_ptr<Canvas> table;
  double table_left = 0.0, table_top = 0.0;
  double width = 0.0, height = 0.0;
};

double disc_tick_step(double radius) {
  for (double step : {0.05, 0.1, 0.125, 0.25, 0.5, 1.0})
    if (radius / step <= 3.0 + 1e-9) return step;
  return 1.0;
}

// Each grid square's spin: its own, or for a square inside the disc without one (at the
// rim), the nearest spin's, so that the disc is filled to its edge without gaps.
std::vector<Cell> cells_of(const plan::SpinMap& map, const prob::Problem& problem,
                           const MissColourScale& scale, const Disc& d) {
  const int n = map.grid;
  std::vector<Cell> cells(static_cast<size_t>(n) * static_cast<size_t>(n));
  const auto at = [&](int row, int col) -> Cell& {
    return cells[static_cast<size_t>(row) * static_cast<size_t>(n) + static_cast<size_t>(col)];
  };
  for (size_t i = 0; i < map.points.size(); ++i) {
    const plan::SpinMapPoint& p = map.points[i];
    const int row = grid_index(p.topspin_k, map), col = grid_index(p.sidespin_k, map);
    if (row < 0 || col < 0 || row >= n || col >= n) continue;
    Cell& c = at(row, col);
    c.point = static_cast<int>(i);
    c.kind = classify(p, problem.limits);
    // Asked for how forgiving each spin is: its success under noise, or "no outcome"
    // for a cell that was not estimated.
    c.colour = map.success_samples > 0 ? (p.success ? viridis(*p.success) : kNoResult)
                                       : cell_colour(c.kind, p.miss_distance, scale);
  }
  const double half = 0.5 * (n - 1);
  const double cell_d = 2.0 * d.radius_d / std::max(1, n - 1);
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      Cell& c = at(row, col);
      if (c.point >= 0) continue;
      // The square's nearest point to the disc's centre, in d/R.
      const double ux = (col - half) * cell_d, uy = (row - half) * cell_d;
      const double nx = std::max(0.0, std::abs(ux) - 0.5 * cell_d);
      const double ny = std::max(0.0, std::abs(uy) - 0.5 * cell_d);
      if (std::hypot(nx, ny) >= d.radius_d) continue;
      double best = INFINITY;
      for (int dr = -2; dr <= 2; ++dr)
        for (int dc = -2; dc <= 2; ++dc) {
          const int r2 = row + dr, c2 = col + dc;
          if (r2 < 0 || c2 < 0 || r2 >= n || c2 >= n || at(r2, c2).point < 0 || at(r2, c2).rim)
            continue;
          const double dist = std::hypot(dr, dc);
          if (dist < best) {
            best = dist;
            c.kind = at(r2, c2).kind;
            c.colour = at(r2, c2).colour;
            c.point = at(r2, c2).point;
          }
        }
      c.rim = std::isfinite(best);
      if (!c.rim) c.point = -1;
    }
  return cells;
}

std::vector<detail::LegendEntry> legend_entries(const SpinMapScene& s) {
  const plan::SpinMap& map = s.map;
  const prob::Problem& problem = s.problem;
  int counts[6] = {0, 0, 0, 0, 0, 0};
  for (const plan::SpinMapPoint& p : map.points)
    ++counts[static_cast<int>(classify(p, problem.limits))];
  const auto spins = [](int n) { return fmt::format(" ({} {})", n, n == 1 ? "spin" : "spins"); };
  const auto swatch = [](Swatch w) {
    return [w](Canvas& c, double x, double y) {
      const double size = 13.0;
      const double left = x - 0.5 * size, top = y - 0.5 * size;
      const Path square = Path().rect(left, top, size, size);
      switch (w) {
        case Swatch::landing:
          c.fill_and_stroke(square, viridis(1.0), Pen{kOutline, 2.0}, "legend-symbol");
          break;
        case Swatch::wrong_cushions: c.fill(square, kWrongCushions, "legend-symbol"); break;
        case Swatch::pocketed: {
          c.fill_and_stroke(square, detail::white(), Pen{Colour::hex("#999999"), 0.5},
                            "legend-symbol");
          c.clip(square);
          Path hatch;
          for (double k = -size; k < size; k += 5.0)
            hatch.move_to(left + k, top + size).line_to(left + k + size, top);
          c.stroke(hatch, Pen{kHatch, 1.6}, "");
          c.unclip();
          break;
        }
        case Swatch::obstacle: c.fill(square, kObstacleCell, "legend-symbol"); break;
        case Swatch::no_pot: c.fill(square, kNoPot, "legend-symbol"); break;
        case Swatch::no_result:
          c.fill_and_stroke(square, kNoResult, Pen{Colour::hex("#999999"), 0.5}, "legend-symbol");
          break;
        case Swatch::marked:
          c.stroke(Path().circle(x, y, 0.4 * size), Pen{detail::white(), 4.0}, "");
          c.stroke(Path().circle(x, y, 0.4 * size), Pen{detail::ink(), 2.0}, "legend-symbol");
          break;
        case Swatch::miscue:
          c.stroke(Path().move_to(left, y).line_to(left + size, y),
                   Pen{detail::ink(), 1.5, {4.0, 3.0}}, "legend-symbol");
          break;
      }
    };
  };
  std::vector<detail::LegendEntry> entries;
  entries.push_back(
      {swatch(Swatch::landing), "lands: at rest within " + mm_label(1000.0 * problem.tolerance) +
                                    " mm after " + cushions_allowed(problem.limits) +
                                    (problem.limits.cushions_max == 1 ? " cushion" : " cushions") +
                                    ", outlined" + spins(map.landing)});
  const auto count = [&](SpinCellKind k) { return counts[static_cast<int>(k)]; };
  if (map.success_samples > 0) {
    // The cells' colours are the success under noise: the kinds' swatches would not match.
    const int missing = static_cast<int>(map.points.size()) - map.success_cells;
    if (missing > 0)
      entries.push_back({swatch(Swatch::no_result), "not estimated (stopped by the deadline)" +
                                                        spins(missing)});
  } else {
  if (count(SpinCellKind::wrong_cushions) > 0)
    entries.push_back(
        {swatch(Swatch::wrong_cushions),
         "at rest after a cushion count not allowed (allowed: " + cushions_allowed(problem.limits) +
             ")" + spins(count(SpinCellKind::wrong_cushions))});
  if (count(SpinCellKind::pocketed) > 0)
    entries.push_back(
        {swatch(Swatch::pocketed), "pocketed" + spins(count(SpinCellKind::pocketed))});
  if (count(SpinCellKind::obstacle) > 0)
    entries.push_back({swatch(Swatch::obstacle),
                       "stops against an obstacle ball" + spins(count(SpinCellKind::obstacle))});
  if (count(SpinCellKind::no_result) > 0)
    entries.push_back({swatch(Swatch::no_result), "no outcome (event limit or impact failure)" +
                                                      spins(count(SpinCellKind::no_result))});
  if (count(SpinCellKind::no_pot) > 0 && problem.pot)
    entries.push_back({swatch(Swatch::no_pot), "no aim pots " + problem.pot->ball +
                                                   " with this spin" +
                                                   spins(count(SpinCellKind::no_pot))});
  }
  if (s.marked_shot) entries.push_back({swatch(Swatch::marked), "the planner's spin"});
  entries.push_back(
      {swatch(Swatch::miscue), fmt::format("spin limit: tip offset {:.3g} R (k = {:.3g})",
                                           map.spin_max / kSpinPerTipOffset, map.spin_max)});
  return entries;
}

TableScene table_scene_of(const SpinMapScene& s, const Layout& l) {
  const prob::Problem& problem = s.problem;
  TableScene t = problem_table(problem);
  t.title = "Where each spin stops (dots coloured as their cells)";
  t.caption.push_back(
      fmt::format("Table {:.4g} \u00d7 {:.4g} m between the cushion noses; {} spins",
                  problem.scene.length, problem.scene.width, s.map.points.size()));
  for (const DrawnPath& p : s.sample_paths) t.balls.front().paths.push_back(p);
  if (s.shot_path) t.balls.front().paths.push_back(*s.shot_path);
  t.faint_legend = "paths of a few grid spins";
  // Rest positions, the farthest first so that the landing ones end on top.
  std::vector<size_t> order(s.map.points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const auto key = [&](size_t i) {
      const plan::SpinMapPoint& p = s.map.points[i];
      return p.lands ? -1.0 : std::isfinite(p.miss_distance) ? p.miss_distance : 1e9;
    };
    return key(a) > key(b);
  });
  for (size_t i : order) {
    const plan::SpinMapPoint& p = s.map.points[i];
    const SpinCellKind kind = classify(p, problem.limits);
    TableDot dot;
    dot.position = p.final_position;
    dot.colour = s.map.success_samples > 0
                     ? (p.success ? viridis(*p.success) : kNoResult)
                     : kind == SpinCellKind::pocketed ? kHatch
                                                      : cell_colour(kind, p.miss_distance, l.scale);
    dot.radius = p.lands ? 3.5 : 2.6;
    if (p.lands) dot.outline = kOutline;
    t.dots.push_back(dot);
  }
  t.dots_legend = "where one spin stops (outlined: it lands)";
  return t;
}

// ---------------------------------------------------------------------------
// Stage: lay_out

Layout lay_out(const SpinMapScene& s, const Typesetter& type) {
  Layout l;
  const plan::SpinMap& map = s.map;
  l.scale = miss_colour_scale(map, s.problem);
  l.grid = map.grid;
  l.success_samples = map.success_samples;

  // The table panel, drawn first: its size sets the picture's.
  TableStyle table_style;
  table_style.pixels_per_metre = 260.0;
  table_style.max_table_side = 1000.0;
  l.table = detail::draw_table(table_scene_of(s, l), table_style, type);

  // The disc panel, left to right: the rotated axis name, tick labels, ticks, cells.
  Disc& d = l.disc;
  d.radius_d = map.spin_max / kSpinPerTipOffset;
  d.tick_step = disc_tick_step(d.radius_d);
  const Font tick_font{0.9 * kFont};
  double widest_tick = 0.0;
  for (double v : detail::multiples(d.tick_step, -d.radius_d, d.radius_d))
    widest_tick =
        std::max(widest_tick, type.set(detail::tick_label(v, d.tick_step), tick_font).width());
  l.y_label_x = kOuter + 0.6 * kFont;
  d.left = kOuter + 1.4 * kFont + widest_tick + 4.0 + 7.0;

  detail::Legend legend(type, legend_entries(s), Font{0.92 * kFont}, 640.0, true);
  const Text disc_title =
      type.set("Tip offset on the cue ball (fraction of its radius R)", Font{kFont, true});
  const double panel_right =
      std::max({d.left + kDiscSize, d.left + legend.width(), kOuter + disc_title.width()});
  const double panel_width = panel_right - kOuter;
  l.table_left = panel_right + kPanelGap;
  l.width = l.table_left + l.table->width() + kOuter;

  // Down: title and caption across the whole picture, then the panels side by side.
  double y = kOuter;
  const double text_width = l.width - 2.0 * kOuter;
  l.title = type.set(s.title, Font{16.0, true}, text_width);
  l.title_top = y;
  y += l.title.height() + 0.3 * kFont;
  for (const std::string& line : s.caption) {
    l.caption.push_back(type.set(line, Font{0.95 * kFont}, text_width));
    l.caption_tops.push_back(y);
    y += l.caption.back().height() + 0.15 * kFont;
  }
  y += 0.6 * kFont;
  l.table_top = y;

  l.disc_title = disc_title;
  l.disc_title_top = y;
  y += disc_title.height() + 0.3 * kFont;
  std::vector<DrawnPath> paths = s.sample_paths;
  if (s.shot_path) paths.push_back(*s.shot_path);
  const std::string note = sidespin_note(paths);
  if (!note.empty()) {
    l.note = type.set(note, Font{0.92 * kFont, true}, panel_width);
    l.note_top = y;
    y += l.note.height() + 0.4 * kFont;
  }
  y += 0.3 * kFont;
  d.top = y;
  const double step_d = 2.0 * d.radius_d / std::max(1, map.grid - 1);
  d.scale = kDiscSize / (2.0 * d.radius_d + step_d);
  d.cell = step_d * d.scale;
  d.cx = d.left + 0.5 * kDiscSize;
  d.cy = d.top + 0.5 * kDiscSize;
  d.radius_px = d.radius_d * d.scale;
  y += kDiscSize + 8.0 + type.set("0", tick_font).height();
  l.x_label_top = y + 0.2 * kFont;
  y = l.x_label_top + type.set("d", Font{kFont}).height() + 0.9 * kFont;

  l.bar_left = d.left;
  l.bar_top = y;
  y += kBarHeight + 4.0 + type.set("0", Font{0.85 * kFont}).height();
  l.bar_label_top = y + 0.2 * kFont;
  y = l.bar_label_top + type.set("m", Font{0.9 * kFont}).height() + 0.9 * kFont;
  l.legend_top = y;
  y += legend.height();
  l.legend.emplace(std::move(legend));
  l.cells = cells_of(map, s.problem, l.scale, d);
  l.height = std::max(y, l.table_top + l.table->height()) + kOuter;
  return l;
}

// ---------------------------------------------------------------------------
// Stages: titles, disc, disc_axes, colour_bar, legend, table_panel

void titles(Canvas& c, const Layout& l) {
  c.text(l.title, kOuter, l.title_top, detail::kTopLeft, detail::ink(), "title");
  for (size_t i = 0; i < l.caption.size(); ++i)
    c.text(l.caption[i], kOuter, l.caption_tops[i], detail::kTopLeft, detail::muted(), "caption");
  c.text(l.disc_title, kOuter, l.disc_title_top, detail::kTopLeft, detail::ink(), "panel-title");
  if (l.note.height() > 0.0)
    c.text(l.note, kOuter, l.note_top, detail::kTopLeft, detail::note_amber(), "note");
}

void disc(Canvas& c, const Layout& l, const SpinMapScene& s) {
  const Disc& d = l.disc;
  const int n = l.grid;
  const double half = 0.5 * (n - 1);
  const auto square = [&](int row, int col) {
    const double x = d.cx + (col - half) * d.cell - 0.5 * d.cell;
    const double y = d.cy - (row - half) * d.cell - 0.5 * d.cell;
    return Box{x, y, x + d.cell, y + d.cell};
  };
  const auto cell = [&](int row, int col) -> const Cell& {
    return l.cells[static_cast<size_t>(row) * static_cast<size_t>(n) + static_cast<size_t>(col)];
  };
  const Path limit = Path().circle(d.cx, d.cy, d.radius_px);
  c.clip(limit);
  // Every square a pixel larger than its grid step, drawn in order: each covers the edge
  // of the one before it, so that no background shows between neighbours (no seams).
  constexpr double kOverlap = 1.0;
  Path pocketed;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const Cell& k = cell(row, col);
      if (k.point < 0) continue;
      const Box b = square(row, col);
      c.fill(Path().rect(b.left, b.top - kOverlap, b.width() + kOverlap, b.height() + kOverlap),
             k.colour, k.rim ? "cell-rim" : "cell");
      if (k.kind == SpinCellKind::pocketed && l.success_samples == 0)
        pocketed.rect(b.left, b.top, b.width(), b.height());
    }
  if (!pocketed.empty()) {
    c.clip(pocketed);
    Path hatch;
    const double size = kDiscSize;
    for (double k = -size; k < size; k += 5.0)
      hatch.move_to(d.left + k, d.top + size).line_to(d.left + k + size, d.top);
    c.stroke(hatch, Pen{kHatch, 1.6}, "hatch");
    c.unclip();
  }
  // The landing region's boundary: edges between a landing spin and one that is not.
  const auto lands = [&](int row, int col) {
    if (row < 0 || col < 0 || row >= n || col >= n) return false;
    const Cell& k = cell(row, col);
    return k.point >= 0 && !k.rim && s.map.points[static_cast<size_t>(k.point)].lands;
  };
  Path outline;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      if (!lands(row, col)) continue;
      const Box b = square(row, col);
      if (!lands(row + 1, col)) outline.move_to(b.left, b.top).line_to(b.right, b.top);
      if (!lands(row - 1, col)) outline.move_to(b.left, b.bottom).line_to(b.right, b.bottom);
      if (!lands(row, col - 1)) outline.move_to(b.left, b.top).line_to(b.left, b.bottom);
      if (!lands(row, col + 1)) outline.move_to(b.right, b.top).line_to(b.right, b.bottom);
    }
  if (!outline.empty()) {
    Pen pen{kOutline, 2.2};
    pen.cap = detail::LineCap::square;
    c.stroke(outline, pen, "landing-outline");
  }
  c.unclip();
  c.stroke(limit, Pen{detail::ink(), 1.5, {4.0, 3.0}}, "miscue-limit");
  const double arm = std::max(6.0, 0.6 * d.cell);
  const Path cross = Path()
                         .move_to(d.cx - arm, d.cy)
                         .line_to(d.cx + arm, d.cy)
                         .move_to(d.cx, d.cy - arm)
                         .line_to(d.cx, d.cy + arm);
  c.stroke(cross, Pen{detail::white(), 3.0}, "");
  c.stroke(cross, Pen{detail::ink(), 1.2}, "centre");
  if (s.marked_shot) {
    const double mx = d.x(s.marked_shot->sidespin_k / kSpinPerTipOffset);
    const double my = d.y(s.marked_shot->topspin_k / kSpinPerTipOffset);
    const double r = std::max(5.0, 0.45 * d.cell);
    c.stroke(Path().circle(mx, my, r), Pen{detail::white(), 4.0}, "");
    c.stroke(Path().circle(mx, my, r), Pen{detail::ink(), 2.0}, "planned-spin");
  }
}

void disc_axes(Canvas& c, const Layout& l, const Typesetter& type) {
  const Disc& d = l.disc;
  const double bottom = d.top + kDiscSize;
  const Pen pen{detail::axis_grey(), 1.0};
  const std::vector<double> ticks = detail::multiples(d.tick_step, -d.radius_d, d.radius_d);
  Path lines;
  lines.move_to(d.x(-d.radius_d), bottom + 2.0).line_to(d.x(d.radius_d), bottom + 2.0);
  lines.move_to(d.left - 2.0, d.y(-d.radius_d)).line_to(d.left - 2.0, d.y(d.radius_d));
  for (double v : ticks) {
    lines.move_to(d.x(v), bottom + 2.0).line_to(d.x(v), bottom + 7.0);
    lines.move_to(d.left - 7.0, d.y(v)).line_to(d.left - 2.0, d.y(v));
  }
  c.stroke(lines, pen, "tick");
  const Font tick_font{0.9 * kFont};
  for (double v : ticks) {
    const Text t = type.set(detail::tick_label(v, d.tick_step), tick_font);
    c.text(t, d.x(v), bottom + 8.0, {0.5, VAnchor::top}, detail::axis_grey(), "tick-label");
    c.text(t, d.left - 10.0, d.y(v), {1.0, VAnchor::middle}, detail::axis_grey(), "tick-label");
  }
  c.text(type.set("tip right of centre, d/R  (left < 0 < right)", Font{kFont}), d.cx, l.x_label_top,
         {0.5, VAnchor::top}, detail::ink(), "axis-label");
  c.text(type.set("tip above centre, d/R  (draw < 0 < follow)", Font{kFont}), l.y_label_x, d.cy,
         {0.5, VAnchor::middle}, detail::ink(), "axis-label", 90.0);
}

// The colour bar of the success under noise: 0 % dark to 100 % bright.
void success_bar(Canvas& c, const Layout& l, const Typesetter& type) {
  const Path bar = Path().rect(l.bar_left, l.bar_top, l.bar_width, kBarHeight);
  std::vector<Canvas::Stop> stops;
  for (int i = 0; i <= 10; ++i) stops.push_back({i / 10.0, viridis(i / 10.0)});
  c.fill_gradient(bar, {l.bar_left, 0.0}, {l.bar_left + l.bar_width, 0.0}, std::move(stops),
                  "colour-bar");
  c.stroke(bar, Pen{detail::axis_grey(), 0.8}, "");
  const Font font{0.85 * kFont};
  Path marks;
  for (int percent = 0; percent <= 100; percent += 25) {
    const double x = l.bar_left + l.bar_width * percent / 100.0;
    marks.move_to(x, l.bar_top + kBarHeight).line_to(x, l.bar_top + kBarHeight + 4.0);
    const double anchor = percent == 0 ? 0.0 : percent == 100 ? 1.0 : 0.5;
    Text t = type.set(std::to_string(percent), font);
    const Box box = detail::text_box(t, x, l.bar_top + kBarHeight + 4.0, {anchor, VAnchor::top});
    c.text(t, box.left, box.top, detail::kTopLeft, detail::axis_grey(), "tick-label");
  }
  c.stroke(marks, Pen{detail::axis_grey(), 1.0}, "tick");
  c.text(type.set(fmt::format("success under noise, % ({} noisy strokes a spin)",
                              l.success_samples),
                  Font{0.9 * kFont}),
         l.bar_left, l.bar_label_top, detail::kTopLeft, detail::ink(), "axis-label");
}

void colour_bar(Canvas& c, const Layout& l, const Typesetter& type) {
  if (l.success_samples > 0) return success_bar(c, l, type);
  const Path bar = Path().rect(l.bar_left, l.bar_top, l.bar_width, kBarHeight);
  std::vector<Canvas::Stop> stops;
  for (int i = 0; i <= 10; ++i) stops.push_back({i / 10.0, viridis(1.0 - i / 10.0)});
  c.fill_gradient(bar, {l.bar_left, 0.0}, {l.bar_left + l.bar_width, 0.0}, std::move(stops),
                  "colour-bar");
  c.stroke(bar, Pen{detail::axis_grey(), 0.8}, "");
  // Ticks at 1-2-5 values; a label that would touch its neighbour's is left out (the
  // first, the tolerance, and the last always stay).
  const std::vector<double> values = l.scale.ticks_mm();
  const Font font{0.85 * kFont};
  struct Tick {
    double x;
    Text text;
    Box box;
  };
  std::vector<Tick> ticks;
  for (size_t i = 0; i < values.size(); ++i) {
    const double x = l.bar_left + l.bar_width * l.scale.position(values[i]);
    Text t = type.set((i == 0 ? "\u2264 " : "") + mm_label(values[i]), font);
    const double anchor = i == 0 ? 0.0 : i + 1 == values.size() ? 1.0 : 0.5;
    const Box box = detail::text_box(t, x, l.bar_top + kBarHeight + 4.0, {anchor, VAnchor::top});
    ticks.push_back({x, std::move(t), box});
  }
  Path marks;
  for (const Tick& t : ticks)
    marks.move_to(t.x, l.bar_top + kBarHeight).line_to(t.x, l.bar_top + kBarHeight + 4.0);
  c.stroke(marks, Pen{detail::axis_grey(), 1.0}, "tick");
  double kept_right = -INFINITY;
  for (size_t i = 0; i < ticks.size(); ++i) {
    const bool last = i + 1 == ticks.size();
    const bool clear = ticks[i].box.left > kept_right + 6.0 &&
                       (last || ticks[i].box.right < ticks.back().box.left - 6.0);
    if (i == 0 || last || clear) {
      c.text(ticks[i].text, ticks[i].box.left, ticks[i].box.top, detail::kTopLeft,
             detail::axis_grey(), "tick-label");
      kept_right = ticks[i].box.right;
    }
  }
  c.text(type.set(fmt::format(
                      "miss distance from the target (mm, log scale), at or beyond {} mm: darkest",
                      mm_label(l.scale.far_mm)),
                  Font{0.9 * kFont}),
         l.bar_left, l.bar_label_top, detail::kTopLeft, detail::ink(), "axis-label");
}

}  // namespace

Colour viridis(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 10.0;
  const size_t i = std::min<size_t>(9, static_cast<size_t>(t));
  const double f = t - static_cast<double>(i);
  const auto& a = kViridis[i];
  const auto& b = kViridis[i + 1];
  return {(a[0] + f * (b[0] - a[0])) / 255.0, (a[1] + f * (b[1] - a[1])) / 255.0,
          (a[2] + f * (b[2] - a[2])) / 255.0, 1.0};
}

SpinCellKind classify(const plan::SpinMapPoint& point, const prob::Limits& limits) {
  if (!point.pots) return SpinCellKind::no_pot;
  switch (point.outcome) {
    case phys::ShotStatus::rest:
      return point.cushion_hits >= limits.cushions_min && point.cushion_hits <= limits.cushions_max
                 ? SpinCellKind::distance
                 : SpinCellKind::wrong_cushions;
    case phys::ShotStatus::pocketed: return SpinCellKind::pocketed;
    case phys::ShotStatus::hit_obstacle: return SpinCellKind::obstacle;
    default: return SpinCellKind::no_result;
  }
}

double MissColourScale::position(double miss_mm) const {
  if (!(miss_mm > near_mm)) return 0.0;
  return std::clamp(std::log(miss_mm / near_mm) / std::log(far_mm / near_mm), 0.0, 1.0);
}

Colour MissColourScale::colour(double miss_m) const {
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

std::string sidespin_note(const std::vector<DrawnPath>& paths) {
  int with_side = 0, spent = 0, no_cushion = 0;
  double latest_stop = 0.0;
  for (const DrawnPath& p : paths) {
    if (p.events.empty() || p.events.front().type != phys::EventType::strike) continue;
    if (!(std::abs(p.events.front().spin.z) > 1e-9)) continue;
    ++with_side;
    double first_cushion = INFINITY, stop = INFINITY;
    for (const phys::ShotEvent& e : p.events) {
      if (e.type == phys::EventType::cushion) first_cushion = std::min(first_cushion, e.time);
      if (e.type == phys::EventType::spin_stop) stop = std::min(stop, e.time);
    }
    if (stop < first_cushion) {
      ++spent;
      latest_stop = std::max(latest_stop, stop);
    } else if (!std::isfinite(first_cushion)) {
      ++no_cushion;  // side without a cushion changes nothing either (no swerve on the cloth)
    }
  }
  if (spent == 0 || spent + no_cushion < with_side) return {};
  const std::string which =
      no_cushion == 0 ? fmt::format("all {} sampled strokes with side", with_side)
                      : fmt::format("{} of the {} sampled strokes with side", spent, with_side);
  const std::string others =
      no_cushion == 0 ? "" : fmt::format(" and the other {} meet no cushion", no_cushion);
  return fmt::format(
      "Sidespin is spent before the first cushion in {} (within {:.2g} s of the strike){}: left "
      "and right change nothing here, only the tip's height does.",
      which, latest_stop, others);
}

Picture spin_map_picture(const SpinMapScene& scene) {
  const Typesetter type;
  const Layout l = lay_out(scene, type);
  auto canvas = std::make_shared<Canvas>(l.width, l.height);
  Canvas& c = *canvas;
  c.fill(Path().rect(0.0, 0.0, c.width(), c.height()), detail::white(), "background");
  titles(c, l);
  disc(c, l, scene);
  disc_axes(c, l, type);
  colour_bar(c, l, type);
  l.legend->draw(c, l.disc.left, l.legend_top);
  c.embed(l.table, l.table_left, l.table_top);
  std::string description;
  for (const std::string& line : scene.caption)
    description += (description.empty() ? "" : "\n") + line;
  return Picture(std::move(canvas), scene.title, description);
}

}  // namespace cueplan::draw
