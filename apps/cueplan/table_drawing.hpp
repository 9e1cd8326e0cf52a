// A table seen from above, to scale, as a standalone SVG document: the cloth between
// the cushion noses, the cushion band outside them, pockets (capture circles), obstacle
// balls, the cue ball, the target zone and any number of ball paths coloured by sliding
// or rolling, with cushion contacts marked and numbered. Metre ticks run along two
// sides, with the origin at the corner where the noses x = 0 and y = 0 meet
// (shared/PHYSICS.md). Shared by the commands that show shots (simulate; solve and
// spinmap will draw their shots with it too).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::cli {

// Where the ball should stop: a circle of radius `radius` (m) around `centre`.
struct TargetZone {
  physics::Vec2 centre;
  double radius = 0.0;
};

// One ball's path, as physics::simulate records it.
struct DrawnPath {
  std::vector<physics::PathSegment> segments;  // drawn exactly (quadratic Bezier pieces)
  std::vector<physics::ShotEvent> events;      // cushion contacts and the end are marked
  // Thin, light and without markers: for alternatives drawn behind the main path.
  bool faint = false;
};

// A small marker on the cloth, e.g. where one spin of a spin map comes to rest.
struct TableDot {
  physics::Vec2 position;  // m, table frame
  std::string colour;      // fill, e.g. "#440154"
  double radius = 3.0;     // px
  std::string outline;     // stroke colour; empty: none
};

struct TableDrawing {
  std::string title;                 // bold line at the top; may use k_{T} subscripts
  std::vector<std::string> caption;  // lines under the title
  physics::Scene scene;
  std::optional<physics::Vec2> cue_ball;  // the ball's start, drawn as a white ball
  std::optional<TargetZone> target;
  std::vector<DrawnPath> paths;  // drawn in order, the last on top
  std::vector<TableDot> dots;    // over the paths, under the balls; the caller explains them
  std::string faint_legend;      // legend text for the faint paths; empty: no entry
};

// Sizes in SVG user units (pixels at 100 %), except where metres are said.
struct TableStyle {
  double pixels_per_metre = 300.0;
  double cushion_band = 0.06;  // m, width of the cushion band drawn outside the noses
  double font_size = 13.0;
  double line_width = 2.0;  // of a path
  std::string font_family = "DejaVu Sans, Helvetica, Arial, sans-serif";
};

// Colours of the two motions on the cloth (Okabe-Ito, as svg_plot's palette).
inline constexpr const char* kSlidingColour = "#D55E00";
inline constexpr const char* kRollingColour = "#0072B2";

// The drawing as a standalone SVG document.
std::string render_table_svg(const TableDrawing& drawing, const TableStyle& style = {});

}  // namespace cueplan::cli
