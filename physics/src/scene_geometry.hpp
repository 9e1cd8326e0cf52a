#pragma once
// The parts of a scene's geometry that the shot simulator meets - the cushion lines, the
// open stretches of them in jawed pockets' mouths, the jaws' points and facings - built
// once per CompiledScene rather than for every shot.

#include <array>
#include <vector>

#include "ball_motion.hpp"
#include "cueplan/physics/shot.hpp"

namespace cueplan::physics::detail {

// The four cushions: outward normal n (from the ball into the cushion) and the
// value of n . p at which the ball's centre touches the cushion.
struct CushionLine {
  Vec2 normal;
  double contact;  // n . p at contact
};

// A straight cushion nose stops where a jawed pocket's point begins: the stretch of the
// cushion's line between the pockets' nose tangents (along x for cushions 0 and 2, y for
// 1 and 3) that lies in a pocket's mouth is open.
struct Gap {
  double lo, hi;
};
using CushionGaps = std::array<std::vector<Gap>, 4>;

// A jawed pocket's parts as the ball's centre meets them: each facing a line (normal n
// from the ball into it, contact where n . p = contact) over [0, length] along `dir`
// from `start`; each point a circle of radius point_radius + R cos(theta). `box` bounds
// all of them, for a cheap first test.
struct JawPart {
  Vec2 normal, start, dir;
  double contact = 0.0, length = 0.0;
};
struct Jaws {
  int pocket = -1;
  JawPart facing[2];
  Vec2 point[2];
  double point_reach = 0.0;  // point_radius + R cos(theta)
  detail::Box box{};
  detail::Box part_box[4]{};  // each part's contact locus, by part number
};

// All of the above for one scene.
struct SceneGeometry {
  std::array<CushionLine, 4> lines{};
  CushionGaps gaps;
  std::vector<Jaws> jaws;
};

// Where p lies along cushion `cushion`: x for cushions 0 and 2, y for 1 and 3.
inline double along_cushion(int cushion, Vec2 p) { return cushion % 2 == 0 ? p.x : p.y; }

SceneGeometry scene_geometry(const Scene& scene);

}  // namespace cueplan::physics::detail
