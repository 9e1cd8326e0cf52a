// The position field: P(next pot) from a cue-ball position, in closed form
// (position.hpp; docs/position.md derives it and checks it against the planner).
#include "cueplan/planner/position.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cueplan::planner {
namespace {

using physics::Vec2;

constexpr double kDeg = std::numbers::pi / 180.0;

Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 add(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 scaled(Vec2 a, double s) { return {a.x * s, a.y * s}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 unit(Vec2 a) {
  const double n = norm(a);
  return n > 0.0 ? scaled(a, 1.0 / n) : Vec2{1.0, 0.0};
}
Vec2 rotated(Vec2 a, double rad) {
  const double c = std::cos(rad), s = std::sin(rad);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}

// Distance from p to the segment [a, b].
double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0) : 0.0;
  return norm(sub(p, add(a, scaled(ab, t))));
}

// Standard normal CDF.
double phi(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// The pocket's opening for a ball arriving along `u` (unit, toward the aim point): the
// half-width (m) of the band of lines on which the ball's centre drops. A capture circle
// takes any line within its radius. A jawed mouth, seen along u, is mouth cos(alpha) wide
// (alpha between u and the pocket's inward direction); the ball's centre must pass a
// fraction kJawClearance of a radius inside each point (a ball that meets a facing
// lightly still drops; calibrated against the simulator's pots, docs/position.md).
// Beyond kSteepApproach from the centre line the far jaw takes more and more of the
// rest, until kMostApproach, beyond which nothing drops (the planner's P(pot) into a
// middle pocket at 69 degrees is under a third of the mouth's projection alone).
constexpr double kJawClearance = 0.5;
constexpr double kSteepApproach = 50.0 * kDeg;
constexpr double kMostApproach = 75.0 * kDeg;
double opening_half_width(const physics::Pocket& pocket, Vec2 u, double radius) {
  if (!pocket.jaws) return pocket.radius;
  const double c = std::clamp(dot(u, pocket.jaws->inward), -1.0, 1.0);
  const double alpha = std::acos(c);
  if (alpha >= kMostApproach) return 0.0;
  const double steep =
      std::clamp((kMostApproach - alpha) / (kMostApproach - kSteepApproach), 0.0, 1.0);
  return steep * std::max(0.0, 0.5 * pocket.jaws->shape.mouth * c - kJawClearance * radius);
}

// The throw's deviation (deg) at the largest, a half-ball cut: the noise's speed and
// spin errors change the collision's throw the aim allowed for (about 0.1 deg measured
// by the planner's pot reports; docs/position.md), as sin(2 cut).
constexpr double kThrowSdDeg = 0.1;

// Cueing penalties: the cue over a cushion (the cue ball within kCushionReach of it,
// the stroke leading away from it) keeps at most 1 - kCushionPenalty of P when frozen;
// closer than kCueRoom to the object ball the cue cannot be swung freely.
constexpr double kCushionReach = 0.03;  // m from the cushion nose (ball surface)
constexpr double kCushionPenalty = 0.6;
constexpr double kCueRoom = 0.015;  // m of gap between the balls

const char* thickness_of(double cut_deg) {
  const double covered = 1.0 - std::sin(cut_deg * kDeg);
  if (covered > 0.875) return "full";
  if (covered > 0.625) return "3/4";
  if (covered > 0.375) return "half";
  if (covered > 0.125) return "1/4";
  return "thin";
}

}  // namespace


PositionField::PositionField(const physics::Scene& layout, std::vector<problems::NextPot> next,
                             const NoiseModel& noise, double cell_m, FieldGrid grid)
    : layout_(layout), next_(std::move(next)), cell_(cell_m), cells_(std::make_shared<Cells>()) {
  if (next_.empty()) throw std::invalid_argument("PositionField: no next pot");
  if (!(cell_m > 0.0)) throw std::invalid_argument("PositionField: cell_m must be positive");
  radius_ = layout_.radius();
  contact_offset_ = layout_.contact_offset();
  // The cue ball's direction error of a centre-ball stroke: the aim's, and the sideways
  // tip offset's, which squirts the ball one way and turns the cue about the bridge the
  // other (robustness.cpp's noisy_stroke).
  const double s = noise.scale;
  const double d = noise.tip_offset * s;  // m
  const double dk = physics::kSpinPerTipOffset * d / radius_;
  const double squirt = physics::squirt_angle_deg(layout_.cue, layout_.ball_and_cushion.mass,
                                                  radius_, dk);
  const double pivot = noise.bridge_length > 0.0 ? d / noise.bridge_length / kDeg : 0.0;
  direction_sd_deg_ = std::hypot(noise.aim_deg * s, squirt - pivot);

  for (const problems::NextPot& n : next_) {
    Target t;
    t.ball = n.ball;
    const auto it = std::find_if(layout_.balls.begin(), layout_.balls.end(),
                                 [&](const physics::ObjectBall& b) { return b.name == n.ball; });
    if (it == layout_.balls.end())
      throw std::invalid_argument("PositionField: no ball " + n.ball + " on the table");
    if (n.pocket < 0 || n.pocket >= static_cast<int>(layout_.pockets.size()))
      throw std::invalid_argument("PositionField: no such pocket");
    const physics::Pocket& pocket = layout_.pockets[static_cast<size_t>(n.pocket)];
    t.centre = it->position;
    t.aim = pocket.centre;
    t.u = unit(sub(t.aim, t.centre));
    double w = 0.0;
    if (pocket.jaws) {
      w = opening_half_width(pocket, t.u, radius_);
    } else {
      // A capture circle: the ball's centre drops where it enters the part of the circle
      // that lies on the cloth (where the centre can be without meeting a cushion; at a
      // corner a small part of it). The band of straight lines through that part, across
      // the ball's direction, is the opening; its middle is the aim (twice: the direction
      // moves with the aim).
      for (int pass = 0; pass < 2; ++pass) {
        const Vec2 across{-t.u.y, t.u.x};
        double lo = 1e9, hi = -1e9;
        constexpr int kSamples = 40;
        for (int a = 0; a <= kSamples; ++a)
          for (int b = 0; b <= kSamples; ++b) {
            const Vec2 q{pocket.centre.x + pocket.radius * (2.0 * a / kSamples - 1.0),
                         pocket.centre.y + pocket.radius * (2.0 * b / kSamples - 1.0)};
            if (norm(sub(q, pocket.centre)) > pocket.radius || q.x < contact_offset_ ||
                q.y < contact_offset_ || q.x > layout_.length - contact_offset_ ||
                q.y > layout_.width - contact_offset_)
              continue;
            const double side = dot(sub(q, t.centre), across);
            lo = std::min(lo, side);
            hi = std::max(hi, side);
          }
        if (hi < lo) break;  // no part on the cloth
        w = 0.5 * (hi - lo);
        // The aim: the band's middle, as far along as the pocket's centre.
        const double along = dot(sub(pocket.centre, t.centre), t.u);
        t.aim = add(add(t.centre, scaled(t.u, along)), scaled(across, 0.5 * (hi + lo)));
        t.u = unit(sub(t.aim, t.centre));
      }
    }
    t.distance = norm(sub(t.aim, t.centre));
    t.ghost = sub(t.centre, scaled(t.u, 2.0 * radius_));
    t.half_angle = t.distance > w ? std::asin(w / t.distance) : 0.5 * std::numbers::pi;
    // The object ball's way in: clear of every other ball until it reaches the mouth.
    const Vec2 end = sub(t.aim, scaled(t.u, std::min(t.distance, radius_)));
    t.clear = path_clear(t.centre, end, t.ball, &t.screened_by);
    targets_.push_back(std::move(t));
  }

  columns_ = std::max(1, static_cast<int>(std::ceil(layout_.length / cell_)));
  rows_ = std::max(1, static_cast<int>(std::ceil(layout_.width / cell_)));
  if (grid == FieldGrid::eager) (void)this->grid();
}

const std::vector<double>& PositionField::second() const {
  std::call_once(cells_->second_once, [this] {
    std::vector<double>& second = cells_->second;
    if (targets_.size() < 2) return;
    second.resize(static_cast<size_t>(columns_) * static_cast<size_t>(rows_));
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < columns_; ++i)
        second[static_cast<size_t>(j) * columns_ + i] = shot_from(cell_centre(i, j), targets_[1]).p;
  });
  return cells_->second;
}

const PositionField::Grid& PositionField::grid() const {
  std::call_once(cells_->grid_once, [this] {
    Grid& g = cells_->grid;
    g.values.resize(static_cast<size_t>(columns_) * static_cast<size_t>(rows_));
    g.best_value = 0.0;
    g.best = targets_.front().ghost;
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < columns_; ++i) {
        const double v = value(cell_centre(i, j));
        g.values[static_cast<size_t>(j) * columns_ + i] = v;
        if (v > g.best_value) {
          g.best_value = v;
          g.best = cell_centre(i, j);
        }
      }
    int in = 0;
    for (double v : g.values) in += g.best_value > 0.0 && v >= g.best_value - kZoneWidth;
    g.zone_area_m2 = in * cell_ * cell_;
  });
  return cells_->grid;
}

PositionField PositionField::for_problem(const problems::Problem& problem, const NoiseModel& noise,
                                         double cell_m, FieldGrid grid) {
  physics::Scene layout = problem.scene;
  if (problem.pot)
    std::erase_if(layout.balls,
                  [&](const physics::ObjectBall& b) { return b.name == problem.pot->ball; });
  return PositionField(layout, problem.next, noise, cell_m, grid);
}

double PositionField::pot_chance(const physics::Scene& layout, Vec2 cue, std::string_view ball,
                                 int pocket, const NoiseModel& noise) {
  const PositionField f(layout, {{std::string(ball), pocket}}, noise, 0.02, FieldGrid::lazy);
  return f.next_shot(cue).p;
}

bool PositionField::path_clear(Vec2 a, Vec2 b, const std::string& skip, std::string* by) const {
  const double reach = 2.0 * radius_;
  for (const physics::ObjectBall& o : layout_.balls) {
    if (o.name == skip) continue;
    if (segment_distance(o.position, a, b) < reach) {
      *by = o.name;
      return false;
    }
  }
  for (size_t k = 0; k < layout_.obstacles.size(); ++k)
    if (segment_distance(layout_.obstacles[k], a, b) < reach) {
      *by = fmt::format("obstacle {}", k);
      return false;
    }
  return true;
}

bool PositionField::cue_can_lie(Vec2 c) const {
  const double r = contact_offset_;
  if (c.x < r || c.y < r || c.x > layout_.length - r || c.y > layout_.width - r) return false;
  for (const physics::ObjectBall& o : layout_.balls)
    if (norm(sub(o.position, c)) < 2.0 * radius_) return false;
  for (const Vec2& o : layout_.obstacles)
    if (norm(sub(o, c)) < 2.0 * radius_) return false;
  for (const physics::Pocket& p : layout_.pockets)
    if (norm(sub(p.centre, c)) < p.radius + radius_) return false;
  return true;
}

NextShot PositionField::shot_from(Vec2 c, const Target& t) const {
  NextShot s;
  s.object_distance_m = t.distance;
  s.cue_distance_m = norm(sub(t.centre, c));
  if (!cue_can_lie(c)) {
    s.valid_position = false;
    return s;
  }
  const Vec2 to_ghost = sub(t.ghost, c);
  const double travel = norm(to_ghost);
  const Vec2 v = unit(to_ghost);
  // The cut: between the cue ball's path and the object ball's (the line of centres).
  const double cos_cut = std::clamp(dot(v, t.u), -1.0, 1.0);
  s.cut_deg = std::acos(cos_cut) / kDeg;
  s.cut_side = cross(v, t.u) > 0.0 ? 1 : cross(v, t.u) < 0.0 ? -1 : 0;
  s.thickness = thickness_of(std::min(s.cut_deg, 90.0));
  if (!t.clear) {
    s.screened_by = t.screened_by;
    return s;
  }
  if (s.cut_deg > kMostCut || travel < 1e-9) {
    s.impossible_cut = true;
    return s;
  }
  // The cue ball's way to the ghost ball, clear of every ball but the one it strikes
  // (which a cut's path may pass within 2R of only at its end: checked up to just short).
  if (!path_clear(c, t.ghost, t.ball, &s.screened_by)) return s;
  {
    // The object ball itself must not be met before the ghost position: the path's
    // closest approach to it is the contact itself.
    const double along = dot(sub(t.centre, c), v);
    if (along < travel - 1e-9 && segment_distance(t.centre, c, t.ghost) < 2.0 * radius_ - 1e-9) {
      s.impossible_cut = true;
      return s;
    }
  }
  // The gain of a direction error: eq. in position.hpp, with D the distance to the ball.
  const double D = s.cue_distance_m;
  const double g = std::abs(D / (2.0 * radius_ * cos_cut) - 1.0);
  const double sigma_throw = kThrowSdDeg * std::abs(std::sin(2.0 * s.cut_deg * kDeg));
  const double sigma = std::hypot(g * direction_sd_deg_, sigma_throw) * kDeg;
  double p = sigma > 0.0 ? 2.0 * phi(t.half_angle / sigma) - 1.0 : 1.0;
  // The cue over a cushion: the nearest cushion behind the stroke.
  const double gaps[4] = {c.x - contact_offset_, layout_.length - contact_offset_ - c.x,
                          c.y - contact_offset_, layout_.width - contact_offset_ - c.y};
  const Vec2 inward[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  double cushion = 1.0;
  for (int k = 0; k < 4; ++k) {
    const double near = std::clamp(1.0 - gaps[k] / kCushionReach, 0.0, 1.0);
    const double away = std::max(0.0, dot(v, inward[k]));
    if (near > 0.0 && away > 0.0) {
      s.near_cushion = true;
      cushion = std::min(cushion, 1.0 - kCushionPenalty * near * away);
    }
  }
  p *= cushion;
  const double gap = s.cue_distance_m - 2.0 * radius_;
  if (gap < kCueRoom) {
    s.too_close = true;
    p *= std::clamp(gap / kCueRoom, 0.0, 1.0);
  }
  s.p = std::clamp(p, 0.0, 1.0);
  return s;
}

NextShot PositionField::next_shot(Vec2 cue, size_t index) const {
  if (index >= targets_.size()) return {};
  return shot_from(cue, targets_[index]);
}

double PositionField::grid_value(const std::vector<double>& grid, Vec2 p) const {
  // Bilinear between cell centres, clamped to the grid.
  const double fx = std::clamp(p.x / cell_ - 0.5, 0.0, columns_ - 1.0);
  const double fy = std::clamp(p.y / cell_ - 0.5, 0.0, rows_ - 1.0);
  const int i = std::min(static_cast<int>(fx), columns_ - 1);
  const int j = std::min(static_cast<int>(fy), rows_ - 1);
  const int i1 = std::min(i + 1, columns_ - 1), j1 = std::min(j + 1, rows_ - 1);
  const double a = fx - i, b = fy - j;
  auto at = [&](int x, int y) { return grid[static_cast<size_t>(y) * columns_ + x]; };
  return (1 - a) * (1 - b) * at(i, j) + a * (1 - b) * at(i1, j) + (1 - a) * b * at(i, j1) +
         a * b * at(i1, j1);
}

// The best P(second) the cue ball can be sent to by the first pot from `cue`: along
// directions from the ghost ball between full follow (the cue ball's own line) through
// stun (the tangent line) to full draw (back along its line), to the first cushion or
// ball, at most kReach away.
double PositionField::reach_value(Vec2 cue, const Target& first) const {
  constexpr int kDirections = 13;
  constexpr double kStep = 0.05;   // m along each direction
  constexpr double kReach = 2.0;   // m
  const Vec2 v = unit(sub(first.ghost, cue));
  // The tangent line, on the cue ball's side of the object ball's path.
  const double side = cross(v, first.u) >= 0.0 ? -1.0 : 1.0;
  const Vec2 tangent = rotated(first.u, side * 0.5 * std::numbers::pi);
  const std::vector<double>& second = this->second();
  double best = grid_value(second, first.ghost);  // stopped dead on a straight pot
  for (int k = 0; k < kDirections; ++k) {
    // From follow (v) through the tangent to draw (-v).
    const double f = static_cast<double>(k) / (kDirections - 1);
    const Vec2 dir = f <= 0.5 ? unit(add(scaled(v, 1.0 - 2.0 * f), scaled(tangent, 2.0 * f)))
                              : unit(add(scaled(tangent, 2.0 - 2.0 * f), scaled(v, 1.0 - 2.0 * f)));
    for (double r = kStep; r <= kReach; r += kStep) {
      const Vec2 p = add(first.ghost, scaled(dir, r));
      if (p.x < contact_offset_ || p.y < contact_offset_ || p.x > layout_.length - contact_offset_ ||
          p.y > layout_.width - contact_offset_)
        break;
      bool hit = false;
      for (const physics::ObjectBall& o : layout_.balls)
        hit = hit || (o.name != first.ball && norm(sub(o.position, p)) < 2.0 * radius_);
      for (const Vec2& o : layout_.obstacles) hit = hit || norm(sub(o, p)) < 2.0 * radius_;
      if (hit) break;
      best = std::max(best, grid_value(second, p));
    }
  }
  return best;
}

double PositionField::value(Vec2 cue) const {
  const Target& first = targets_.front();
  const double p = shot_from(cue, first).p;
  if (targets_.size() < 2 || p <= 0.0) return p;
  return p * reach_value(cue, first);
}

std::shared_ptr<const PositionField> PositionCache::get(const problems::Problem& problem,
                                                        const NoiseModel& noise) {
  // The key: everything the field depends on (the layout, the next pots, the noise).
  const physics::Scene& s = problem.scene;
  std::string key = fmt::format("{:.9g} {:.9g} {:.9g} {:.9g} {:.9g}|", s.length, s.width, s.radius(),
                                s.contact_offset(), s.cue.end_mass);
  for (const physics::Pocket& p : s.pockets)
    key += fmt::format("{:.9g},{:.9g},{:.9g},{};", p.centre.x, p.centre.y, p.radius,
                       p.jaws ? p.jaws->shape.mouth : 0.0);
  for (const physics::ObjectBall& b : s.balls)
    if (!problem.pot || b.name != problem.pot->ball)
      key += fmt::format("{}@{:.9g},{:.9g};", b.name, b.position.x, b.position.y);
  for (const Vec2& o : s.obstacles) key += fmt::format("o{:.9g},{:.9g};", o.x, o.y);
  for (const problems::NextPot& n : problem.next) key += fmt::format("n{}>{};", n.ball, n.pocket);
  key += fmt::format("{:.9g} {:.9g} {:.9g} {:.9g} {:.9g}", noise.aim_deg, noise.tip_offset,
                     noise.bridge_length, noise.scale, noise.speed);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (auto it = fields_.find(key); it != fields_.end()) return it->second;
  }
  // Built outside the lock: two threads may build the same field; the first kept wins.
  auto field = std::make_shared<const PositionField>(PositionField::for_problem(problem, noise));
  const std::lock_guard<std::mutex> lock(mutex_);
  return fields_.try_emplace(key, std::move(field)).first->second;
}

namespace {

// A cut as a player names it.
std::string cut_words(const NextShot& s) {
  if (s.cut_deg < 3.0) return "a straight pot";
  if (s.thickness == "full") return "a nearly full-ball pot";
  if (s.thickness == "3/4") return "a three-quarter-ball cut";
  if (s.thickness == "half") return "a half-ball cut";
  if (s.thickness == "1/4") return "a quarter-ball cut";
  return "a thin cut";
}

}  // namespace

NextReport next_report(const problems::Problem& problem, const PositionField& field, Vec2 landing) {
  NextReport r;
  const problems::NextPot& n = field.next().front();
  r.ball = n.ball;
  r.pocket = n.pocket;
  r.pocket_name = problems::pocket_name(problem.scene, n.pocket);
  r.landing = landing;
  const NextShot s = field.next_shot(landing);
  r.p = s.p;
  r.cut_deg = s.cut_deg;
  r.cut_side = s.cut_side;
  r.thickness = s.thickness;
  r.distance_m = s.cue_distance_m;
  r.screened_by = s.screened_by;
  r.zone_area_m2 = field.zone_area_m2();
  r.in_zone = field.in_zone(landing);
  r.best_p = field.best_value();
  r.best = field.best();
  const std::string cm = fmt::format("{:.0f} cm", 100.0 * s.cue_distance_m);
  if (!s.valid_position)
    r.words = fmt::format("leaves no shot at the {}", n.ball);
  else if (!s.screened_by.empty())
    r.words = fmt::format("leaves the {} screened by the {}", n.ball, s.screened_by);
  else if (s.impossible_cut)
    r.words = fmt::format("leaves no pot of the {} into the {} (too thin a cut)", n.ball, r.pocket_name);
  else
    r.words = fmt::format("leaves {} on the {}, {}", cut_words(s), n.ball, cm);
  if (s.valid_position && s.near_cushion && s.screened_by.empty()) r.words += ", cueing over the cushion";
  if (s.valid_position && s.too_close) r.words += ", too close to cue freely";
  return r;
}

size_t PositionCache::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return fields_.size();
}

}  // namespace cueplan::planner
