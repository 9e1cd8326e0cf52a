// Arithmetic on the table-plane vector physics::Vec2 (declared with the shot, in
// shot.hpp), shared by the physics, problems and planner layers.
//
// The operations live in their own namespace, brought in where they are used
// (`using namespace cueplan::physics::vec2;`), so that argument-dependent lookup never
// finds them and files with helpers of their own keep them. Each is written with the
// arithmetic of the helpers it replaces, term for term, so results stay bit-identical.
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
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }

}  // namespace cueplan::physics::vec2
