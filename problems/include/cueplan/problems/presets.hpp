// Table presets of problem files (`table: carom`) and the physics: block read on its own,
// for commands that build scenes without a whole problem file (`cueplan fit --physics`).
#pragma once

#include <string>

#include "cueplan/physics/shot.hpp"

namespace cueplan::problems {

// The carom preset (`table: carom`): a UMB match table (2.84 x 1.42 m between the
// cushion noses, no pockets), 61.5 mm balls of 210 g, the carom cushion's nose
// kCaromCushionHeight above the cloth, and cloth, cushion and ball constants from the
// literature (docs/fit.md cites them). A file's table, ball and physics fields override it.
inline constexpr double kCaromCushionHeight = 0.037;  // m, UMB: 37 mm (+-1 mm)
physics::Scene carom_scene();

// Applies the `physics:` block of a YAML (or JSON) document - the same fields, read by the
// same code, as a problem file's - to `scene`. Empty on success; otherwise one line,
// "SOURCE:LINE: physics.FIELD: message".
std::string apply_physics_block(const std::string& yaml_text, const std::string& source_name,
                                physics::Scene* scene);

}  // namespace cueplan::problems
