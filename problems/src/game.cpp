#include "cueplan/problems/game.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cueplan/problems/ball_names.hpp"

namespace cueplan::problems {
namespace {

bool is_pool(BallKind kind) {
  return kind == BallKind::pool_solid || kind == BallKind::pool_eight ||
         kind == BallKind::pool_stripe;
}

bool in_group(Group group, const std::string& ball) {
  const BallKind kind = identify_ball(ball).kind;
  if (group == Group::solids) return kind == BallKind::pool_solid;
  if (group == Group::stripes) return kind == BallKind::pool_stripe;
  return kind == BallKind::pool_solid || kind == BallKind::pool_stripe;  // open table
}

bool any_of_group(Group group, const std::vector<physics::ObjectBall>& balls) {
  return std::any_of(balls.begin(), balls.end(),
                     [&](const physics::ObjectBall& b) { return in_group(group, b.name); });
}

bool any_red(const std::vector<physics::ObjectBall>& balls) {
  return std::any_of(balls.begin(), balls.end(), [](const physics::ObjectBall& b) {
    return identify_ball(b.name).kind == BallKind::red;
  });
}

// Snooker's lowest-valued colour on the table.
std::optional<std::string> lowest_colour(const std::vector<physics::ObjectBall>& balls) {
  std::optional<std::string> best;
  int value = 99;
  for (const physics::ObjectBall& b : balls) {
    const BallIdentity id = identify_ball(b.name);
    if (id.kind == BallKind::colour && id.number < value) {
      value = id.number;
      best = b.name;
    }
  }
  return best;
}

double dist(physics::Vec2 a, physics::Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Whether a ball placed at `p` touches none of `balls` (but `except`) nor the cue ball.
bool spot_free(physics::Vec2 p, const std::vector<physics::ObjectBall>& balls,
               const std::string& except, std::optional<physics::Vec2> cue, double radius) {
  const double clear = 2.0 * radius;
  if (cue && dist(p, *cue) < clear) return false;
  return std::none_of(balls.begin(), balls.end(), [&](const physics::ObjectBall& b) {
    return b.name != except && dist(p, b.position) < clear;
  });
}

// Puts the colour back: on its spot when free, else the highest-valued free spot, else
// as near its own spot as is free along the table's length.
void respot(const physics::Scene& scene, const std::string& colour,
            std::vector<physics::ObjectBall>* balls, std::optional<physics::Vec2> cue) {
  const int value = identify_ball(colour).number;
  const double r = scene.radius();
  std::optional<physics::Vec2> place;
  if (spot_free(colour_spot(scene, value), *balls, colour, cue, r)) place = colour_spot(scene, value);
  for (int v = 7; v >= 2 && !place; --v)
    if (spot_free(colour_spot(scene, v), *balls, colour, cue, r)) place = colour_spot(scene, v);
  for (int step = 1; step < 2000 && !place; ++step) {
    for (int sign : {1, -1}) {
      physics::Vec2 p = colour_spot(scene, value);
      p.x += sign * step * 0.002;
      if (p.x > r && p.x < scene.length - r && spot_free(p, *balls, colour, cue, r)) {
        place = p;
        break;
      }
    }
  }
  if (!place) place = colour_spot(scene, value);
  auto it = std::find_if(balls->begin(), balls->end(),
                         [&](const physics::ObjectBall& b) { return b.name == colour; });
  if (it == balls->end())
    balls->push_back({colour, *place});
  else
    it->position = *place;
}

// The state change of one ball potted legally; the ball is already off `balls`.
void pot_one(GameState& s, const physics::Scene& scene, const std::string& ball,
             std::vector<physics::ObjectBall>* balls, std::optional<physics::Vec2> cue) {
  const BallIdentity id = identify_ball(ball);
  ++s.potted;
  switch (s.game) {
    case Game::any_order:
      s.score += 1;
      if (balls->empty()) s.cleared = true;
      break;
    case Game::nine_ball:
      s.score += 1;
      if (id.number == 9) s.cleared = true;
      break;
    case Game::eight_ball:
      s.score += 1;
      if (s.group == Group::open && (id.kind == BallKind::pool_solid || id.kind == BallKind::pool_stripe))
        s.group = id.kind == BallKind::pool_solid ? Group::solids : Group::stripes;
      if (id.kind == BallKind::pool_eight) s.cleared = true;
      break;
    case Game::snooker:
      s.score += id.number;
      if (id.kind == BallKind::red) {
        s.colour_on = true;
      } else if (s.colour_on) {
        respot(scene, ball, balls, cue);
        s.colour_on = false;
      }
      if (balls->empty()) s.cleared = true;
      break;
  }
}

}  // namespace

const char* to_string(Game game) { return kGameNames[static_cast<int>(game)]; }

bool parse_game(const std::string& name, Game* game) {
  for (int i = 0; i < 4; ++i)
    if (name == kGameNames[i]) {
      *game = static_cast<Game>(i);
      return true;
    }
  return false;
}

const char* to_string(Group group) {
  switch (group) {
    case Group::solids: return "solids";
    case Group::stripes: return "stripes";
    case Group::open: break;
  }
  return "open";
}

bool parse_group(const std::string& name, Group* group) {
  if (name == "solids") *group = Group::solids;
  else if (name == "stripes") *group = Group::stripes;
  else return false;
  return true;
}

GameState initial_state(Game game, std::optional<Group> group) {
  GameState s;
  s.game = game;
  if (group) s.group = *group;
  return s;
}

physics::Vec2 colour_spot(const physics::Scene& scene, int value) {
  // The standard spots of a 3569 x 1778 mm snooker table, scaled to this one.
  const double sx = scene.length / 3.569, sy = scene.width / 1.778;
  const double mid = scene.width / 2.0;
  switch (value) {
    case 2: return {0.737 * sx, mid - 0.292 * sy};
    case 3: return {0.737 * sx, mid + 0.292 * sy};
    case 4: return {0.737 * sx, mid};
    case 5: return {scene.length / 2.0, mid};
    case 6: return {scene.length * 0.75, mid};
    default: return {scene.length - 0.324 * sx, mid};
  }
}

std::vector<std::string> balls_on(const GameState& s, const std::vector<physics::ObjectBall>& balls) {
  std::vector<std::string> on;
  if (s.cleared) return on;
  switch (s.game) {
    case Game::any_order:
      for (const auto& b : balls) on.push_back(b.name);
      break;
    case Game::nine_ball:
      if (auto low = lowest_pool_ball(balls)) on.push_back(*low);
      break;
    case Game::eight_ball:
      for (const auto& b : balls)
        if (in_group(s.group, b.name)) on.push_back(b.name);
      if (on.empty())
        for (const auto& b : balls)
          if (identify_ball(b.name).kind == BallKind::pool_eight) on.push_back(b.name);
      break;
    case Game::snooker:
      if (s.colour_on) {
        for (const auto& b : balls)
          if (identify_ball(b.name).kind == BallKind::colour) on.push_back(b.name);
      } else if (any_red(balls)) {
        for (const auto& b : balls)
          if (identify_ball(b.name).kind == BallKind::red) on.push_back(b.name);
      } else if (auto low = lowest_colour(balls)) {
        on.push_back(*low);
      }
      break;
  }
  return on;
}

std::string contact_rule(const GameState& s, const std::vector<physics::ObjectBall>& balls,
                         const std::string& nominated) {
  switch (s.game) {
    case Game::any_order: return "";
    case Game::nine_ball: return lowest_pool_ball(balls).value_or("");
    case Game::eight_ball:
      if (any_of_group(s.group, balls)) return s.group == Group::solids    ? "solids"
                                               : s.group == Group::stripes ? "stripes"
                                                                           : nominated;
      return "8";
    case Game::snooker:
      if (s.colour_on) return nominated;
      if (any_red(balls)) return "any_red";
      return lowest_colour(balls).value_or("");
  }
  return "";
}

GameState after_pot(const GameState& state, const physics::Scene& scene, const std::string& ball,
                    std::vector<physics::ObjectBall>* balls) {
  GameState s = state;
  std::erase_if(*balls, [&](const physics::ObjectBall& b) { return b.name == ball; });
  pot_one(s, scene, ball, balls, std::nullopt);
  return s;
}

ShotJudgement judge_stroke(const GameState& state, const physics::Scene& scene,
                           const Candidate& aimed, const physics::ShotResult& result) {
  ShotJudgement j;
  j.next = state;
  const std::vector<physics::ObjectBall>& before = scene.balls;
  const auto end = [&](bool foul, std::string reason) {
    j.continues = false;
    j.foul = foul;
    j.reason = std::move(reason);
    return j;
  };
  if (result.status == physics::ShotStatus::pocketed) return end(true, "foul: cue ball potted");
  if (result.status != physics::ShotStatus::rest) return end(true, "stroke failed");
  if (result.first_contact < 0) return end(true, "foul: struck no ball");
  const std::string first = result.balls[static_cast<size_t>(result.first_contact)].name;
  const std::string rule = contact_rule(state, before, aimed.ball);
  if (!rule.empty() && !contact_allowed(rule, first, before))
    return end(true, "foul: struck " + first + " first");

  std::vector<std::pair<std::string, int>> dropped;  // ball, pocket
  for (size_t k = 1; k < result.balls.size(); ++k) {
    const physics::BallOutcome& b = result.balls[k];
    if (b.pocketed) dropped.emplace_back(b.name, b.pocket);
    else j.balls.push_back({b.name, b.final_position});
  }
  for (const auto& d : dropped) j.potted.push_back(d.first);
  const physics::Vec2 cue = result.final_position;

  GameState s = state;
  switch (state.game) {
    case Game::any_order:
    case Game::nine_ball:
      for (const auto& d : dropped) pot_one(s, scene, d.first, &j.balls, cue);
      break;
    case Game::eight_ball: {
      const bool group_left = any_of_group(state.group, before);
      bool own = false;
      for (const auto& d : dropped) {
        const BallIdentity id = identify_ball(d.first);
        if (id.kind == BallKind::pool_eight) {
          if (group_left) return end(true, "the 8 potted early");
          if (aimed.ball != d.first || aimed.pocket != d.second)
            return end(true, "the 8 in the wrong pocket");
        }
      }
      // The aimed ball first, so that an open table takes its group.
      std::stable_sort(dropped.begin(), dropped.end(),
                       [&](const auto& a, const auto& b) { return a.first == aimed.ball && b.first != aimed.ball; });
      for (const auto& d : dropped) {
        const Group g = s.group;
        if (in_group(g, d.first) || identify_ball(d.first).kind == BallKind::pool_eight) {
          own = true;
          pot_one(s, scene, d.first, &j.balls, cue);
        }
      }
      if (!own && !dropped.empty()) return end(false, "potted only the other group");
      break;
    }
    case Game::snooker: {
      for (const auto& d : dropped) {
        const BallKind kind = identify_ball(d.first).kind;
        const bool legal = state.colour_on ? d.first == aimed.ball
                           : any_red(before) ? kind == BallKind::red
                                             : d.first == rule;
        if (!legal) return end(true, "foul: potted " + d.first);
      }
      for (const auto& d : dropped) pot_one(s, scene, d.first, &j.balls, cue);
      if (state.colour_on && dropped.empty()) s.colour_on = true;
      break;
    }
  }
  j.points = s.score - state.score;
  j.next = s;
  if (dropped.empty()) return end(false, "missed the pot");
  j.continues = true;
  if (state.game == Game::snooker && j.balls.empty()) j.next.cleared = true;
  if (state.game == Game::any_order && j.balls.empty()) j.next.cleared = true;
  return j;
}

// --- layouts -------------------------------------------------------------------------

namespace {

LayoutResult layout_error(const std::string& source, int line, const std::string& field,
                          const std::string& message) {
  LayoutResult r;
  r.error = source + ":" + (line > 0 ? std::to_string(line) + ":" : "") + " " + field + ": " + message;
  return r;
}

int node_line(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

// The line of a top-level key (from 1), or 0.
int key_line(const std::vector<std::string>& lines, const std::string& key) {
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(key + ":", 0) == 0) return static_cast<int>(i) + 1;
  return 0;
}

// Whether `ball` names a ball the game knows.
std::string game_ball_error(Game game, const std::string& ball) {
  const BallKind kind = identify_ball(ball).kind;
  switch (game) {
    case Game::any_order: return "";
    case Game::nine_ball:
    case Game::eight_ball:
      return is_pool(kind) ? "" : "is not a pool ball (name pool balls 1 to 15) in " +
                                      std::string(to_string(game));
    case Game::snooker:
      return kind == BallKind::red || kind == BallKind::colour
                 ? ""
                 : "is not a snooker ball (red, red2, ..., yellow .. black)";
  }
  return "";
}

}  // namespace

LayoutResult parse_layout(const std::string& yaml_text, const std::string& source) {
  std::vector<std::string> lines;
  {
    std::istringstream in(yaml_text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  Layout layout;
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    const int line = e.mark.is_null() ? 0 : e.mark.line + 1;
    return layout_error(source, line, "yaml", e.msg);
  }
  std::string rest = yaml_text;
  if (root.IsMap()) {
    if (root["pot"])
      return layout_error(source, node_line(root["pot"]), "pot",
                          "a layout has no pot: the run chooses its pots");
    if (root["target"])
      return layout_error(source, node_line(root["target"]), "target",
                          "a layout has no target: the run chooses where the cue ball goes");
    for (const char* key : {"game", "group"}) {
      const YAML::Node node = root[key];
      if (!node) continue;
      const int line = key_line(lines, key);
      const std::string value = node.IsScalar() ? node.Scalar() : "";
      if (std::string(key) == "game") {
        Game g;
        if (!parse_game(value, &g))
          return layout_error(source, line, key,
                              "must be any_order, nine_ball, eight_ball or snooker, got '" + value + "'");
        layout.game = g;
      } else {
        Group g;
        if (!parse_group(value, &g))
          return layout_error(source, line, key, "must be solids or stripes, got '" + value + "'");
        layout.group = g;
      }
      if (line == 0)
        return layout_error(source, node_line(node), key, "write it as a top-level key of its own line");
      lines[static_cast<size_t>(line) - 1] = "# " + lines[static_cast<size_t>(line) - 1];
    }
    if (layout.group && layout.game && *layout.game != Game::eight_ball)
      return layout_error(source, key_line(lines, "# group"), "group",
                          "is for eight_ball only, the game is " + std::string(to_string(*layout.game)));
    rest.clear();
    for (const std::string& line : lines) rest += line + "\n";
    // The loader asks for a target without a pot: the cue ball's own place stands in.
    const YAML::Node cue = root["cue_ball"];
    if (cue && cue.IsSequence() && cue.size() == 2 && cue[0].IsScalar() && cue[1].IsScalar())
      rest += "target: [" + cue[0].Scalar() + ", " + cue[1].Scalar() + "]\n";
  }
  LoadResult loaded = parse_problem(rest, source);
  if (!loaded.ok()) {
    LayoutResult r;
    r.error = loaded.error;
    return r;
  }
  layout.problem = std::move(*loaded.problem);
  layout.problem.has_target = false;
  if (layout.problem.scene.balls.empty())
    return layout_error(source, key_line(lines, "balls"), "balls", "a layout needs at least one object ball");
  if (layout.game)
    if (std::string e = check_game_balls(layout.problem.scene.balls, *layout.game); !e.empty()) {
      const size_t colon = e.find(": ");
      return layout_error(source, key_line(lines, "balls"), e.substr(0, colon), e.substr(colon + 2));
    }
  LayoutResult r;
  r.layout = std::move(layout);
  return r;
}

LayoutResult load_layout(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    LayoutResult r;
    r.error = path + ": is a directory, not a layout file";
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    LayoutResult r;
    r.error = path + ": cannot open";
    return r;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_layout(text.str(), path);
}

std::string check_game_balls(const std::vector<physics::ObjectBall>& balls, Game game) {
  for (const physics::ObjectBall& b : balls)
    if (std::string e = game_ball_error(game, b.name); !e.empty()) return "balls." + b.name + ": " + e;
  if (game == Game::eight_ball &&
      std::none_of(balls.begin(), balls.end(), [](const physics::ObjectBall& b) {
        return identify_ball(b.name).kind == BallKind::pool_eight;
      }))
    return "balls: eight_ball needs the 8 on the table";
  return "";
}

}  // namespace cueplan::problems
