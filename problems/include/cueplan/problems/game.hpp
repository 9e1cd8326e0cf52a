// The rules of a run-out, as far as a run needs them: which pots are legal, and what a
// simulated stroke did to the run (a pot that goes on, a clearance, or a foul or miss
// that ends it).
//
//   any_order  - pot every ball, in any order; a stroke must pot at least one ball.
//   nine_ball  - the cue ball strikes the lowest-numbered ball first; any ball may drop;
//                a legal stroke that drops the 9 wins (last, or on a combination).
//   eight_ball - the player's group (solids 1-7 or stripes 9-15) first, then the 8 in
//                the called pocket; the 8 dropped early or elsewhere loses.
//   snooker    - a red, then a colour (re-spotted while reds remain: on its own spot,
//                else the highest-valued free one), then the colours in order; the
//                break's score counts.
//
// A layout is a problem file with named `balls`, the cue ball and no `pot`; `game:` and
// `group:` may name the game in the file. Pure functions, no state: safe from any thread.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::problems {

enum class Game { any_order, nine_ball, eight_ball, snooker };
inline constexpr const char* kGameNames[] = {"any_order", "nine_ball", "eight_ball", "snooker"};
const char* to_string(Game game);
bool parse_game(const std::string& name, Game* game);

// Eight-ball's groups; open until the first ball of a group is potted, unless given.
enum class Group { open, solids, stripes };
const char* to_string(Group group);  // "open", "solids", "stripes"
bool parse_group(const std::string& name, Group* group);  // "solids" or "stripes" only

// Where a run stands between strokes.
struct GameState {
  Game game = Game::any_order;
  Group group = Group::open;  // eight_ball
  bool colour_on = false;     // snooker: a red has just dropped, a colour is on
  int potted = 0;             // balls potted this run (re-spotted colours count)
  int score = 0;              // snooker: the break; pool: balls potted
  bool cleared = false;       // the run is complete (table cleared, 9 or 8 legally potted)
};

// A pot the rules allow now: `ball` into `pocket`, the cue ball striking it first.
struct Candidate {
  std::string ball;
  int pocket = -1;
};

// The balls a player may aim to pot next (in table order); empty when none is on.
std::vector<std::string> balls_on(const GameState& state,
                                  const std::vector<physics::ObjectBall>& balls);
// The first-contact rule for the next stroke (a ball's name or a contact class of
// ball_names.hpp); `nominated` is the ball the player aims to pot (snooker's colour).
std::string contact_rule(const GameState& state, const std::vector<physics::ObjectBall>& balls,
                         const std::string& nominated);

// What a stroke did to the run.
struct ShotJudgement {
  bool continues = false;  // the player stays at the table (or the run is complete)
  bool foul = false;       // a foul or a loss of frame; otherwise a miss when !continues
  std::string reason;      // why the run ended, in words: "missed the pot", "foul: ..."
  std::vector<std::string> potted;  // object balls that dropped, in the result's order
  int points = 0;          // snooker: the points scored; pool: balls counted
  GameState next;          // the state after the stroke
  // The balls where the next stroke finds them: those at rest on the table, re-spotted
  // colours on their spots.
  std::vector<physics::ObjectBall> balls;
};

// Judges `result`, the stroke played from `state` with `balls` on `scene`, aiming to pot
// `aimed.ball` into `aimed.pocket` (eight-ball's called pocket for the 8).
ShotJudgement judge_stroke(const GameState& state, const physics::Scene& scene,
                           const Candidate& aimed, const physics::ShotResult& result);

// The state and balls after `ball` is potted legally (for look-ahead): the ball leaves
// the table or is re-spotted, the state moves on.
GameState after_pot(const GameState& state, const physics::Scene& scene, const std::string& ball,
                    std::vector<physics::ObjectBall>* balls);

// Where snooker's colour of value 2..7 is spotted on this table (the standard spots,
// scaled to its size; x along the length from the baulk cushion x = 0).
physics::Vec2 colour_spot(const physics::Scene& scene, int value);

// A layout: a problem without a pot, the game and group the file names (if any).
struct Layout {
  Problem problem;  // has_target false; no pot
  std::optional<Game> game;
  std::optional<Group> group;
};
struct LayoutResult {
  std::optional<Layout> layout;
  std::string error;  // "FILE:LINE: FIELD: message", as the problem loader's
  bool ok() const { return layout.has_value(); }
};
LayoutResult parse_layout(const std::string& yaml_text, const std::string& source_name);
LayoutResult load_layout(const std::string& path);

// Whether `balls` suit `game` (every ball a pool ball for nine_ball and eight_ball, the
// 8 among them for eight_ball; reds and colours for snooker): empty, or
// "balls.NAME: why" naming the first that does not.
std::string check_game_balls(const std::vector<physics::ObjectBall>& balls, Game game);

// The state a run starts from, with the file's group (eight_ball) or open.
GameState initial_state(Game game, std::optional<Group> group);

}  // namespace cueplan::problems
