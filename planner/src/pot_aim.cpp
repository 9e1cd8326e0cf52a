// The aim that pots, solved as a root, and the pot in a player's terms.
#include "pot_aim.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cueplan/physics/vec2.hpp"
#include "search_space.hpp"
#include "task.hpp"

namespace cueplan::planner::detail {
namespace {

using physics::Vec2;

constexpr double kDeg = 180.0 / std::numbers::pi;
// The aim root stops once the pot's ball's line passes this close (deg, seen from where
// it is struck) to the pocket's centre: a few hundredths of a millimetre a metre away,
// far inside any pocket.
constexpr double kAimTolerance = 0.005;
constexpr int kAimIterations = 8;
constexpr double kMaxAimStep = 2.0;  // deg: a Newton step is never larger
// The search may aim the pot's ball this share of the capture radius either side of the
// pocket's centre: a pot played off-centre leaves the cue ball elsewhere, and its
// position may need it.
constexpr double kPotWindow = 0.6;

using physics::vec2::operator-;
using physics::vec2::cross;
using physics::vec2::dot;
using physics::vec2::norm;
Vec2 unit(Vec2 a) {
  const double n = norm(a);
  return n > 0.0 ? Vec2{a.x / n, a.y / n} : Vec2{1.0, 0.0};
}
Vec2 along(double deg) { return {std::cos(deg / kDeg), std::sin(deg / kDeg)}; }
double angle_of(Vec2 a) { return std::atan2(a.y, a.x) * kDeg; }
// Signed angle (deg) from a to b, in (-180, 180].
double angle_between(Vec2 a, Vec2 b) { return std::atan2(cross(a, b), dot(a, b)) * kDeg; }

// The direction (deg) in which a ball at `from` moving along `dir_deg` sends a ball at
// rest at `at`, struck along their line of centres with no throw; empty when it
// passes by (radius: of the balls).
std::optional<double> struck_direction(Vec2 from, double dir_deg, Vec2 at, double radius) {
  const Vec2 u = along(dir_deg);
  const Vec2 d = at - from;
  const double ahead = dot(d, u);
  const double offset = cross(u, d);  // > 0: the struck ball lies to the left
  if (ahead <= 0.0 || std::abs(offset) >= 2.0 * radius) return std::nullopt;
  const double back = std::sqrt(4.0 * radius * radius - offset * offset);
  const Vec2 contact{from.x + (ahead - back) * u.x, from.y + (ahead - back) * u.y};
  return angle_of(at - contact);
}

// The ball's straight motion after `e`, with its sliding in closed form (PHYSICS.md,
// "Ball on the cloth"): where it crosses the line through `pocket` across `normal`,
// and its velocity there; or, when it rolls before crossing, any point of its rolling
// line and that line's direction. Either way a point and a direction of the line on
// which it meets the pocket.
struct Line {
  Vec2 point, direction;
};
Line line_toward(const physics::Scene& scene, const physics::ShotEvent& e, Vec2 pocket,
                 Vec2 normal) {
  const double g = scene.cloth.gravity, mu = scene.cloth.mu_slide, radius = scene.radius();
  const Vec2 v = e.velocity;
  const Vec2 u{v.x - radius * e.spin.y, v.y + radius * e.spin.x};  // contact point's slip
  const double slip = norm(u);
  if (slip < 1e-12) return {e.position, unit(v)};
  const Vec2 a{-mu * g * u.x / slip, -mu * g * u.y / slip};
  const double t_roll = 2.0 * slip / (7.0 * mu * g);
  // dot(p(t) - pocket, normal) = 0 with p(t) = p0 + v t + a t^2 / 2.
  const double c0 = dot(e.position - pocket, normal), c1 = dot(v, normal),
               c2 = 0.5 * dot(a, normal);
  double t = -1.0;
  if (std::abs(c2) < 1e-15) {
    if (c1 != 0.0) t = -c0 / c1;
  } else {
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc >= 0.0) {
      const double s = std::sqrt(disc);
      const double r1 = (-c1 - s) / (2.0 * c2), r2 = (-c1 + s) / (2.0 * c2);
      const double lo = std::min(r1, r2), hi = std::max(r1, r2);
      t = lo >= 0.0 ? lo : hi;
    }
  }
  const auto at = [&](double s) {
    return Vec2{e.position.x + v.x * s + 0.5 * a.x * s * s, e.position.y + v.y * s + 0.5 * a.y * s * s};
  };
  if (t >= 0.0 && t <= t_roll) return {at(t), unit({v.x + a.x * t, v.y + a.y * t})};
  return {at(t_roll), unit({v.x + a.x * t_roll, v.y + a.y * t_roll})};
}

// The first ball_contact event of ball k, or null.
const physics::ShotEvent* first_contact_of(const physics::BallOutcome& ball) {
  for (const physics::ShotEvent& e : ball.events)
    if (e.type == physics::EventType::ball_contact) return &e;
  return nullptr;
}

}  // namespace

PotAim::PotAim(const problems::Problem& problem) : problem_(problem) {
  const physics::Scene& scene = problem.scene;
  pot_ball_ = problem.pot->ball;
  const physics::Pocket& p = scene.pockets.at(static_cast<size_t>(problem.pot->pocket));
  pocket_ = p.centre;
  capture_ = p.radius;
  const std::string first = problem.required_first_contact();
  const auto centre = [&](const std::string& name) {
    for (size_t i = 0; i < scene.balls.size(); ++i)
      if (scene.balls[i].name == name) return scene.balls[i].position;
    return Vec2{};
  };
  for (size_t i = 0; i < scene.balls.size(); ++i)
    if (scene.balls[i].name == pot_ball_) pot_index_ = static_cast<int>(i) + 1;
  if (first != pot_ball_) chain_.push_back(centre(first));
  chain_.push_back(centre(pot_ball_));
  const Vec2 line = unit(pocket_ - chain_.back());
  across_ = {-line.y, line.x};
  // Ghost balls from the pocket back to the cue ball.
  const double two_r = 2.0 * scene.radius();
  Vec2 aim_point = pocket_;
  for (size_t i = chain_.size(); i-- > 0;) {
    const Vec2 d = unit(aim_point - chain_[i]);
    aim_point = {chain_[i].x - two_r * d.x, chain_[i].y - two_r * d.y};
  }
  ghost_aim_deg_ = wrap_degrees(angle_of(aim_point - problem.cue_ball));
}

std::optional<double> PotAim::geometric_direction(double aim_deg) const {
  const double radius = problem_.scene.radius();
  Vec2 from = problem_.cue_ball;
  double dir = aim_deg;
  for (const Vec2& ball : chain_) {
    const std::optional<double> next = struck_direction(from, dir, ball, radius);
    if (!next) return std::nullopt;
    from = ball;
    dir = *next;
  }
  return dir;
}

double PotAim::lateral_reach() const { return kPotWindow * capture_; }

std::optional<double> PotAim::lateral_of(const physics::ShotResult& result) const {
  if (pot_index_ <= 0 || pot_index_ >= static_cast<int>(result.balls.size())) return std::nullopt;
  const physics::ShotEvent* hit = first_contact_of(result.balls[static_cast<size_t>(pot_index_)]);
  if (hit == nullptr) return std::nullopt;
  const Vec2 to_pocket = pocket_ - hit->position;
  if (!(norm(to_pocket) > 0.0)) return std::nullopt;
  const Line line = line_toward(problem_.scene, *hit, pocket_, unit(to_pocket));
  return -cross(line.direction, pocket_ - line.point);
}

std::optional<double> PotAim::direction_error(const physics::ShotResult& result,
                                              double* margin_m, double lateral_m) const {
  if (pot_index_ <= 0 || pot_index_ >= static_cast<int>(result.balls.size())) return std::nullopt;
  const physics::ShotEvent* hit = first_contact_of(result.balls[static_cast<size_t>(pot_index_)]);
  if (hit == nullptr) return std::nullopt;
  const Vec2 to_pocket = pocket_ - hit->position;
  const double distance = norm(to_pocket);
  if (!(distance > 0.0)) return std::nullopt;
  const Line line = line_toward(problem_.scene, *hit, pocket_, unit(to_pocket));
  // Where the pocket's centre lies from the ball's line: > 0 to its left.
  const double lateral = cross(line.direction, pocket_ - line.point);
  if (margin_m) *margin_m = capture_ - std::abs(lateral);
  // The point aimed at, `lateral_m` across the pocket.
  const Vec2 aim_point{pocket_.x + lateral_m * across_.x, pocket_.y + lateral_m * across_.y};
  const Vec2 to_aim = aim_point - hit->position;
  if (dot(line.direction, to_aim) <= 0.0)
    return angle_between(unit(line.point - hit->position), to_aim);
  const double off = cross(line.direction, aim_point - line.point);
  return std::asin(std::clamp(off / norm(to_aim), -1.0, 1.0)) * kDeg;
}

double squirt_of(const problems::Problem& problem, const physics::Shot& shot) {
  const physics::Scene& scene = problem.scene;
  return physics::squirt_angle_deg(scene.cue, scene.ball_and_cushion.mass, scene.radius(),
                                   shot.sidespin_k);
}

PotAim::Aimed PotAim::aim(const Task& task, const physics::Shot& shot,
                          const physics::SimulationOptions& simulation,
                          double offset_hint_deg, double lateral_m) const {
  Aimed out;
  const auto play = [&](double aim_deg) {
    physics::Shot s = shot;
    s.aim_deg = wrap_degrees(aim_deg);
    out.shot = s;
    out.result = task.simulate(s, simulation);
    ++out.simulations;
    return direction_error(out.result, nullptr, lateral_m);
  };
  // The cue's line is turned from the ball's by the squirt: start that much the other way.
  const double squirt = squirt_of(task.problem, shot);
  // The geometric slope of the pot's ball's direction in the aim (deg per deg), taken
  // where the cue ball goes: the cue's aim turned by the squirt.
  const auto gain = [&](double aim_deg) {
    constexpr double h = 1e-4;
    const std::optional<double> a = geometric_direction(aim_deg + squirt - h);
    const std::optional<double> b = geometric_direction(aim_deg + squirt + h);
    if (!a || !b) return 0.0;
    return wrap_degrees(*b - *a) / (2.0 * h);
  };
  double x = ghost_aim_deg_ + offset_hint_deg - squirt;
  std::optional<double> e = play(x);
  if (!e && offset_hint_deg != 0.0) {
    x = ghost_aim_deg_ - squirt;
    e = play(x);
  }
  if (!e) return out;
  // A bracket [lo, hi] in aim once the error has changed sign.
  std::optional<std::pair<double, double>> lo, hi;  // (aim, error)
  for (int i = 0; i < kAimIterations; ++i) {
    if (std::abs(*e) <= kAimTolerance) {
      out.found = true;
      return out;
    }
    // The error falls as the pot's ball's direction rises toward the pocket.
    (*e > 0.0 ? lo : hi) = std::make_pair(x, *e);
    double next;
    if (lo && hi) {
      // Regula falsi on the bracket: the error is smooth in the aim near the root.
      const double e_lo = lo->second, e_hi = hi->second;
      next = lo->first + (hi->first - lo->first) * e_lo / (e_lo - e_hi);
    } else {
      const double slope = gain(x);
      if (slope == 0.0) return out;
      next = x + std::clamp(*e / slope, -kMaxAimStep, kMaxAimStep);
    }
    std::optional<double> e_next = play(next);
    if (!e_next) {
      // Past the edge of the object ball: come back halfway.
      next = 0.5 * (x + next);
      e_next = play(next);
      if (!e_next) return out;
    }
    x = next;
    e = e_next;
  }
  out.found = std::abs(*e) <= kAimTolerance;
  return out;
}

const char* thickness_of(double cut_deg) {
  const double covered = 1.0 - std::sin(std::abs(cut_deg) / kDeg);
  if (covered >= 0.875) return "full";
  if (covered >= 0.625) return "3/4";
  if (covered >= 0.375) return "half";
  if (covered >= 0.125) return "1/4";
  return "thin";
}

PotReport pot_report(const Task& task, const PotAim& aim, const physics::Shot& shot,
                     const physics::ShotResult& result,
                     const physics::SimulationOptions& simulation, int* simulations) {
  const problems::Problem& problem = task.problem;
  PotReport p;
  p.ball = problem.pot->ball;
  p.pocket = problem.pot->pocket;
  p.pocket_name = problems::pocket_name(problem.scene, p.pocket);
  p.ghost_aim_deg = aim.ghost_aim_deg();
  p.aim_allowance_deg = wrap_degrees(shot.aim_deg - aim.ghost_aim_deg());
  const auto drops = [&](const physics::ShotResult& r) {
    for (const physics::BallOutcome& b : r.balls)
      if (b.name == p.ball) return b.pocketed && b.pocket == p.pocket;
    return false;
  };
  p.made = drops(result);
  double margin = 0.0;
  if (aim.direction_error(result, &margin)) p.margin_m = margin;
  // A jawed pocket: the ball's straight line from where it was struck against the
  // points' contact circles.
  const auto& jaws = problem.scene.pockets[static_cast<size_t>(p.pocket)].jaws;
  for (size_t k = 1; jaws && k < result.balls.size(); ++k) {
    if (result.balls[k].name != p.ball) continue;
    const physics::ShotEvent* hit = first_contact_of(result.balls[k]);
    if (hit == nullptr || !(norm(hit->velocity) > 0.0)) break;
    const Vec2 d = unit(hit->velocity);
    const double reach = jaws->shape.point_radius + problem.scene.contact_offset();
    for (int side = 0; side < 2; ++side) {
      const double clear = std::abs(cross(d, jaws->point_centre[side] - hit->position)) - reach;
      if (!p.jaw_clearance_m || clear < *p.jaw_clearance_m) {
        p.jaw_clearance_m = clear;
        p.near_jaw = side == 0 ? "left" : "right";
      }
    }
    break;
  }
  // Cut and throw at the collision that set the pot's ball moving.
  for (size_t k = 1; k < result.balls.size(); ++k) {
    if (result.balls[k].name != p.ball) continue;
    const physics::ShotEvent* hit = first_contact_of(result.balls[k]);
    if (hit == nullptr || hit->other < 0) break;
    const physics::BallOutcome& striker = result.balls[static_cast<size_t>(hit->other)];
    p.striker = striker.name;
    for (size_t i = 1; i < striker.events.size(); ++i) {
      const physics::ShotEvent& e = striker.events[i];
      if (e.type != physics::EventType::ball_contact || e.other != static_cast<int>(k) ||
          e.time != hit->time)
        continue;
      const Vec2 incoming = unit(striker.events[i - 1].velocity);
      const Vec2 centres = unit(hit->position - e.position);
      const double cut = angle_between(incoming, centres);
      p.cut_deg = std::abs(cut);
      p.cut_side = cut > 0.0 ? 1 : cut < 0.0 ? -1 : 0;
      p.thickness = thickness_of(p.cut_deg);
      p.throw_deg = angle_between(centres, unit(hit->velocity));
      break;
    }
    break;
  }
  // The aim error that would miss: the least change of aim, either way, at which the
  // ball no longer drops in its pocket (bracketed by doubling, then bisected).
  if (p.made) {
    physics::SimulationOptions quiet = simulation;
    quiet.record_path = false;
    const auto pots_at = [&](double delta) {
      physics::Shot s = shot;
      s.aim_deg = shot.aim_deg + delta;
      ++*simulations;
      return drops(task.simulate(s, quiet));
    };
    double least = std::numeric_limits<double>::infinity();
    for (double side : {-1.0, 1.0}) {
      double in = 0.0, out = 1e-3;
      while (out < 10.0 && pots_at(side * out)) {
        in = out;
        out *= 2.0;
      }
      if (out >= 10.0) continue;
      for (int i = 0; i < 14; ++i) {
        const double mid = 0.5 * (in + out);
        (pots_at(side * mid) ? in : out) = mid;
      }
      least = std::min(least, in);
    }
    p.aim_margin_deg = std::isfinite(least) ? least : 10.0;
  }
  return p;
}

}  // namespace cueplan::planner::detail
