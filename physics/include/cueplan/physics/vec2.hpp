// Arithmetic on the table-plane vector physics::Vec2 (declared with the shot, in
// shot.hpp), shared by the physics, problems and planner layers.
//
// The operations live in their own namespace, brought in where they are used
// (`using namespace cueplan::physics::vec2;`), so that argument-dependent lookup never
// finds them and files with helpers of their own keep them.
#pragma once

#include <cmath>

#include "cueplan/physics/shot.hpp"

namespace cueplan::physics::vec2 {

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// The z component of a x b: > 0 when b lies counter-clockwise of a.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// |(x, y)|: the square root of the sum of the squares, within 2 ulps (hypot: 1) in about
// half hypot's time (no correction step after the root; hypot was 8 % of a plan's
// time); std::hypot where a square could underflow or overflow (|x|, |y| below 1e-150 or
// above 1e150), and for the zero vector and non-finite input.
inline double length(double x, double y) {
  const double s = x * x + y * y;
  if (s >= 0x1p-1000 && s <= 0x1p1000) return std::sqrt(s);
  return std::hypot(x, y);
}
inline double norm(Vec2 a) { return length(a.x, a.y); }

}  // namespace cueplan::physics::vec2
