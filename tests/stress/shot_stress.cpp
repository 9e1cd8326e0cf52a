// Stress run of the shot simulator: random strokes on random scenes.
//
// Scenes: the snooker table, random sizes and tables with just room for a ball; other
// balls, cushions and cloths; pockets or none; the cue ball touching a cushion or in a
// corner; obstacle balls touching the cue ball, each other and the cushions, or lying
// in a pocket; object balls (one scene in three, 1 to 8 of them, 15 now and then)
// touching the cue ball, each other or an obstacle, on the stroke's line, by a pocket,
// with either collision model; scenes built to bounce for ever (elastic frictionless
// cushions, almost no friction on the cloth) to reach the event cap. Strokes: speeds
// from 1e-6 to 20 m/s, any aim, spins inside the miscue limit and far beyond it, both
// impact methods, and small event caps. A few inputs in twenty are spoiled (zero-length
// table, negative radius, NaN, a ball off the table, ...). Checks, per shot:
//   - every number in the result, every ball's events and path is finite;
//   - the simulation ends: at most max_events + 1 events of all balls (+ 4 with object
//     balls: a contact logs one event for each ball, rests at one instant one each), and
//     event_limit says so;
//   - each ball's kinetic energy never rises along its events and inside its path
//     segments except where another ball strikes it, two balls' energy never rises
//     across their contact, and no centre leaves the cushion lines;
//   - balls in contact are 2R apart, and no two balls (nor a ball and an obstacle) ever
//     overlap, at any event or half-way along any path segment (to 1e-6 of 2R);
//   - the status agrees with the balls' last events;
//   - spoiled input is refused with a message naming the field;
//   - the same input gives the same events (one shot in a thousand).
// Prints the counts; exits 1 when a check fails, 2 for bad arguments.
//
//   stress_shots [--shots N] [--seed S] [--json FILE]
#include <algorithm>
#include <array>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "support/physics_checks.hpp"
#include "support/stress_output.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// On the cloth the energy is rebuilt from the path (tests/support/physics_checks.hpp)
// and compared with the simulator's events: the two differ by rounding, which with
// spins of thousands of rad/s reaches a few 1e-11 of the energy.
constexpr double kEnergySlack = 1e-10;
constexpr double kPaperEnergySlack = 1e-3;
// The exact method's error at the simulator's default accuracy (1e-9) can show as a
// gain where nothing is lost (e = 1, no friction at the cloth).
constexpr double kExactImpactEnergySlack = 1e-9;
// The same for a ball-ball collision (its error stays below 100 tolerances of the speed,
// bench/README.md, and the energy's below twice that). A ball at rest before a contact
// is counted with the sidespin it had when it stopped, which only adds to "before".
constexpr double kCollisionEnergySlack = 1e-8;
// How far, in units of 2R, balls in contact may be from 2R apart, and any two balls may
// overlap: a contact missed lets balls pass through each other (overlaps of order 1);
// rounding in the cascades of ever smaller contacts of balls pressed together leaves
// them a few 1e-7 inside.
constexpr double kContactSlack = 1e-6;

struct Options {
  long long shots = 50000;
  uint64_t seed = 1;
  std::string json;
};

class Sampler {
 public:
  explicit Sampler(uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  template <size_t N>
  double pick(const std::array<double, N>& values) {
    return values[static_cast<size_t>(index(static_cast<int>(N)))];
  }

 private:
  std::mt19937_64 rng_;
};

struct Case {
  Scene scene;
  Vec2 cue_ball;
  Shot shot;
  SimulationOptions options;
  std::string kind;
  std::string bad_field;  // set when the input must be refused: the field its error names
};

// Ball and cushion: snooker, or another ball size with friction and restitution
// anywhere validate() accepts.
CushionParams draw_ball(Sampler& s) {
  if (s.chance(0.6)) return CushionParams{};
  CushionParams p = params_for_radius(s.log_uniform(0.005, 0.06));
  p.mass = s.log_uniform(0.01, 1.0);
  const double tan_theta = p.sin_theta() / p.cos_theta();
  p.mu_cushion = s.chance(0.2) ? 0.0 : s.uniform(0.0, 1.0) * tan_theta;
  p.mu_table = s.chance(0.2) ? 0.0 : s.uniform(0.0, 1.0);
  p.restitution = s.chance(0.2) ? 1.0 : s.uniform(0.3, 1.0);
  for (int i = 0; i < 200 && p.validate(); ++i) {
    p.mu_cushion *= 0.7;
    p.mu_table *= 0.7;
  }
  return p;
}

Vec2 random_spot(Sampler& s, const Scene& sc) {
  const double off = sc.contact_offset();
  Vec2 p{s.uniform(off, sc.length - off), s.uniform(off, sc.width - off)};
  // One spot in five on a cushion line, one in twenty in a corner.
  const double u = s.uniform(0.0, 1.0);
  if (u < 0.05) {
    p = {s.chance(0.5) ? off : sc.length - off, s.chance(0.5) ? off : sc.width - off};
  } else if (u < 0.25) {
    switch (s.index(4)) {
      case 0:
        p.y = off;
        break;
      case 1:
        p.x = sc.length - off;
        break;
      case 2:
        p.y = sc.width - off;
        break;
      default:
        p.x = off;
        break;
    }
  }
  return p;
}

// Object balls (and how they collide), kept only where the scene stays valid. Returns
// the direction (deg) along which some of them lie from the cue ball.
double draw_object_balls(Sampler& s, Case* c) {
  Scene& sc = c->scene;
  const double r = sc.radius();
  const double line_deg = s.uniform(0.0, 360.0);
  const Vec2 line{std::cos(line_deg * kDeg), std::sin(line_deg * kDeg)};
  const int n = s.chance(0.1) ? 15 : 1 + s.index(8);
  for (int i = 0; i < n; ++i) {
    const double turn = s.uniform(0.0, 2.0 * std::numbers::pi);
    const Vec2 dir{std::cos(turn), std::sin(turn)};
    const auto touching = [&](Vec2 o) {
      return Vec2{o.x + 2.0 * r * dir.x, o.y + 2.0 * r * dir.y};
    };
    Vec2 p;
    switch (s.index(6)) {
      case 0: p = touching(c->cue_ball); break;
      case 1:
        if (!sc.balls.empty()) {
          p = touching(
              sc.balls[static_cast<size_t>(s.index(static_cast<int>(sc.balls.size())))].position);
          break;
        }
        [[fallthrough]];
      case 2: {  // on the stroke's line, a few diameters on
        const double d = 2.0 * r * (1.0 + s.uniform(0.0, 8.0));
        p = {c->cue_ball.x + d * line.x, c->cue_ball.y + d * line.y};
        break;
      }
      case 3:
        if (!sc.obstacles.empty()) {
          p = touching(
              sc.obstacles[static_cast<size_t>(s.index(static_cast<int>(sc.obstacles.size())))]);
          break;
        }
        [[fallthrough]];
      case 4:  // by a pocket's jaws
        if (!sc.pockets.empty()) {
          const Pocket& k =
              sc.pockets[static_cast<size_t>(s.index(static_cast<int>(sc.pockets.size())))];
          p = {k.centre.x + (k.radius + r) * dir.x, k.centre.y + (k.radius + r) * dir.y};
          break;
        }
        [[fallthrough]];
      default: p = random_spot(s, sc); break;
    }
    sc.balls.push_back({"b" + std::to_string(i), p});
    if (sc.validate() || sc.check_position(c->cue_ball, {"cue_ball"})) sc.balls.pop_back();
  }
  BallContact& contact = sc.ball_contact;
  if (s.chance(0.3)) {
    contact.model = BallModel::frictional_inelastic;
    if (s.chance(0.5)) contact.friction = BallFriction::speed_dependent;
  }
  if (s.chance(0.3)) {
    contact.mu_ball = s.chance(0.2) ? 0.0 : s.uniform(0.0, 0.3);
    contact.restitution = s.chance(0.2) ? 1.0 : s.uniform(0.3, 1.0);
  }
  for (int i = 0; i < 200 && sc.validate(); ++i) contact.mu_ball *= 0.7;  // mu_b mu_s < 2/7
  if (!sc.balls.empty()) c->kind += ", object balls";
  return line_deg;
}

Case draw_case(Sampler& s) {
  Case c;
  Scene& sc = c.scene;
  sc.ball_and_cushion = draw_ball(s);
  const double off = sc.contact_offset();
  const double r = sc.radius();

  // Table size.
  const int size_kind = s.index(20);
  if (size_kind < 10) {
    c.kind = "snooker size";
  } else if (size_kind < 15) {
    c.kind = "random size";
    sc.length = s.log_uniform(0.2, 10.0);
    sc.width = s.log_uniform(0.2, 10.0);
  } else if (size_kind < 18) {
    c.kind = "tiny table";
    sc.length = 2.0 * off * (1.0 + s.log_uniform(1e-9, 2.0));
    sc.width = 2.0 * off * (1.0 + s.log_uniform(1e-9, 2.0));
  } else {
    c.kind = "corridor";
    sc.length = s.log_uniform(1.0, 10.0);
    sc.width = 2.0 * off * (1.0 + s.log_uniform(1e-9, 0.5));
  }

  // Cloth.
  if (s.chance(0.3)) {
    sc.cloth.mu_slide = s.log_uniform(0.01, 1.0);
    sc.cloth.mu_roll = s.log_uniform(1e-4, 0.1);
    sc.cloth.mu_spin = s.chance(0.2) ? 0.0 : s.uniform(0.0, 0.2);
    sc.cloth.gravity = s.uniform(1.0, 30.0);
  }

  // Pockets: none, the six of a table (radius 1.7 R), or a few anywhere.
  const int pocket_kind = s.index(5);
  if (pocket_kind < 2) {
    const double pr = 1.7 * r;
    const double l = sc.length, w = sc.width;
    sc.pockets = {{{0, 0}, pr}, {{l / 2, 0}, pr}, {{l, 0}, pr},
                  {{0, w}, pr}, {{l / 2, w}, pr}, {{l, w}, pr}};
    c.kind += ", 6 pockets";
  } else if (pocket_kind == 2) {
    const int n = 1 + s.index(4);
    for (int i = 0; i < n; ++i)
      sc.pockets.push_back({{s.uniform(-0.1, sc.length + 0.1), s.uniform(-0.1, sc.width + 0.1)},
                            s.log_uniform(0.2 * r, 5.0 * r)});
    c.kind += ", random pockets";
  }

  // The cue ball: anywhere it may rest, on a cushion line or in a corner.
  c.cue_ball = random_spot(s, sc);
  for (int i = 0; i < 20 && sc.check_position(c.cue_ball, {"cue_ball"}); ++i)
    c.cue_ball = random_spot(s, sc);
  if (sc.check_position(c.cue_ball, {"cue_ball"})) {
    sc.pockets.clear();  // a table too small for the ball beside its pockets
    c.kind = c.kind.substr(0, c.kind.find(','));
  }

  // Obstacles, kept only where the scene stays valid.
  const int obstacles = s.chance(0.4) ? 0 : 1 + s.index(6);
  for (int i = 0; i < obstacles; ++i) {
    Vec2 o;
    const double turn = s.uniform(0.0, 2.0 * std::numbers::pi);
    const Vec2 dir{std::cos(turn), std::sin(turn)};
    switch (s.index(5)) {
      case 0:  // touching the cue ball
        o = {c.cue_ball.x + 2.0 * r * dir.x, c.cue_ball.y + 2.0 * r * dir.y};
        break;
      case 1:  // touching another obstacle
        if (!sc.obstacles.empty()) {
          const Vec2 b =
              sc.obstacles[static_cast<size_t>(s.index(static_cast<int>(sc.obstacles.size())))];
          o = {b.x + 2.0 * r * dir.x, b.y + 2.0 * r * dir.y};
          break;
        }
        [[fallthrough]];
      case 2:  // in a pocket
        if (!sc.pockets.empty()) {
          o = sc.pockets[static_cast<size_t>(s.index(static_cast<int>(sc.pockets.size())))].centre;
          o = {std::clamp(o.x, off, sc.length - off), std::clamp(o.y, off, sc.width - off)};
          break;
        }
        [[fallthrough]];
      default:
        o = random_spot(s, sc);
        break;
    }
    sc.obstacles.push_back(o);
    if (sc.validate() || sc.check_position(c.cue_ball, {"cue_ball"}))
      sc.obstacles.pop_back();
  }

  const bool object_balls = s.chance(0.35);
  const double line_deg = object_balls ? draw_object_balls(s, &c) : 0.0;

  // The stroke.
  c.shot.speed =
      s.chance(0.1) ? s.pick(std::array{1e-6, 10.0, 20.0, 1e-3}) : s.log_uniform(1e-6, 10.0);
  c.shot.aim_deg = s.chance(0.2) ? s.pick(std::array{0.0, 90.0, 180.0, 270.0, 45.0, -135.0, 720.0})
                                 : s.uniform(-360.0, 720.0);
  if (s.chance(0.7)) {
    // Inside the miscue limit k_T^2 + k_S^2 <= 1.25^2.
    const double k = 1.25 * std::sqrt(s.uniform(0.0, 1.0)), turn = s.uniform(0.0, 360.0) * kDeg;
    c.shot.topspin_k = k * std::cos(turn);
    c.shot.sidespin_k = k * std::sin(turn);
  } else {
    c.shot.topspin_k =
        s.chance(0.2) ? s.pick(std::array{-20.0, 20.0, 0.0, 1.0}) : s.uniform(-20.0, 20.0);
    c.shot.sidespin_k =
        s.chance(0.2) ? s.pick(std::array{-20.0, 20.0, 0.0}) : s.uniform(-20.0, 20.0);
  }

  // Half the strokes on a table with object balls go along the line some lie on.
  if (!sc.balls.empty() && s.chance(0.5)) c.shot.aim_deg = line_deg;

  // Options: the paper's scheme sometimes, small event caps sometimes.
  if (s.chance(0.15)) c.options.impact_method = ImpactMethod::paper;
  if (s.chance(0.15)) c.options.max_events = 1 + s.index(20);

  // One scene in forty bounces for ever: elastic, frictionless cushions and almost
  // no friction on the cloth of a small table.
  if (s.chance(0.025)) {
    c.kind = "endless bouncing";
    sc.ball_and_cushion = CushionParams{};
    sc.ball_and_cushion.mu_cushion = sc.ball_and_cushion.mu_table = 0.0;
    sc.ball_and_cushion.restitution = 1.0;
    sc.cloth.mu_roll = 1e-9;
    sc.cloth.mu_slide = 1e-9;
    sc.cloth.mu_spin = 0.0;
    sc.length = s.uniform(0.2, 1.0);
    sc.width = s.uniform(0.2, 1.0);
    sc.pockets.clear();
    sc.obstacles.clear();
    sc.balls.clear();
    c.cue_ball = {sc.length / 2, sc.width / 2};
    c.shot = {s.uniform(1.0, 10.0), s.uniform(0.0, 360.0), 1.0, 0.0};
    c.options.max_events = 200;
  }
  return c;
}

// Spoils one field of a case; its error must then name `bad_field` (as FieldPath::text()).
void spoil(Sampler& s, Case* c) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Scene& sc = c->scene;
  c->kind = "spoiled";
  switch (s.index(20)) {
    case 0:
      sc.length = 0.0;
      c->bad_field = "length";
      break;
    case 1:
      sc.length = s.chance(0.5) ? -1.0 : nan;
      c->bad_field = "length";
      break;
    case 2:
      sc.width = s.chance(0.5) ? 0.0 : inf;
      c->bad_field = "width";
      break;
    case 3:  // no room for a ball
      sc.length = sc.width = sc.contact_offset();
      c->bad_field = "length";
      break;
    case 4:
      sc.ball_and_cushion.radius = -0.02;
      sc.ball_and_cushion.cushion_height = -0.028;
      c->bad_field = "ball_and_cushion.radius";
      break;
    case 5:
      sc.ball_and_cushion.mass = s.chance(0.5) ? 0.0 : nan;
      c->bad_field = "ball_and_cushion.mass";
      break;
    case 6:
      sc.ball_and_cushion.restitution = 0.0;
      c->bad_field = "ball_and_cushion.restitution";
      break;
    case 7:
      sc.cloth.gravity = s.chance(0.5) ? 0.0 : nan;
      c->bad_field = "cloth.gravity";
      break;
    case 8:
      sc.cloth.mu_roll = 0.0;
      c->bad_field = "cloth.mu_roll";
      break;
    case 9:
      sc.cloth.mu_slide = s.chance(0.5) ? nan : -0.2;
      c->bad_field = "cloth.mu_slide";
      break;
    case 10:
      sc.cloth.mu_spin = s.chance(0.5) ? -1.0 : inf;
      c->bad_field = "cloth.mu_spin";
      break;
    case 11:
      sc.pockets.insert(sc.pockets.begin(), Pocket{{0.0, 0.0}, s.chance(0.5) ? nan : -0.05});
      sc.obstacles.clear();
      c->bad_field = "pockets[0].radius";
      break;
    case 12:
      sc.pockets.insert(sc.pockets.begin(), Pocket{{nan, 0.0}, 0.05});
      sc.obstacles.clear();
      c->bad_field = "pockets[0].centre";
      break;
    case 13:
      sc.obstacles.insert(sc.obstacles.begin(), s.chance(0.5) ? Vec2{nan, 0.5} : Vec2{-1.0, 0.5});
      c->bad_field = "obstacles[0]";
      break;
    case 14:
      c->cue_ball = s.chance(0.5) ? Vec2{0.5, nan} : Vec2{-0.01, 0.5};
      c->bad_field = "cue_ball";
      break;
    case 15:
      c->shot.speed = s.chance(0.5) ? 0.0 : (s.chance(0.5) ? nan : -1.0);
      c->bad_field = "shot.speed";
      break;
    case 16:
      if (s.chance(0.5)) {
        c->shot.aim_deg = inf;
        c->bad_field = "shot.aim_deg";
      } else {
        (s.chance(0.5) ? c->shot.topspin_k : c->shot.sidespin_k) = nan;
        c->bad_field = std::isnan(c->shot.topspin_k) ? "shot.topspin_k" : "shot.sidespin_k";
      }
      break;
    case 17:  // an object ball off the table
      sc.balls.insert(sc.balls.begin(),
                      ObjectBall{"spoilt", s.chance(0.5) ? Vec2{nan, 0.5} : Vec2{-1.0, 0.5}});
      c->bad_field = "balls.spoilt";
      break;
    case 18:
      if (s.chance(0.5)) {
        sc.ball_contact.restitution = s.chance(0.5) ? 0.0 : 1.5;
        c->bad_field = "ball_contact.restitution";
      } else {
        sc.ball_contact.mu_ball = s.chance(0.5) ? -0.1 : nan;
        c->bad_field = "ball_contact.mu_ball";
      }
      break;
    default:
      c->options.max_events = s.chance(0.5) ? 0 : -5;
      c->bad_field = "max_events";
      break;
  }
}

std::string reproducer(const Case& c) {
  const Scene& sc = c.scene;
  const CushionParams& p = sc.ball_and_cushion;
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "[%s] table %.17g x %.17g, ball {mass %.17g, radius %.17g, height %.17g, mu_w "
                "%.17g, mu_s %.17g, e %.17g}, cloth {%.17g, %.17g, %.17g, g %.17g}, %zu pockets, "
                "%zu obstacles, cue ball (%.17g, %.17g), shot {%.17g, %.17g, %.17g, %.17g}, "
                "method %s, max_events %d",
                c.kind.c_str(), sc.length, sc.width, p.mass, p.radius, p.cushion_height,
                p.mu_cushion, p.mu_table, p.restitution, sc.cloth.mu_slide, sc.cloth.mu_roll,
                sc.cloth.mu_spin, sc.cloth.gravity, sc.pockets.size(), sc.obstacles.size(),
                c.cue_ball.x, c.cue_ball.y, c.shot.speed, c.shot.aim_deg, c.shot.topspin_k,
                c.shot.sidespin_k, to_string(c.options.impact_method), c.options.max_events);
  std::string out = buf;
  for (const Pocket& k : sc.pockets) {
    std::snprintf(buf, sizeof buf, " pocket (%.17g, %.17g) r %.17g", k.centre.x, k.centre.y,
                  k.radius);
    out += buf;
  }
  for (const Vec2& o : sc.obstacles) {
    std::snprintf(buf, sizeof buf, " obstacle (%.17g, %.17g)", o.x, o.y);
    out += buf;
  }
  if (!sc.balls.empty()) {
    std::snprintf(buf, sizeof buf, " ball contact {%s, %s, mu_b %.17g, e_b %.17g}",
                  to_string(sc.ball_contact.model), to_string(sc.ball_contact.friction),
                  sc.ball_contact.mu_ball, sc.ball_contact.restitution);
    out += buf;
  }
  for (const ObjectBall& b : sc.balls) {
    std::snprintf(buf, sizeof buf, " ball %s (%.17g, %.17g)", b.name.c_str(), b.position.x,
                  b.position.y);
    out += buf;
  }
  return out;
}

struct Failures {
  std::map<std::string, long long> count;
  std::vector<std::string> examples;
  void add(const std::string& what, const std::string& detail) {
    if (++count[what] <= 3) examples.push_back(what + ": " + detail);
  }
  long long total() const {
    long long n = 0;
    for (const auto& [what, k] : count) n += k;
    return n;
  }
};

bool same_events(const ShotResult& a, const ShotResult& b) {
  if (a.status != b.status || a.balls.size() != b.balls.size()) return false;
  for (size_t k = 0; k < a.balls.size(); ++k) {
    const std::vector<ShotEvent>&ea = a.balls[k].events, &eb = b.balls[k].events;
    if (ea.size() != eb.size()) return false;
    for (size_t i = 0; i < ea.size(); ++i) {
      const ShotEvent &x = ea[i], &y = eb[i];
      if (x.type != y.type || x.other != y.other ||
          std::memcmp(&x.time, &y.time, sizeof x.time) != 0 ||
          std::memcmp(&x.position, &y.position, sizeof x.position) != 0 ||
          std::memcmp(&x.velocity, &y.velocity, sizeof x.velocity) != 0 ||
          std::memcmp(&x.spin, &y.spin, sizeof x.spin) != 0)
        return false;
    }
  }
  return true;
}

int run(const Options& opt) {
  Sampler s(opt.seed);
  Failures fail;
  std::map<std::string, long long> statuses, kinds, failed_impacts;
  long long nonfinite = 0, refused = 0, refused_right = 0, cushion_hits = 0, repeats = 0;
  long long impacts_paper = 0, capped_endless = 0, endless = 0;
  long long ball_scenes = 0, ball_contacts = 0, balls_pocketed = 0;
  size_t most_events = 0, most_balls = 0;
  double max_gain_exact_impact = 0.0, max_gain_paper_impact = 0.0;
  double max_gain_collision = 0.0, max_contact_gap = 0.0, max_overlap = 0.0;
  double max_gain = 0.0, max_seconds = 0.0, total_seconds = 0.0, max_outside = 0.0;
  std::string slowest;

  for (long long i = 0; i < opt.shots; ++i) {
    Case c = draw_case(s);
    if (s.chance(0.05)) spoil(s, &c);
    ++kinds[c.kind.substr(0, c.kind.find(','))];

    const auto t0 = std::chrono::steady_clock::now();
    const ShotResult r = simulate(c.scene, c.cue_ball, c.shot, c.options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total_seconds += seconds;
    if (seconds > max_seconds) {
      max_seconds = seconds;
      slowest = reproducer(c);
    }
    ++statuses[to_string(r.status)];
    if (r.status == ShotStatus::impact_failed || r.status == ShotStatus::collision_failed) {
      const bool pressed = r.message.find("pressed") != std::string::npos;
      const std::string why =
          r.status == ShotStatus::collision_failed
              ? (pressed ? "balls pressed together" : "ball-ball collision failed")
              : (pressed ? "pressed against a cushion"
                         : r.message.substr(r.message.find(':') + 2, 30) + "...");
      const std::string key = why + " (" + c.kind.substr(0, c.kind.find(',')) +
                              (std::hypot(c.shot.topspin_k, c.shot.sidespin_k) <= 1.25
                                   ? ", spin within the miscue limit)"
                                   : ", spin beyond it)");
      if (++failed_impacts[key] == 1 && std::getenv("STRESS_SHOW_FAILED"))
        std::printf("%s: %s\n", key.c_str(), reproducer(c).c_str());
    }

    if (!test::all_finite(r)) {
      ++nonfinite;
      fail.add("non-finite result", reproducer(c));
    }
    if (!c.bad_field.empty()) {
      ++refused;
      if (r.status == ShotStatus::invalid_input && r.error && r.error->field.text() == c.bad_field &&
          r.message.find(c.bad_field) != std::string::npos)
        ++refused_right;
      else
        fail.add("bad input not refused by name",
                 reproducer(c) + " status " + to_string(r.status) + " message '" + r.message + "'");
      continue;
    }
    if (r.status == ShotStatus::invalid_input) {
      fail.add("valid input refused", reproducer(c) + " message '" + r.message + "'");
      continue;
    }

    // The simulation ends, and says how.
    const bool several = r.balls.size() > 1;
    size_t all_events = 0;
    for (const BallOutcome& b : r.balls) all_events += b.events.size();
    most_events = std::max(most_events, all_events);
    most_balls = std::max(most_balls, r.balls.size());
    const size_t cap = static_cast<size_t>(c.options.max_events);
    // With object balls the cap is checked before each event as with one, but the last
    // can be a contact (an event for each of its balls) after two balls came to rest.
    const size_t slack = several ? 4 : 1;
    if (all_events > cap + slack) fail.add("more events than the cap allows", reproducer(c));
    if (r.status == ShotStatus::event_limit &&
        (r.message.empty() || all_events < cap + 1 || all_events > cap + slack))
      fail.add("event_limit without its message or event count", reproducer(c));
    if (c.kind == "endless bouncing") {
      ++endless;
      capped_endless += r.status == ShotStatus::event_limit;
    }
    if (r.events.empty() || r.balls.size() != 1 + c.scene.balls.size()) {
      fail.add("no events, or not every ball", reproducer(c));
      continue;
    }
    // The status and the balls' last events: at rest (or pocketed, for an object ball)
    // when the shot ran out; the obstacle contact that ended it.
    const auto last_of = [](const BallOutcome& b) { return b.events.back().type; };
    const auto settled = [&](bool cue_pocketed) {
      if (last_of(r.balls[0]) != (cue_pocketed ? EventType::pocket : EventType::rest)) return false;
      for (size_t k = 1; k < r.balls.size(); ++k)
        if (!r.balls[k].events.empty() && last_of(r.balls[k]) != EventType::rest &&
            last_of(r.balls[k]) != EventType::pocket)
          return false;
      return true;
    };
    bool obstacle_last = false;
    for (const BallOutcome& b : r.balls)
      obstacle_last = obstacle_last || (!b.events.empty() && last_of(b) == EventType::obstacle);
    const bool consistent =
        (r.status == ShotStatus::rest && settled(false)) ||
        (r.status == ShotStatus::pocketed && settled(true)) ||
        (r.status == ShotStatus::hit_obstacle && obstacle_last) ||
        r.status == ShotStatus::event_limit ||
        (r.status == ShotStatus::impact_failed && r.message.find("cushion") != std::string::npos) ||
        (r.status == ShotStatus::collision_failed && r.message.find("balls ") == 0);
    if (!consistent)
      fail.add("status disagrees with the last events", reproducer(c) + " status " +
                                                            to_string(r.status) + " last " +
                                                            to_string(last_of(r.balls[0])));
    for (const BallOutcome& b : r.balls) {
      int hits = 0;
      for (const ShotEvent& e : b.events) hits += e.type == EventType::cushion;
      if (hits != b.cushion_hits)
        fail.add("cushion count disagrees with the events", reproducer(c));
      cushion_hits += hits;
      if (c.options.impact_method == ImpactMethod::paper) impacts_paper += hits;
      if (b.pocketed) {
        ++balls_pocketed;
        const Pocket& k = c.scene.pockets.at(static_cast<size_t>(b.pocket));
        if (std::hypot(b.final_position.x - k.centre.x, b.final_position.y - k.centre.y) >
            k.radius * (1.0 + 1e-9))
          fail.add("pocketed outside its pocket", reproducer(c) + " ball " + b.name);
      }
    }
    if (r.cushion_hits != r.balls[0].cushion_hits)
      fail.add("the cue ball's cushions disagree with its record", reproducer(c));

    // Energy and the table's edges along every ball's path.
    // The paper's scheme may overshoot the end of an impact by one of its steps, a
    // first-order error that can add energy (the unit tests allow it 1e-3).
    const bool paper = c.options.impact_method == ImpactMethod::paper;
    const double scale = std::max(c.scene.length, c.scene.width);
    std::vector<test::PathAudit> audits;
    for (const BallOutcome& b : r.balls) {
      const test::PathAudit audit = test::audit_path(c.scene, b.events, b.path);
      const std::string who = several ? " ball " + b.name : "";
      max_gain = std::max(max_gain, audit.max_energy_gain);
      (paper ? max_gain_paper_impact : max_gain_exact_impact) = std::max(
          paper ? max_gain_paper_impact : max_gain_exact_impact, audit.max_impact_energy_gain);
      if (!(audit.max_energy_gain <= kEnergySlack))
        fail.add("kinetic energy rose", reproducer(c) + who + " relative gain " +
                                            std::to_string(1e12 * audit.max_energy_gain) +
                                            "e-12 at " + audit.where);
      if (!(audit.max_impact_energy_gain <= (paper ? kPaperEnergySlack : kExactImpactEnergySlack)))
        fail.add("kinetic energy rose in a cushion impact",
                 reproducer(c) + who + " relative gain " +
                     std::to_string(1e12 * audit.max_impact_energy_gain) + "e-12");
      max_outside = std::max(max_outside, audit.max_outside / scale);
      if (!(audit.max_outside <= 1e-12 * scale))
        fail.add("centre past a cushion line",
                 reproducer(c) + who + " by " + std::to_string(audit.max_outside));
      if (!(audit.max_gap <= 1e-9 * scale))
        fail.add("path and events disagree",
                 reproducer(c) + who + " gap " + std::to_string(audit.max_gap));
      if (!audit.times_ordered) fail.add("times go back or do not meet", reproducer(c) + who);
      if (!audit.segments_matched)
        fail.add("a path segment starts at no event", reproducer(c) + who);
      audits.push_back(audit);
    }

    // Ball contacts: 2R apart, and the two balls' energy does not rise across one; no
    // two balls overlap anywhere.
    if (several) {
      ++ball_scenes;
      const test::ContactAudit contacts = test::audit_contacts(c.scene, r, audits);
      ball_contacts += contacts.contacts;
      max_contact_gap = std::max(max_contact_gap, contacts.max_gap);
      max_gain_collision = std::max(max_gain_collision, contacts.max_energy_gain);
      max_overlap = std::max(max_overlap, contacts.max_overlap);
      if (!contacts.paired) fail.add("a contact logged for one ball only", reproducer(c));
      if (!(contacts.max_gap <= kContactSlack))
        fail.add("balls in contact not 2R apart",
                 reproducer(c) + " by " + std::to_string(contacts.max_gap) + " of 2R");
      if (!(contacts.max_energy_gain <= kCollisionEnergySlack))
        fail.add("kinetic energy rose in a ball-ball collision",
                 reproducer(c) + " relative gain " + std::to_string(contacts.max_energy_gain));
      if (!(contacts.max_overlap <= kContactSlack))
        fail.add("two balls overlap",
                 reproducer(c) + " by " + std::to_string(contacts.max_overlap) + " of 2R");
    }

    if (i % 1000 == 0) {
      ++repeats;
      if (!same_events(r, simulate(c.scene, c.cue_ball, c.shot, c.options)))
        fail.add("same input, different result", reproducer(c));
    }
  }

  std::printf("stress_shots: seed %" PRIu64 ", %lld shots\n", opt.seed, opt.shots);
  std::printf("  statuses:");
  for (const auto& [k, n] : statuses) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n  impact_failed and collision_failed:");
  for (const auto& [k, n] : failed_impacts) std::printf("\n    %s: %lld", k.c_str(), n);
  std::printf("\n  scenes:");
  for (const auto& [k, n] : kinds) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n  cushion impacts: %lld (%lld with the paper scheme)\n", cushion_hits,
              impacts_paper);
  std::printf(
      "  endlessly bouncing scenes stopped by the event cap: %lld of %lld; most events "
      "in a shot %zu\n",
      capped_endless, endless, most_events);
  std::printf("  non-finite results: %lld\n", nonfinite);
  std::printf("  bad inputs refused naming the field: %lld of %lld\n", refused_right, refused);
  std::printf("  energy: rises beyond %.0e on the cloth: %lld, largest relative rise %.3e\n",
              kEnergySlack, fail.count["kinetic energy rose"], max_gain);
  std::printf(
      "  energy across cushion impacts: largest relative rise %.3e (exact, allowed %.0e), "
      "%.3e (paper, allowed %.0e); rises beyond that: %lld\n",
      max_gain_exact_impact, kExactImpactEnergySlack, max_gain_paper_impact, kPaperEnergySlack,
      fail.count["kinetic energy rose in a cushion impact"]);
  std::printf("  farthest past a cushion line: %.3e of the table size\n", max_outside);
  std::printf(
      "  object balls: %lld scenes (up to %zu balls), %lld ball contacts, %lld balls pocketed;"
      " contacts off 2R by at most %.3e of 2R; deepest overlap of two balls anywhere %.3e "
      "of 2R inside; energy across collisions: largest relative rise %.3e (allowed %.0e)\n",
      ball_scenes, most_balls, ball_contacts, balls_pocketed, max_contact_gap,
      max_overlap, max_gain_collision, kCollisionEnergySlack);
  std::printf("  time per shot: mean %.2f us, max %.1f us\n",
              1e6 * total_seconds / static_cast<double>(opt.shots), 1e6 * max_seconds);
  std::printf("    slowest: %s\n", slowest.c_str());
  std::printf("  determinism: %lld repeats, %lld differed\n", repeats,
              fail.count["same input, different result"]);
  std::printf("  failed checks: %lld\n", fail.total());
  for (const auto& [what, n] : fail.count)
    if (n > 0) std::printf("    %s: %lld\n", what.c_str(), n);
  for (const std::string& e : fail.examples) std::printf("    %s\n", e.c_str());

  if (!opt.json.empty()) {
    std::ofstream out(opt.json);
    out << "{\"shots\": " << opt.shots << ", \"seed\": " << opt.seed
        << ", \"nonfinite\": " << nonfinite
        << ", \"energy_violations\": " << fail.count["kinetic energy rose"]
        << ", \"max_energy_gain\": " << max_gain << ", \"cushion_impacts\": " << cushion_hits
        << ", \"event_cap_endless\": " << capped_endless << ", \"endless\": " << endless
        << ", \"refused\": " << refused << ", \"refused_by_name\": " << refused_right
        << ", \"ball_scenes\": " << ball_scenes << ", \"ball_contacts\": " << ball_contacts
        << ", \"max_collision_energy_gain\": " << max_gain_collision
        << ", \"max_us\": " << 1e6 * max_seconds << ", \"failed_checks\": " << fail.total()
        << ", \"statuses\": ";
    test::write_counts_json(out, statuses);
    out << "}\n";
    if (!out) {
      std::fprintf(stderr, "stress_shots: could not write %s\n", opt.json.c_str());
      return 1;
    }
  }
  return fail.total() == 0 ? 0 : 1;
}

}  // namespace
}  // namespace cueplan::physics

int main(int argc, char** argv) {
  using cueplan::physics::test::parse_count;
  cueplan::physics::Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    long long n = 0;
    bool ok = value != nullptr;
    if (arg == "--shots" && ok && (ok = parse_count(value, 1, &n))) {
      opt.shots = n;
    } else if (arg == "--seed" && ok && (ok = parse_count(value, 0, &n))) {
      opt.seed = static_cast<uint64_t>(n);
    } else if (arg == "--json" && ok) {
      opt.json = value;
    } else {
      std::fprintf(stderr,
                   "stress_shots: bad argument '%s'; usage: stress_shots [--shots N] [--seed S] "
                   "[--json FILE]\n",
                   arg.c_str());
      return 2;
    }
    ++i;
  }
  return cueplan::physics::run(opt);
}
