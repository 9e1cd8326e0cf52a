// What a ball's name says about it in the games cueplan knows: snooker's reds and
// colours, pool's numbered balls (solids 1-7, the 8, stripes 9-15), or neither.
//
// Problem files name object balls freely (`balls: {red: [x, y]}`); names that a game
// uses carry its meaning: "red", "red3" are reds; "yellow" .. "black" are snooker's
// colours with their values 2 .. 7; "1" .. "15" (or "ball1" .. "ball15") are pool balls.
// "black" is snooker's black; pool's black is "8". Every other name is a plain ball.
//
// Pure functions, no state: safe from any thread.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::problems {

enum class BallKind {
  plain,        // a name no game gives a meaning
  red,          // snooker: "red", "red" followed by digits
  colour,       // snooker: yellow, green, brown, blue, pink, black
  pool_solid,   // pool 1-7
  pool_eight,   // pool 8
  pool_stripe,  // pool 9-15
};

struct BallIdentity {
  BallKind kind = BallKind::plain;
  int number = 0;  // pool: 1-15; snooker: the value potted (red 1, yellow 2 .. black 7); else 0
  // How the ball is drawn: its base colour as "#rrggbb" (empty for a plain ball: the
  // picture's own colour), and whether it is a stripe (a white ball with a band).
  std::string colour;
  bool striped = false;
};

// The identity a name gives a ball (plain when none).
BallIdentity identify_ball(const std::string& name);

// The classes of ball `first_contact` may name besides a single ball:
//   any_red    - any red (snooker);
//   lowest     - the lowest-numbered pool ball on the table (nine-ball);
//   solids     - pool 1-7; stripes - pool 9-15;
//   any_colour - any of snooker's colours.
inline constexpr const char* kContactClasses[] = {"any_red", "lowest", "solids", "stripes",
                                                   "any_colour"};
bool is_contact_class(const std::string& word);

// Whether striking `ball` first is legal when the rule is `rule` (a class above or a
// ball's name), with `balls` on the table when the stroke starts (for `lowest`).
bool contact_allowed(const std::string& rule, const std::string& ball,
                     const std::vector<physics::ObjectBall>& balls);

// The lowest-numbered pool ball among `balls`; empty when there is none.
std::optional<std::string> lowest_pool_ball(const std::vector<physics::ObjectBall>& balls);

}  // namespace cueplan::problems
