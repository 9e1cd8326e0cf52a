// The shot simulator: every ball from the strike to rest, event by event
// (PHYSICS.md, "Several balls on the table").
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "ball_motion.hpp"
#include "cueplan/physics/shot.hpp"
#include "impact_methods.hpp"
#include "scene_geometry.hpp"

namespace cueplan::physics {
namespace {

using detail::along_cushion;
using detail::Ball;
using detail::CushionGaps;
using detail::CushionLine;
using detail::Gap;
using detail::JawPart;
using detail::Jaws;
using detail::ClothModel;
using detail::dot;
using detail::kNever;
using detail::Piece;
using detail::Quadratic;
using detail::operator+;
using detail::operator-;
using detail::operator*;
// An approach speed below this fraction of the ball's speed at a cushion that the cloth's
// friction presses it into is the end of a run of ever smaller bounces: the ball is
// pressed against the cushion.
constexpr double kRoundingApproach = 1e-12;

constexpr double kDegree = std::numbers::pi / 180.0;
// Events this close in time (s) are taken in the contract's fixed order.
constexpr double kTie = 1e-12;
// Balls pressed together that would roll on less than this (m) are put at rest.
constexpr double kSettleDistance = 1e-6;
// m: how far past a jaw's contact a ball's centre may be found by rounding; a ball
// further from a jawed pocket's parts than this touches none of them.
constexpr double kJawSlack = 1e-3;

// The contract's order of event kinds within kTie of each other: ball-ball, cushion,
// pocket, obstacle contact, motion change.
int rank(EventType type) {
  switch (type) {
    case EventType::ball_contact: return 0;
    case EventType::cushion: return 1;
    case EventType::jaw: return 1;  // a jaw contact is a cushion contact
    case EventType::pocket: return 2;
    case EventType::obstacle: return 3;
    default: return 4;
  }
}

// Event codes of jaw contacts (NextEvent::which, Next::other): after the four cushions,
// four parts per pocket, so that a cushion ranks before a jaw at the same instant.
constexpr int kFirstJaw = 4;
int jaw_code(int pocket, int part) { return kFirstJaw + 4 * pocket + part; }
int jaw_pocket(int code) { return (code - kFirstJaw) / 4; }
int jaw_part(int code) { return (code - kFirstJaw) % 4; }

// The stroke's own inputs, checked on every call (the scene was checked when compiled).
Validation check_stroke(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                        const SimulationOptions& options) {
  if (Validation e = scene.check_position(cue_ball, {"cue_ball"})) return e;
  if (Validation e = shot.validate()) return e->under({"shot"});
  if (options.max_events < 1)
    return invalid({"max_events"}, "must be at least 1", options.max_events);
  if (!(options.max_time > 0.0))
    return invalid({"max_time"}, "must be positive", options.max_time);
  return {};
}

// What ends a ball's current piece of motion, and when.
struct NextEvent {
  EventType type = EventType::rest;
  double after = kNever;  // s from the start of the piece
  int which = -1;         // cushion, pocket or obstacle index
};

// One ball during the shot. Its state is kept at the start of its current piece of
// motion; where it is later follows in closed form, so a ball that no event touches is
// never stepped.
struct BallRun {
  Ball b;           // state at t0
  double t0 = 0.0;  // s, when its current piece started
  Piece piece;
  NextEvent own;  // its next event of its own (after: from t0)
  bool on_table = true;
  bool moving = false;          // its piece is not resting
  bool changed = false;         // an event changed its state: piece and events to find again
  bool check_cushions = false;  // whether a cushion lies within its reach

  double own_time() const { return moving ? t0 + own.after : kNever; }
  // Its path about the instant `t`, within its current piece.
  Quadratic path_at(double t) const {
    if (!moving) return {b.p, {0.0, 0.0}, {0.0, 0.0}};
    const double s = t - t0;
    return {b.p + s * b.v + (0.5 * s * s) * piece.accel, b.v + s * piece.accel, 0.5 * piece.accel};
  }
};

// When two balls next touch while approaching, found when either last changed.
struct PairContact {
  double time = kNever;   // s since the strike
  double from = 0.0;      // s, the instant both paths were taken about
  double root = 0.0;      // time - from
  double horizon = 0.0;   // s after `from` that the search covered
  bool touching = false;  // they touched already when they began to approach
  double parts = kNever;  // s after `from`: where the paths part again after `root`
};

// The next event of the shot.
struct Next {
  EventType type = EventType::rest;
  double time = kNever;  // s since the strike
  int ball = -1;         // whose (the lower index for a ball-ball contact)
  int other = -1;        // the other ball of a contact; else the cushion, pocket or obstacle
  bool pressed = false;  // balls that touch with no approach speed left, pressed together
};

// True when `a` goes before `b` among events within kTie of each other.
bool earlier_in_order(const Next& a, const Next& b) {
  if (rank(a.type) != rank(b.type)) return rank(a.type) < rank(b.type);
  if (a.ball != b.ball) return a.ball < b.ball;
  return a.other < b.other;
}

// One shot from the strike until every ball rests, as stages run in order for every
// event of the shot:
//   1. find_next_event - balls the last event changed get their new piece of motion,
//                        own next event (slide to roll, rest, sidespin stop, cushion,
//                        pocket, obstacle) and next contacts with the other balls; then
//                        the earliest event of all, ties in the contract's order;
//   2. advance         - the shot's clock moves to that event, and the balls it involves
//                        move along their pieces to it (paths recorded); every other
//                        ball's piece runs on unchanged;
//   3. resolve         - the event changes the balls' states (a cushion through the
//                        impact model, a contact through the collision model) and is
//                        logged; an obstacle contact or a failure ends the shot.
class ShotRun {
 public:
  ShotRun(const CompiledScene& compiled, const SimulationOptions& options, ShotResult* result)
      : scene_(compiled.scene()),
        options_(options),
        cloth_(scene_),
        lines_(compiled.geometry().lines),
        gaps_(compiled.geometry().gaps),
        jaws_(compiled.geometry().jaws),
        ball_ball_(compiled.ball_ball_params()),
        result_(result) {
    // The cheapest impact method that meets the accuracy asked for: the table where its
    // measured error does, else an exact method at a tolerance that does. Over the
    // uniform domain `exact` (also the table's fallback) errs by at most about 5
    // tolerances, `extrapolation` by about 100 (bench/README.md): a tenth and a
    // hundredth of the accuracy. The collisions' error stays below 100 tolerances.
    impact_.method = chosen_impact_method(scene_, options);
    const double tolerances = impact_.method == ImpactMethod::extrapolation ? 100.0 : 10.0;
    impact_.tolerance = std::clamp(options.impact_accuracy / tolerances, 1e-14, 1e-3);
    const double tolerance = std::clamp(options.impact_accuracy / 100.0, 1e-14, 1e-3);
    if (impact_.method == ImpactMethod::table) {
      impact_.table = options.table;
      impact_.table_fallback_tolerance = impact_.tolerance;  // the accuracy asked for, as above
    }
    collision_.tolerance = tolerance;
    result_->impact_method = impact_.method;
    // Every cushion contact of the shot shares the parameters and these options: they
    // are checked here, once, not on every impact.
    impact_error_ = detail::check_impact_inputs(scene_.ball_and_cushion, impact_);
  }

  // Cue strike: speed along the aim turned by the squirt, topspin about the horizontal
  // axis perpendicular to the motion (natural-roll sense), sidespin about z, and with an
  // elevated cue the swerve spin about the line of motion. The object balls lie at rest.
  void strike(Vec2 cue_ball, const Shot& shot) {
    const size_t n = 1 + scene_.balls.size();
    runs_.resize(n);
    result_->balls.resize(n);
    result_->balls[0].name = kCueBallName;
    result_->balls[0].start = cue_ball;
    for (size_t k = 1; k < n; ++k) {
      runs_[k].b.p = scene_.balls[k - 1].position;
      result_->balls[k].name = scene_.balls[k - 1].name;
      result_->balls[k].start = scene_.balls[k - 1].position;
    }
    if (n > 1) pairs_.resize(n * (n - 1) / 2);

    // The cue ball leaves at the squirt angle off the cue's line: to the left of it
    // (counter-clockwise) for right side. The spins are taken about its actual motion.
    const double squirt = squirt_angle_deg(scene_.cue, scene_.ball_and_cushion.mass,
                                           cloth_.radius, shot.sidespin_k);
    const double phi = (shot.aim_deg + squirt) * kDegree;
    const Vec2 along{std::cos(phi), std::sin(phi)};
    Ball& b = runs_[0].b;
    b.p = cue_ball;
    b.v = {shot.speed * along.x, shot.speed * along.y};
    const double wt = shot.topspin_k * shot.speed / cloth_.radius;
    const double ws = shot.sidespin_k * shot.speed / cloth_.radius;
    // Swerve. In the frame (x along the motion, y to its left, z up) an elevated cue
    // pushes with impulse J (cos e, 0, -sin e) through a point of its line at r =
    // (0, -d, c): d is the tip offset to the right (d > 0 for right side), c its
    // height. The angular impulse r x J = J (d sin e, c cos e, d cos e) gives the ball
    // w_z = d cos e J / I and w_par = d sin e J / I about its line of motion; the
    // horizontal speed is V = J cos e / m (the vertical part goes into the cloth; the
    // jump is ignored). So w_z R / V = (5/2) d / R = k_S keeps its meaning and
    // w_par = w_z tan e = k_S (V / R) tan e. That spin makes the contact point slip
    // sideways, u_y = R w_par, and the cloth's friction, against the slip, curves the
    // sliding ball to the right for right side until it rolls.
    const double wpar = shot.elevation_deg > 0.0 ? ws * std::tan(shot.elevation_deg * kDegree) : 0.0;
    b.w = {-wt * along.y + wpar * along.x, wt * along.x + wpar * along.y, ws};
    log(0, EventType::strike);
    runs_[0].changed = true;
    runs_[0].check_cushions = cushions_in_reach(b);
    result_->status = ShotStatus::rest;
  }

  // Runs the stages until every ball rests or the shot ends otherwise.
  void run() {
    while (!over_ && anything_left()) {
      if (events_ > options_.max_events) {
        end_shot(ShotStatus::event_limit,
                 fmt::format("more than {} events before the {} came to rest", options_.max_events,
                             runs_.size() == 1 ? "ball" : "balls"));
        break;
      }
      const Next next = find_next_event();
      if (next.time == kNever) break;
      if (next.time > options_.max_time) {
        // finish() brings every moving ball to the horizon.
        t_ = options_.max_time;
        end_shot(ShotStatus::time_limit,
                 fmt::format("followed to {} s (max_time), balls still moving", options_.max_time));
        break;
      }
      advance(next);
      resolve(next);
    }
    finish();
  }

 private:
  // ---- Stage 1 -------------------------------------------------------------------

  Next find_next_event() {
    refresh_changed_balls();
    for (;;) {
      const Next next = earliest();
      if (next.type != EventType::ball_contact) return next;
      // The contact's balls must approach along their line of centres where they meet,
      // as the collision model asks. A graze that rounding makes a parting is no
      // contact, and the pair's next contact after the graze is looked for; but balls
      // that touch and that their paths press together with no approach speed left are
      // a push, which is not modelled (like a ball pressed into a cushion).
      if (approaching(next)) return next;
      PairContact& pair = pair_of(next.ball, next.other);
      if (pair.touching || pair.parts == kNever) {
        // Touching already, or crossing into 2R without parting again within their
        // pieces: pressed together.
        Next pressed = next;
        pressed.pressed = true;
        return pressed;
      }
      search_pair(next.ball, next.other, pair.parts);
    }
  }

  // New pieces, own events and pair contacts for the balls the last event changed.
  void refresh_changed_balls() {
    bool any = false;
    for (size_t k = 0; k < runs_.size(); ++k) {
      BallRun& r = runs_[k];
      if (!r.changed || !r.on_table) continue;
      any = true;
      r.piece = detail::piece_from(cloth_, r.b);
      r.moving = r.piece.motion != Motion::resting;
      if (!r.moving) {
        r.b.v = {0.0, 0.0};
        log(static_cast<int>(k), EventType::rest);
      } else {
        r.own = own_event(r);
      }
    }
    if (any && !pairs_.empty()) {
      for (size_t i = 0; i < runs_.size(); ++i)
        for (size_t j = i + 1; j < runs_.size(); ++j)
          if (runs_[i].changed || runs_[j].changed)
            search_pair(static_cast<int>(i), static_cast<int>(j), -1.0);
    }
    for (BallRun& r : runs_) r.changed = false;
  }

  // A ball's own next event: the piece's end (slide to roll, rest), the sidespin stop,
  // then the first contact before either (cushion, pocket, obstacle).
  NextEvent own_event(const BallRun& r) const {
    const Ball& b = r.b;
    const Piece& piece = r.piece;
    NextEvent next;
    next.after = piece.duration;
    next.type = piece.motion == Motion::sliding ? EventType::slide_to_roll : EventType::rest;
    const double spin_stop = b.w.z != 0.0 ? std::abs(b.w.z) / cloth_.spin_decel : kNever;
    if (spin_stop < next.after) {
      next.after = spin_stop;
      next.type = EventType::spin_stop;
    }
    const Quadratic q{b.p, b.v, 0.5 * piece.accel};
    if (r.check_cushions) {
      for (int i = 0; i < 4; ++i) {
        const double hit = cushion_contact(q, i, next.after);
        if (hit < next.after) next = {EventType::cushion, hit, i};
      }
    }
    if (!jaws_.empty()) {
      // The path's box over the horizon so far rules out most pockets and parts cheaply.
      const detail::Box path = detail::box_of(q, next.after);
      for (const Jaws& w : jaws_) {
        if (!boxes_meet(path, w.box)) continue;
        for (int part = 0; part < 4; ++part) {
          if (!boxes_meet(path, w.part_box[part])) continue;
          const double hit = jaw_contact(q, w, part, next.after);
          if (hit < next.after) next = {EventType::jaw, hit, jaw_code(w.pocket, part)};
        }
      }
    }
    for (size_t i = 0; i < scene_.pockets.size(); ++i) {
      const auto [centre, radius] = capture_circle(i);
      const double hit = detail::entry_time(q, next.after, centre, radius);
      if (hit < next.after) next = {EventType::pocket, hit, static_cast<int>(i)};
    }
    for (size_t i = 0; i < scene_.obstacles.size(); ++i) {
      const double hit =
          detail::entry_time(q, next.after, scene_.obstacles[i], 2.0 * cloth_.radius);
      if (hit < next.after) next = {EventType::obstacle, hit, static_cast<int>(i)};
    }
    return settle_ties(r, q, next);
  }

  // The contract's order among a ball's events within kTie of each other: a contact of
  // an earlier kind (or of the same kind with a lower index) that begins within kTie
  // after the event found comes first, at the time of the event found. Each search above is bounded
  // by the earliest event found before it, so such a contact is looked for here: where the ball is
  // at the window's end says cheaply whether one can exist, and only then is it solved.
  NextEvent settle_ties(const BallRun& r, const Quadratic& q, const NextEvent& found) const {
    if (!(found.after < kNever)) return found;
    const double end = found.after + kTie;
    const Vec2 p = q.a0 + end * q.a1 + (end * end) * q.a2;
    NextEvent best = found;
    const auto before_best = [&](EventType type, int which) {
      return rank(type) != rank(best.type) ? rank(type) < rank(best.type) : which < best.which;
    };
    // Events of one window are taken as simultaneous, at the first one's time: a ball is
    // never carried past a contact it meets first (the cushion it then resolves puts it
    // on its line).
    const auto consider = [&](EventType type, double hit, int which) {
      if (hit <= end && before_best(type, which)) best = {type, found.after, which};
    };
    if (r.check_cushions) {
      for (int i = 0; i < 4; ++i)
        if (before_best(EventType::cushion, i) && dot(lines_[i].normal, p) >= lines_[i].contact)
          consider(EventType::cushion, cushion_contact(q, i, end), i);
    }
    for (const Jaws& w : jaws_) {
      // A ball that has not been carried into a jaw's rubber touches its parts only
      // within their boxes (kJawSlack allows for rounding past a contact).
      if (p.x < w.box.xlo - kJawSlack || p.x > w.box.xhi + kJawSlack ||
          p.y < w.box.ylo - kJawSlack || p.y > w.box.yhi + kJawSlack)
        continue;
      for (int part = 0; part < 4; ++part) {
        const int code = jaw_code(w.pocket, part);
        if (before_best(EventType::jaw, code) && jaw_touched(w, part, p))
          consider(EventType::jaw, jaw_contact(q, w, part, end), code);
      }
    }
    for (size_t i = 0; i < scene_.pockets.size(); ++i) {
      const auto [centre, radius] = capture_circle(i);
      const Vec2 d = p - centre;
      if (before_best(EventType::pocket, static_cast<int>(i)) && dot(d, d) < radius * radius)
        consider(EventType::pocket, detail::entry_time(q, end, centre, radius),
                 static_cast<int>(i));
    }
    const double reach = 2.0 * cloth_.radius;
    for (size_t i = 0; i < scene_.obstacles.size(); ++i) {
      const Vec2 d = p - scene_.obstacles[i];
      if (before_best(EventType::obstacle, static_cast<int>(i)) && dot(d, d) < reach * reach)
        consider(EventType::obstacle, detail::entry_time(q, end, scene_.obstacles[i], reach),
                 static_cast<int>(i));
    }
    return best;
  }

  // When within `horizon` the centre meets cushion i moving in; kNever if it does not.
  double cushion_contact(const Quadratic& q, int i, double horizon) const {
    const Vec2 n = lines_[i].normal;
    // n . p(t) - contact, negative on the table; contact when it rises to zero.
    double c[3] = {dot(n, q.a0) - lines_[i].contact, dot(n, q.a1), dot(n, q.a2)};
    const std::vector<Gap>& gaps = gaps_[static_cast<size_t>(i)];
    // Past the line in a pocket's mouth: the jaws, not this cushion, meet the ball there.
    const bool in_mouth = !gaps.empty() && c[0] >= 0.0 && in_gap(i, q.a0);
    if (c[0] >= 0.0 && !in_mouth) {
      // Touching (or rounding past): on the line, so that a ball leaving the cushion
      // is caught when friction on the cloth brings it back.
      c[0] = 0.0;
    }
    if (c[0] == 0.0 && (c[1] > 0.0 || (c[1] == 0.0 && c[2] > 0.0)))
      return gaps.empty() || !in_gap(i, q.a0) ? 0.0 : kNever;  // touching and moving in, or
                                                              // at rest across it and pressed in
    double roots[2];
    const int n_roots = detail::roots_in(c, 2, 0.0, horizon, roots);
    for (int k = 0; k < n_roots; ++k)
      if (c[1] + 2.0 * c[2] * roots[k] > 0.0) {
        if (gaps.empty()) return roots[k];
        const double t = roots[k];
        return in_gap(i, q.a0 + t * q.a1 + (t * t) * q.a2) ? kNever : roots[k];
      }
    return kNever;
  }

  // Whether the point p lies, along cushion i, in a pocket's mouth.
  bool in_gap(int i, Vec2 p) const {
    const double x = along_cushion(i, p);
    for (const Gap& g : gaps_[static_cast<size_t>(i)])
      if (x > g.lo && x < g.hi) return true;
    return false;
  }

  // Where a ball is pocketed: the capture circle, or a jawed pocket's hole.
  std::pair<Vec2, double> capture_circle(size_t i) const {
    const Pocket& k = scene_.pockets[i];
    if (k.jaws) return {k.jaws->hole_centre, k.jaws->shape.hole_radius};
    return {k.centre, k.radius};
  }

  static bool boxes_meet(const detail::Box& p, const detail::Box& b) {
    return !(p.xhi < b.xlo || p.xlo > b.xhi || p.yhi < b.ylo || p.ylo > b.yhi);
  }

  // Part 0 left point, 1 left facing, 2 right facing, 3 right point.
  static int jaw_side(int part) { return part < 2 ? 0 : 1; }
  static bool is_point(int part) { return part == 0 || part == 3; }

  // Whether the centre at p is at or past the part's contact (inside a point's circle,
  // or past a facing's line along its length).
  bool jaw_touched(const Jaws& w, int part, Vec2 p) const {
    const int side = jaw_side(part);
    if (is_point(part)) {
      const Vec2 d = p - w.point[side];
      return dot(d, d) < w.point_reach * w.point_reach;
    }
    const JawPart& f = w.facing[side];
    const double s = dot(f.dir, p - f.start);
    return s >= 0.0 && s <= f.length && dot(f.normal, p) >= f.contact;
  }

  // When within `horizon` the centre meets a jaw's part moving in; kNever if it does not.
  double jaw_contact(const Quadratic& q, const Jaws& w, int part, double horizon) const {
    const int side = jaw_side(part);
    if (is_point(part)) {
      // A path that passes the circle by more than its radius never meets it: no quartic
      // to solve. The path p(t) = a0 + a1 t + a2 t^2 strays from its tangent line at a0 by
      // |a1 x a2| t^2 / |a1| at most, so it misses when the line misses by more than the
      // radius and that stray over the horizon (a straight path - rolling, or sliding
      // with the slip along the motion - strays by nothing).
      const double speed = vec2::length(q.a1.x, q.a1.y);
      if (speed > 0.0) {
        const double bend = q.a1.x * q.a2.y - q.a1.y * q.a2.x;
        const bool straight = std::abs(bend) <= 1e-12 * speed * vec2::length(q.a2.x, q.a2.y);
        const double stray = straight ? 0.0 : std::abs(bend) / speed * horizon * horizon;
        const Vec2 r = q.a0 - w.point[side];
        const double miss = std::abs(q.a1.x * r.y - q.a1.y * r.x) / speed;
        if (miss - stray > w.point_reach * (1.0 + 1e-9)) return kNever;
      }
      // |p(t) - P|^2 - reach^2, a quartic: contact where it falls through zero.
      double c[5];
      detail::distance_quartic(q.a0 - w.point[side], q.a1, q.a2, w.point_reach, c);
      if (c[0] <= 0.0) {
        if (c[1] < 0.0) return 0.0;  // touching (or a rounding inside) and moving in
        c[0] = 0.0;
      }
      double roots[detail::kMaxDegree];
      const int n = detail::roots_in(c, 4, 0.0, horizon, roots);
      for (int k = 0; k < n; ++k) {
        const double t = roots[k];
        const double slope = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * 4.0 * c[4]));
        if (t > 0.0 && slope < 0.0) return t;
      }
      return kNever;
    }
    const JawPart& f = w.facing[side];
    double c[3] = {dot(f.normal, q.a0) - f.contact, dot(f.normal, q.a1), dot(f.normal, q.a2)};
    const auto on_facing = [&](double t) {
      const double s = dot(f.dir, q.a0 + t * q.a1 + (t * t) * q.a2 - f.start);
      return s >= 0.0 && s <= f.length;
    };
    if (c[0] >= 0.0 && on_facing(0.0)) {
      c[0] = 0.0;  // touching (or rounding past), as at a cushion
      if (c[1] > 0.0 || (c[1] == 0.0 && c[2] > 0.0)) return 0.0;
    }
    double roots[2];
    const int n = detail::roots_in(c, 2, 0.0, horizon, roots);
    for (int k = 0; k < n; ++k)
      if (c[1] + 2.0 * c[2] * roots[k] > 0.0 && on_facing(roots[k])) return roots[k];
    return kNever;
  }

  // The next contact of balls i < j within both pieces (and kTie beyond the earlier
  // end), after `after` s from the instant the pair was last searched about (< 0: a
  // fresh search from now). Pairs off the table or with neither ball moving never meet.
  void search_pair(int i, int j, double after) {
    PairContact& pair = pair_of(i, j);
    const BallRun& a = runs_[static_cast<size_t>(i)];
    const BallRun& b = runs_[static_cast<size_t>(j)];
    if (!a.on_table || !b.on_table || !(a.moving || b.moving)) {
      pair = PairContact{};
      return;
    }
    if (after < 0.0) {
      pair.from = t_;
      pair.horizon = std::min(a.own_time(), b.own_time()) - t_ + kTie;
    }
    const detail::Meeting contact = detail::contact_time(a.path_at(pair.from), b.path_at(pair.from),
                                                         pair.horizon, 2.0 * cloth_.radius, after);
    pair.root = contact.time;
    pair.touching = contact.touching;
    pair.parts = contact.parts;
    pair.time = contact.time < kNever ? pair.from + contact.time : kNever;
  }

  // The earliest event of all; of those within kTie of it, the contract's order decides
  // which contact comes first, resolved at the first one's time.
  Next earliest() const {
    double first = kNever;
    for (const BallRun& r : runs_)
      if (r.on_table) first = std::min(first, r.own_time());
    for (const PairContact& p : pairs_) first = std::min(first, p.time);
    Next best, soonest;
    if (first == kNever) return best;
    const double window = first + kTie;
    const auto consider = [&](const Next& c) {
      if (c.time <= window && (best.time == kNever || earlier_in_order(c, best))) best = c;
      if (c.time < soonest.time) soonest = c;
    };
    for (size_t k = 0; k < runs_.size(); ++k) {
      const BallRun& r = runs_[k];
      if (r.on_table && r.moving)
        consider({r.own.type, r.own_time(), static_cast<int>(k), r.own.which});
    }
    if (!pairs_.empty()) {
      for (size_t i = 0; i < runs_.size(); ++i)
        for (size_t j = i + 1; j < runs_.size(); ++j) {
          const PairContact& p = pair_of(static_cast<int>(i), static_cast<int>(j));
          if (p.time < kNever)
            consider({EventType::ball_contact, p.time, static_cast<int>(i), static_cast<int>(j)});
        }
    }
    // When the window holds no contact, only motion changes, which leave other balls
    // alone whatever their order: each at its own time (one resolved early would set a
    // ball rolling before its slip is spent).
    if (rank(best.type) == rank(EventType::rest)) return soonest;
    best.time = first;  // the window's contacts are simultaneous, at its first time
    return best;
  }

  // Whether the balls of a contact approach along their line of centres at its time: the
  // collision model's own test (ball_collision.hpp), on the same numbers.
  bool approaching(const Next& next) const {
    const Ball a = state_at(next.ball, next.time), b = state_at(next.other, next.time);
    const Vec2 d = b.p - a.p;
    const double distance = vec2::length(d.x, d.y);
    if (!(distance > 0.0)) return false;
    const Vec2 n{d.x / distance, d.y / distance};
    return dot(a.v, n) > dot(b.v, n);
  }

  // Ball k's state at `t` along its piece, leaving it where it is.
  Ball state_at(int k, double t) const {
    const BallRun& r = runs_[static_cast<size_t>(k)];
    Ball b = r.b;
    detail::advance(cloth_, r.piece, t - r.t0, &b);
    return b;
  }

  // ---- Stage 2 -------------------------------------------------------------------

  void advance(const Next& next) {
    t_ = next.time;
    if (next.type == EventType::ball_contact) {
      bring(next.ball, next.time - runs_[static_cast<size_t>(next.ball)].t0);
      bring(next.other, next.time - runs_[static_cast<size_t>(next.other)].t0);
    } else {
      const BallRun& r = runs_[static_cast<size_t>(next.ball)];
      bring(next.ball, next.time == r.own_time() ? r.own.after : next.time - r.t0);
    }
  }

  // Ball k moved `dt` along its piece to the shot's clock (its path recorded).
  void bring(int k, double dt) {
    BallRun& r = runs_[static_cast<size_t>(k)];
    if (options_.record_path && dt > 0.0 && r.moving)
      path_of(k).push_back({r.t0, t_, r.b.p, r.b.v, r.piece.accel, r.piece.motion});
    detail::advance(cloth_, r.piece, dt, &r.b);
    r.t0 = t_;
  }

  // ---- Stage 3 -------------------------------------------------------------------

  void resolve(const Next& next) {
    const int k = next.ball;
    BallRun& r = runs_[static_cast<size_t>(k)];
    switch (next.type) {
      case EventType::slide_to_roll:
        r.b.w.x = -r.b.v.y / cloth_.radius;
        r.b.w.y = r.b.v.x / cloth_.radius;
        log(k, next.type);
        r.changed = true;
        break;
      case EventType::spin_stop:
        r.b.w.z = 0.0;
        log(k, next.type);
        r.changed = true;
        break;
      case EventType::rest:
        r.b.v = {0.0, 0.0};
        r.b.w.x = r.b.w.y = 0.0;
        log(k, next.type);
        r.moving = false;
        r.piece = Piece{};
        search_pairs_of(k);
        break;
      case EventType::cushion:
      case EventType::jaw: rebound(k, next.other); break;
      case EventType::pocket:
        r.on_table = false;
        r.moving = false;
        result_->balls[static_cast<size_t>(k)].pocketed = true;
        result_->balls[static_cast<size_t>(k)].pocket = next.other;
        if (k == 0) result_->status = ShotStatus::pocketed;
        log(k, next.type, -1, next.other);
        search_pairs_of(k);
        break;
      case EventType::obstacle:
        result_->status = ShotStatus::hit_obstacle;
        log(k, next.type, -1, next.other);
        over_ = true;
        break;
      case EventType::ball_contact:
        if (next.pressed)
          settle_pressed(next.ball, next.other);
        else
          collide(next.ball, next.other);
        break;
      case EventType::strike: break;
    }
  }

  // A cushion or jaw contact (`which`: a cushion 0-3, or a jaw's code): into the
  // contact's frame (X = n x z, Y = n, Z = z, n from the ball into the cushion, the
  // facing, or a point's centre), resolved by the impact model, and back.
  void rebound(int k, int which) {
    BallRun& r = runs_[static_cast<size_t>(k)];
    Ball& b = r.b;
    const bool jaw = which >= kFirstJaw;
    const Jaws* w = nullptr;
    int part = -1;
    if (jaw) {
      const int pocket = jaw_pocket(which);
      for (const Jaws& j : jaws_)
        if (j.pocket == pocket) w = &j;
      part = jaw_part(which);
    }
    const Vec2 n = !jaw ? lines_[which].normal : jaw_normal(*w, part, b.p);
    // Put in words only when the contact fails.
    const auto where = [&] {
      return !jaw ? fmt::format("cushion {}", which)
                  : fmt::format("pocket {} jaw part {}", jaw_pocket(which), part);
    };
    const Vec2 x_axis{n.y, -n.x};
    BallState in;
    in.velocity = {dot(b.v, x_axis), dot(b.v, n), 0.0};
    in.spin = {b.w.x * x_axis.x + b.w.y * x_axis.y, b.w.x * n.x + b.w.y * n.y, b.w.z};
    // (Whether friction presses the ball in is asked only of an approach within rounding
    // of none.)
    if (!(in.velocity.y > 0.0) ||
        (in.velocity.y <= kRoundingApproach * vec2::length(in.velocity.x, in.velocity.y) &&
         dot(detail::piece_from(cloth_, b).accel, n) > 0.0)) {
      // Friction on the cloth presses the ball into the cushion with no approach speed
      // left (a run of ever smaller bounces, each e times the last: the exact method
      // follows them down to far below the rounding of the speed, so the run is cut at
      // kRoundingApproach): sliding along a cushion is not modelled.
      end_shot(ShotStatus::impact_failed,
               fmt::format("{}{}: the ball is pressed against it with no approach speed "
                           "(sliding along a cushion is not modelled)",
                           whose(k), where()));
      return;
    }
    if (impact_error_) {
      end_shot(ShotStatus::impact_failed,
               fmt::format("{}{}: {}", whose(k), where(), impact_error_->message()));
      return;
    }
    const ImpactResult out = detail::resolve_checked_impact(scene_.ball_and_cushion, in, impact_);
    if (!usable(out.status)) {
      end_shot(ShotStatus::impact_failed, fmt::format("{}{}: {}", whose(k), where(), out.message));
      return;
    }
    b.v = out.outgoing.velocity.x * x_axis + out.outgoing.velocity.y * n;
    const Vec2 wh = out.outgoing.spin.x * x_axis + out.outgoing.spin.y * n;
    b.w = {wh.x, wh.y, out.outgoing.spin.z};
    // On the contact line exactly, so rounding never leaves it past the cushion (a point:
    // a hair outside its circle, as balls are put 2R apart after a collision).
    if (!jaw) {
      b.p = b.p + (lines_[which].contact - dot(n, b.p)) * n;
    } else if (is_point(part)) {
      b.p = w->point[jaw_side(part)] - (w->point_reach * (1.0 + 4e-16)) * n;
    } else {
      const JawPart& f = w->facing[jaw_side(part)];
      b.p = b.p + (f.contact - dot(n, b.p)) * n;
    }
    BallOutcome& o = result_->balls[static_cast<size_t>(k)];
    if (jaw) ++o.jaw_hits;
    else ++o.cushion_hits;
    o.max_cushion_normal_speed = std::max(o.max_cushion_normal_speed, in.velocity.y);
    if (k == 0 && out.status == ImpactStatus::rigid_limit_exceeded)
      result_->rigid_limit_exceeded = true;
    if (out.method_used == ImpactMethod::table) ++result_->table_impacts;
    if (jaw) log(k, EventType::jaw, part, jaw_pocket(which), in.velocity.y);
    else log(k, EventType::cushion, which, -1, in.velocity.y);
    r.changed = true;
    r.check_cushions = cushions_in_reach(b);
  }

  // The unit normal from the ball's centre at p into a jaw's part.
  static Vec2 jaw_normal(const Jaws& w, int part, Vec2 p) {
    const int side = jaw_side(part);
    if (!is_point(part)) return w.facing[side].normal;
    const Vec2 d = w.point[side] - p;
    return (1.0 / vec2::length(d.x, d.y)) * d;
  }

  // A contact of balls i < j, resolved along their line of centres by the collision
  // model (ball i is the lower index, as the contract fixes).
  void collide(int i, int j) {
    Ball& a = runs_[static_cast<size_t>(i)].b;
    Ball& b = runs_[static_cast<size_t>(j)].b;
    const CollisionResult out =
        resolve_table_collision(ball_ball_, {a.p.x, a.p.y, 0.0}, {{a.v.x, a.v.y, 0.0}, a.w},
                                {b.p.x, b.p.y, 0.0}, {{b.v.x, b.v.y, 0.0}, b.w}, collision_);
    if (!usable(out.status)) {
      end_shot(ShotStatus::collision_failed,
               fmt::format("balls {} and {}: {}", result_->balls[static_cast<size_t>(i)].name,
                           result_->balls[static_cast<size_t>(j)].name, out.message));
      return;
    }
    const Vec2 d = b.p - a.p;
    const double approach = dot(a.v - b.v, (1.0 / vec2::length(d.x, d.y)) * d);
    const double speed = std::max(detail::norm(a.v), detail::norm(b.v));
    a.v = {out.ball_i.velocity.x, out.ball_i.velocity.y};
    a.w = out.ball_i.spin;
    b.v = {out.ball_j.velocity.x, out.ball_j.velocity.y};
    b.w = out.ball_j.spin;
    drop_rounding(1e-12 * speed, &a);
    drop_rounding(1e-12 * speed, &b);
    // Exactly 2R apart (a hair more), so that rounding never leaves them overlapping and
    // their next contact is a crossing of 2R that the search finds (as a ball that met a
    // cushion is put on its contact line).
    const double distance = vec2::length(d.x, d.y), diameter = 2.0 * cloth_.radius;
    const double apart = diameter * (1.0 + 4e-16);
    if (distance < apart && distance > diameter * (1.0 - 1e-9)) {
      const Vec2 shift = (0.5 * (apart - distance) / distance) * d;
      a.p = a.p - shift;
      b.p = b.p + shift;
    }
    // Two balls that leave a contact barely moving would go on touching in ever smaller
    // contacts as friction brings them together again (a ball rolling up to another):
    // they come to rest here, which moves them by less than kSettleDistance.
    if (crawling(a) && crawling(b)) {
      stop(&a);
      stop(&b);
    }
    log(i, EventType::ball_contact, -1, -1, approach, j, out.impulse_total);
    log(j, EventType::ball_contact, -1, -1, approach, i, out.impulse_total);
    for (const int k : {i, j}) {
      BallRun& r = runs_[static_cast<size_t>(k)];
      r.changed = true;
      r.check_cushions = cushions_in_reach(r.b);
    }
    if (i == 0 && result_->first_contact < 0) result_->first_contact = j;
  }

  // Balls i and j touch with no approach speed left while friction presses them together:
  // a push, which the collision model does not describe. Balls that barely move - each
  // would roll on less than kSettleDistance - are put at rest where they are (a ball
  // rolling up to another ends the shot this way); a faster push ends the shot (as a
  // ball pressed into a cushion does).
  void settle_pressed(int i, int j) {
    BallRun& a = runs_[static_cast<size_t>(i)];
    BallRun& b = runs_[static_cast<size_t>(j)];
    if (!crawling(a.b) || !crawling(b.b)) {
      end_shot(ShotStatus::collision_failed,
               fmt::format("balls {} and {}: pressed together with no approach speed left "
                           "(a sustained push is not modelled)",
                           result_->balls[static_cast<size_t>(i)].name,
                           result_->balls[static_cast<size_t>(j)].name));
      return;
    }
    for (BallRun* r : {&a, &b}) {
      stop(&r->b);
      r->changed = true;  // at rest: its rest is logged with its new piece
    }
  }

  // Whether a ball barely moves: it would roll on less than kSettleDistance.
  bool crawling(const Ball& b) const {
    const double crawl = std::sqrt(2.0 * cloth_.roll_decel * kSettleDistance);  // m/s
    return detail::norm(b.v) <= crawl && cloth_.radius * vec2::length(b.w.x, b.w.y) <= crawl;
  }

  static void stop(Ball* b) {
    b->v = {0.0, 0.0};
    b->w.x = b->w.y = 0.0;
  }

  // What rounding leaves of a ball's motion after a collision, far below the model's own
  // error: a ball within `noise` (m/s) of rest is at rest, and sidespin that small is
  // none. Kept, it would play out as ever smaller contacts and spin stops at one instant
  // (a stun shot leaves the cue ball with 1e-17 m/s against the ball it stopped behind).
  void drop_rounding(double noise, Ball* b) const {
    const double r = cloth_.radius;
    if (std::abs(b->v.x) <= noise && std::abs(b->v.y) <= noise && r * std::abs(b->w.x) <= noise &&
        r * std::abs(b->w.y) <= noise) {
      b->v = {0.0, 0.0};
      b->w.x = b->w.y = 0.0;
    }
    if (r * std::abs(b->w.z) <= noise) b->w.z = 0.0;
  }

  // ---- Bookkeeping ---------------------------------------------------------------

  bool anything_left() const {
    for (const BallRun& r : runs_)
      if (r.on_table && (r.moving || r.changed)) return true;
    return false;
  }

  void end_shot(ShotStatus status, std::string message) {
    result_->status = status;
    result_->message = std::move(message);
    over_ = true;
  }

  // Ball k's contacts with every other ball searched again: it stopped (it meets another
  // only if that one moves) or left the table (it meets none).
  void search_pairs_of(int k) {
    for (size_t m = 0; m < runs_.size(); ++m)
      if (static_cast<int>(m) != k)
        search_pair(std::min(k, static_cast<int>(m)), std::max(k, static_cast<int>(m)), -1.0);
  }

  // "" for the cue ball (as messages have always read), else "ball NAME: ".
  std::string whose(int k) const {
    return k == 0 ? std::string()
                  : fmt::format("ball {}: ", result_->balls[static_cast<size_t>(k)].name);
  }

  void log(int k, EventType type, int cushion = -1, int index = -1, double normal_speed = 0.0,
           int other = -1, double impulse = 0.0) {
    const Ball& b = runs_[static_cast<size_t>(k)].b;
    ShotEvent e;
    e.type = type;
    e.time = t_;
    e.position = b.p;
    e.velocity = b.v;
    e.spin = b.w;
    e.cushion = cushion;
    e.index = index;
    e.normal_speed = normal_speed;
    e.ball = k;
    e.other = other;
    e.impulse = impulse;
    std::vector<ShotEvent>& events = events_of(k);
    if (events.empty()) events.reserve(16);
    events.push_back(e);
    ++events_;
  }

  std::vector<ShotEvent>& events_of(int k) {
    return k == 0 ? result_->events : result_->balls[static_cast<size_t>(k)].events;
  }
  std::vector<PathSegment>& path_of(int k) {
    return k == 0 ? result_->path : result_->balls[static_cast<size_t>(k)].path;
  }
  PairContact& pair_of(int i, int j) { return pairs_[pair_index(i, j)]; }
  const PairContact& pair_of(int i, int j) const { return pairs_[pair_index(i, j)]; }
  // Pairs i < j in the order (0, 1), (0, 2), ..., (1, 2), ...
  size_t pair_index(int i, int j) const {
    const size_t n = runs_.size(), a = static_cast<size_t>(i), b = static_cast<size_t>(j);
    return a * (2 * n - a - 1) / 2 + (b - a - 1);
  }

  // Whether any cushion is within reach of a ball in this state; found again after
  // every cushion and collision.
  bool cushions_in_reach(const Ball& b) const {
    const double d = detail::reach(cloth_, b);
    for (const CushionLine& c : lines_)
      if (c.contact - dot(c.normal, b.p) <= d) return true;
    return false;
  }

  // Every ball where the shot ended; the outcomes, the cue ball's at the top.
  void finish() {
    double cue_end = t_;
    const std::vector<ShotEvent>& cue_events = result_->events;
    if (!cue_events.empty() && !runs_[0].moving)
      cue_end = cue_events.back().time;  // at rest or pocketed before the others
    for (size_t k = 0; k < runs_.size(); ++k) {
      BallRun& r = runs_[k];
      if (r.on_table && r.moving && t_ > r.t0) bring(static_cast<int>(k), t_ - r.t0);
      result_->balls[k].final_position = r.b.p;
    }
    const BallOutcome& cue = result_->balls[0];
    result_->final_position = cue.final_position;
    result_->duration = cue_end;
    result_->cushion_hits = cue.cushion_hits;
    result_->max_cushion_normal_speed = cue.max_cushion_normal_speed;
    result_->balls[0].events = result_->events;
    result_->balls[0].path = result_->path;
  }

  const Scene& scene_;
  const SimulationOptions& options_;
  const ClothModel cloth_;
  const std::array<CushionLine, 4>& lines_;
  const CushionGaps& gaps_;       // open stretches of the cushion lines (jawed pockets' mouths)
  const std::vector<Jaws>& jaws_;  // the jawed pockets' points and facings
  const BallBallParams& ball_ball_;
  ImpactOptions impact_;
  Validation impact_error_;  // what is wrong with the parameters or impact_, if anything
  CollisionOptions collision_;
  ShotResult* result_;
  std::vector<BallRun> runs_;
  std::vector<PairContact> pairs_;
  double t_ = 0.0;  // s, the shot's clock: the time of the last event
  int events_ = 0;  // events logged, of every ball
  bool over_ = false;
};

ShotResult invalid_shot(ValidationError error) {
  ShotResult result;
  result.status = ShotStatus::invalid_input;
  result.message = error.message();
  result.error = std::move(error);
  return result;
}

}  // namespace

namespace detail {
namespace {

CushionGaps cushion_gaps(const Scene& s) {
  CushionGaps gaps;
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const Pocket& k : s.pockets) {
    if (!k.jaws) continue;
    const PocketJaws& j = *k.jaws;
    if (j.cushion[0] == j.cushion[1]) {
      const double a = along_cushion(j.cushion[0], j.nose_tangent[0]);
      const double b = along_cushion(j.cushion[1], j.nose_tangent[1]);
      gaps[static_cast<size_t>(j.cushion[0])].push_back({std::min(a, b), std::max(a, b)});
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      const int c = j.cushion[side];
      const double t = along_cushion(c, j.nose_tangent[side]);
      // The gap runs from the tangent toward the corner the cushion ends at.
      const double toward = along_cushion(c, j.mouth_centre - j.nose_tangent[side]);
      gaps[static_cast<size_t>(c)].push_back(toward < 0.0 ? Gap{-inf, t} : Gap{t, inf});
    }
  }
  return gaps;
}

std::vector<Jaws> jaws_of(const Scene& s) {
  std::vector<Jaws> out;
  const double off = s.contact_offset();
  for (size_t i = 0; i < s.pockets.size(); ++i) {
    if (!s.pockets[i].jaws) continue;
    const PocketJaws& j = *s.pockets[i].jaws;
    Jaws w;
    w.pocket = static_cast<int>(i);
    w.point_reach = j.shape.point_radius + off;
    double xlo = kNever, xhi = -kNever, ylo = kNever, yhi = -kNever;
    const auto grow = [&](Vec2 p, double r) {
      xlo = std::min(xlo, p.x - r);
      xhi = std::max(xhi, p.x + r);
      ylo = std::min(ylo, p.y - r);
      yhi = std::max(yhi, p.y + r);
    };
    const auto box_around = [](Vec2 a, Vec2 b, double r) {
      return detail::Box{std::min(a.x, b.x) - r, std::max(a.x, b.x) + r, std::min(a.y, b.y) - r,
                         std::max(a.y, b.y) + r};
    };
    for (int side = 0; side < 2; ++side) {
      JawPart& f = w.facing[side];
      f.start = j.facing_start[side];
      f.dir = j.facing_dir[side];
      f.length = j.facing_length[side];
      // The rubber lies to the facing's left on the left side, to its right on the right.
      f.normal = side == 0 ? Vec2{-f.dir.y, f.dir.x} : Vec2{f.dir.y, -f.dir.x};
      f.contact = dot(f.normal, f.start) - off;
      w.point[side] = j.point_centre[side];
      grow(w.point[side], w.point_reach);
      grow(f.start, off);
      grow(f.start + f.length * f.dir, off);
      // Parts 0 left point, 1 left facing, 2 right facing, 3 right point.
      w.part_box[side == 0 ? 0 : 3] = box_around(w.point[side], w.point[side], w.point_reach);
      w.part_box[side == 0 ? 1 : 2] = box_around(f.start, f.start + f.length * f.dir, off);
    }
    w.box = {xlo, xhi, ylo, yhi};
    out.push_back(w);
  }
  return out;
}

std::array<CushionLine, 4> cushion_lines(const Scene& s) {
  const double off = s.contact_offset();
  return {{{{0.0, -1.0}, -off},
           {{1.0, 0.0}, s.length - off},
           {{0.0, 1.0}, s.width - off},
           {{-1.0, 0.0}, -off}}};
}

}  // namespace

SceneGeometry scene_geometry(const Scene& scene) {
  return {cushion_lines(scene), cushion_gaps(scene), jaws_of(scene)};
}

}  // namespace detail

ShotResult simulate(const CompiledScene& compiled, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options) {
  if (compiled.error()) return invalid_shot(*compiled.error());
  if (Validation e = check_stroke(compiled.scene(), cue_ball, shot, options))
    return invalid_shot(std::move(*e));
  ShotResult result;
  result.cushion_model = compiled.scene().ball_and_cushion.model;
  ShotRun run(compiled, options, &result);
  run.strike(cue_ball, shot);
  run.run();
  return result;
}

ShotResult simulate(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options) {
  return simulate(CompiledScene(scene), cue_ball, shot, options);
}

}  // namespace cueplan::physics
