// A table seen from above, to scale, as players know it: the cloth between the cushion
// noses, cushions and rails, pockets as holes with their jaws, the snooker markings (baulk
// line, D and the six spots) or a pool or carom table's diamonds, the target zone, and
// any number of balls - each with a name, a colour and its own path - with sliding and
// rolling in two colours, cushion contacts numbered, strokes numbered, and labels placed
// so that none covers another. Metre ticks run along two sides, the origin at the corner
// where the noses x = 0 and y = 0 meet (shared/PHYSICS.md).
//
// The canvas is bounded whatever the scene's size (kMaxCanvasSide): the scale follows the
// table, the tick spacing the scale.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/draw/picture.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::draw {

// Where a ball should stop: a circle of radius `radius` (m) around `centre`.
struct TargetZone {
  physics::Vec2 centre;
  double radius = 0.0;  // m
};

// One movement of a ball, as physics::simulate records it.
struct DrawnPath {
  std::vector<physics::PathSegment> segments;  // drawn exactly (quadratic Bezier pieces)
  std::vector<physics::ShotEvent> events;      // cushion contacts and the end are marked
  bool faint = false;  // an alternative: thin, grey, without markers, behind the others
  int stroke = 0;      // > 0: the stroke's number, written on the table at its start
  // Drawn in this colour (an object ball's own), edged dark, dashed while the ball
  // slides; empty: in the sliding and rolling colours (the cue ball's).
  std::optional<Colour> colour = std::nullopt;
};

// A ball on the table: where it stands and how it moves, stroke after stroke. It is drawn
// in its colour where it starts, with its name beside it; where its last (not faint)
// path ends it is drawn again as a ghost, and a path that retraces an earlier one is
// offset beside it so that both stay readable.
struct DrawnBall {
  std::string name;              // e.g. "cue ball", "red", "yellow"; empty: no label
  Colour colour;                 // its fill (a stripe's band)
  physics::Vec2 start;           // m, table frame
  std::vector<DrawnPath> paths;  // in order; each starts where the one before it ended
  // Pool's numbered balls: > 0 writes the number on a white disc at the ball's middle;
  // striped: a white ball with a band of `colour` across it (9-15).
  int number = 0;
  bool striped = false;
};

// The colours of named balls: "cue ball" and "white", the snooker colours (red, yellow,
// green, brown, blue, pink, black), also numbered ("red1", "red_2", "red 3"), and the
// pool balls "1" to "15" (9-15 as 1-7). Empty for any other name.
std::optional<Colour> ball_colour(std::string_view name);
// The fill of a ball whose name has no colour (ivory).
Colour other_ball_colour();
// A ball standing at `start` as its name says it looks (no paths yet): its colour
// (ball_colour, else other_ball_colour()), and for pool's "1" to "15" (also "ball9") its
// number, 9-15 striped (problems::identify_ball).
DrawnBall named_ball(const std::string& name, physics::Vec2 start);

// A small marker on the cloth, e.g. where one spin of a spin map comes to rest.
struct TableDot {
  physics::Vec2 position;  // m, table frame
  Colour colour;
  double radius = 3.0;            // px
  std::optional<Colour> outline;  // a 1 px ring; none when empty
};

// A quantity over the cloth in square cells, e.g. P(next pot) from each cue-ball position
// (planner/position.hpp): shaded (viridis, 0 transparent) and, at `outline_level`, its
// zone outlined like a coaching diagram (cell edges between values >= the level and
// below it).
struct TableField {
  double cell = 0.02;  // m, the cells' side; cell (i, j) spans [i cell, (i + 1) cell) x ...
  int columns = 0, rows = 0;
  std::vector<double> values;  // row-major from y = 0: values[j * columns + i], in [0, 1]
  bool shade = true;           // false: the outline alone (solve --svg)
  std::optional<double> outline_level;
  std::string shade_legend;    // e.g. "P(next pot) from each cue-ball position, 0-100 %"
  std::string outline_legend;  // e.g. "zone: within 10 points of the best"
};

// Which markings the cloth and rails carry.
enum class TableMarkings {
  automatic,  // snooker for a table of the default snooker size (3.569 x 1.778 m),
              // diamonds for any other 2:1 table, none otherwise
  snooker,    // baulk line, D, the six spots (scaled to the table)
  diamonds,   // pool and carom: three diamonds between pockets along the rails
  none,
};

struct TableScene {
  std::string title;                 // bold line at the top; may use k_{T} subscripts
  std::vector<std::string> caption;  // lines under the title, wrapped to the picture
  physics::Scene scene;              // table, pockets, ball radius; obstacles no ball stands on are
                                     // drawn as grey balls (problem_table() names them)
  TableMarkings markings = TableMarkings::automatic;
  std::vector<DrawnBall> balls;  // drawn in order, the last on top
  std::optional<TargetZone> target;
  std::optional<TableField> field;  // over the cloth, under the target zone and paths
  std::vector<TableDot> dots;  // over the paths, under the balls; the caller explains them
  std::string dots_legend;     // legend text for the dots; empty: no entry
  std::string faint_legend;    // legend text for the faint paths; empty: no entry
};

// The scene of a problem file: its table, its target zone, the cue ball (white, "cue
// ball"), its object balls by name in their colours (ball_colour, else
// other_ball_colour) and its obstacles as red balls named "obstacle 1", "obstacle 2", ...
// (named obstacles by their names, in their colours where a game gives them one)
TableScene problem_table(const problems::Problem& problem);

// The markings TableMarkings::automatic chooses for a scene.
TableMarkings markings_for(const physics::Scene& scene);

// Sizes in picture units (px), except where metres are said.
struct TableStyle {
  double pixels_per_metre = 300.0;  // preferred scale, kept so that the table's long side
  double min_table_side = 480.0;    // lies within [min_table_side, max_table_side] px
  double max_table_side = 1400.0;
  double font_size = 13.0;
  double line_width = 2.0;  // of a path
};

// Colours of the two motions on the cloth (Okabe-Ito, as the plots' palette).
Colour sliding_colour();
Colour rolling_colour();

Picture table_picture(const TableScene& scene, const TableStyle& style = {});

}  // namespace cueplan::draw
