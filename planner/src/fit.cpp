// Strokes and table constants from recorded shots (fit.hpp).
#include "cueplan/planner/fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <functional>
#include <numbers>

#include "cueplan/parallel.hpp"
#include "nlopt_stage.hpp"

namespace cueplan::planner {
namespace {

namespace phys = cueplan::physics;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNudge = 0.01;  // m: what prepare_shot moves a ball by, at most
constexpr double kFailedLoss = 1.0;  // m^2 of Huber loss for a stroke that cannot be simulated

std::string shot_ball(const std::string& id, const std::string& ball) {
  return "shot " + id + ", ball " + ball;
}

// One array of numbers under `key` of ball `b`; empty optional with *error set otherwise.
std::optional<std::vector<double>> numbers(const json& b, const char* key, const std::string& where,
                                           std::string* error) {
  if (!b.contains(key)) {
    *error = where + ": " + key + " is missing";
    return std::nullopt;
  }
  const json& a = b.at(key);
  if (!a.is_array()) {
    *error = where + ": " + key + " must be an array of numbers";
    return std::nullopt;
  }
  std::vector<double> v;
  v.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number()) {
      *error = fmt::format("{}: {}[{}] is {}, not a number", where, key, i, a[i].dump());
      return std::nullopt;
    }
    const double value = a[i].get<double>();
    if (!std::isfinite(value)) {
      *error = fmt::format("{}: {}[{}] is not finite", where, key, i);
      return std::nullopt;
    }
    v.push_back(value);
  }
  return v;
}

double huber(double r, double delta) {
  return r <= delta ? 0.5 * r * r : delta * (r - 0.5 * delta);
}

// Position of a simulated ball at time ts (s after the strike); `seg` walks along the path
// for increasing times.
phys::Vec2 position_at(const phys::BallOutcome& ball, double ts, size_t* seg) {
  if (ts <= 0.0 || ball.path.empty()) return ts <= 0.0 ? ball.start : ball.final_position;
  while (*seg + 1 < ball.path.size() && ts > ball.path[*seg].t1) ++*seg;
  const phys::PathSegment& s = ball.path[*seg];
  if (ts < s.t0) return s.at(s.t0);
  if (ts > s.t1) return ball.final_position;
  return s.at(ts);
}

double window(const ShotData& d, const FitOptions& o) { return o.max_offset_s + d.strike_extra; }

// The squirt of a stroke with this side on the shot's table (deg, counter-clockwise).
double squirt_deg(const ShotData& d, double sidespin_k) {
  const phys::Scene& s = d.scene;
  return phys::squirt_angle_deg(s.cue, s.ball_and_cushion.mass, s.radius(), sidespin_k);
}

// The search's coordinates: u[1] is the direction the cue ball leaves in (what the first
// samples pin), and the cue's aim is that less the squirt of the stroke's side, so that
// side and aim do not trade off through the squirt.
phys::Shot stroke_of(const double* u, const phys::Shot& centre, const ShotData& d,
                     const FitOptions& o, double* offset) {
  phys::Shot s;
  s.speed = centre.speed * (1.0 + o.speed_span * (2.0 * u[0] - 1.0));
  s.topspin_k = o.spin_max * (2.0 * u[2] - 1.0);
  s.sidespin_k = o.spin_max * (2.0 * u[3] - 1.0);
  // A cue gives no more spin than the miscue limit: the box's corners map onto its circle.
  const double spin = std::hypot(s.topspin_k, s.sidespin_k);
  if (spin > phys::kMiscueSpin) {
    s.topspin_k *= phys::kMiscueSpin / spin;
    s.sidespin_k *= phys::kMiscueSpin / spin;
  }
  s.aim_deg = centre.aim_deg + o.aim_span_deg * (2.0 * u[1] - 1.0) - squirt_deg(d, s.sidespin_k);
  *offset = d.strike_lo + window(d, o) * u[4];
  // The cue's elevation (swerve with side), when the search has it.
  if (o.max_elevation_deg > 0.0) s.elevation_deg = o.max_elevation_deg * u[5];
  return s;
}

std::vector<double> unit_of(const StrokeFit& f, const phys::Shot& centre, const ShotData& d,
                            const FitOptions& o) {
  auto clamp01 = [](double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.5; };
  std::vector<double> u = {
      clamp01(0.5 * (f.shot.speed / centre.speed - 1.0) / o.speed_span + 0.5),
      clamp01(0.5 * (f.shot.aim_deg + squirt_deg(d, f.shot.sidespin_k) - centre.aim_deg) /
                  o.aim_span_deg + 0.5),
      clamp01(0.5 * f.shot.topspin_k / o.spin_max + 0.5),
      clamp01(0.5 * f.shot.sidespin_k / o.spin_max + 0.5),
      clamp01(window(d, o) > 0 ? (f.offset_s - d.strike_lo) / window(d, o) : 0.0)};
  if (o.max_elevation_deg > 0.0) u.push_back(clamp01(f.shot.elevation_deg / o.max_elevation_deg));
  return u;
}

}  // namespace

// The loss over the samples up to t_max (s on the file's clock); the RMSEs over all.
StrokeFit score_stroke(const phys::CompiledScene& scene, const ShotData& data,
                       const phys::Shot& shot, double offset_s, const FitOptions& options,
                       double t_max);

namespace {

struct StrokeObjective {
  const phys::CompiledScene* scene;
  const ShotData* data;
  const FitOptions* options;
  phys::Shot centre;
  StrokeFit best;
  int evaluations = 0;
  double t_max = std::numeric_limits<double>::infinity();
  double operator()(const double* u) {
    double offset = 0.0;
    const phys::Shot shot = stroke_of(u, centre, *data, *options, &offset);
    const StrokeFit f = score_stroke(*scene, *data, shot, offset, *options, t_max);
    ++evaluations;
    if (f.loss < best.loss) best = f;
    return f.loss;
  }
};

double sq(double v) { return v * v; }

}  // namespace

TrackRead parse_track(const std::string& line, int line_number) {
  TrackRead r;
  r.id = "line " + std::to_string(line_number);
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception& e) {
    r.error = r.id + ": not JSON: " + e.what();
    return r;
  }
  if (!j.is_object()) {
    r.error = r.id + ": must be a JSON object {\"id\": ..., \"balls\": {...}}";
    return r;
  }
  if (j.contains("id")) r.id = j["id"].is_string() ? j["id"].get<std::string>() : j["id"].dump();
  const std::string shot = "shot " + r.id;
  if (!j.contains("balls") || !j["balls"].is_object() || j["balls"].empty()) {
    r.error = shot + ": balls must be an object of balls {\"1\": {t, x, y}, ...}";
    return r;
  }
  Track track;
  track.id = r.id;
  for (const auto& [name, b] : j["balls"].items()) {
    const std::string where = shot_ball(r.id, name);
    if (!b.is_object()) {
      r.error = where + ": must be an object {t, x, y}";
      return r;
    }
    TrackedBall ball;
    ball.name = name;
    auto t = numbers(b, "t", where, &r.error);
    if (!t) return r;
    auto x = numbers(b, "x", where, &r.error);
    if (!x) return r;
    auto y = numbers(b, "y", where, &r.error);
    if (!y) return r;
    if (t->empty()) {
      r.error = where + ": no samples";
      return r;
    }
    if (x->size() != t->size() || y->size() != t->size()) {
      r.error = fmt::format("{}: t, x and y differ in length ({}, {}, {})", where, t->size(),
                            x->size(), y->size());
      return r;
    }
    for (size_t i = 1; i < t->size(); ++i)
      if ((*t)[i] < (*t)[i - 1]) {
        r.error = fmt::format("{}: times out of order: t[{}] = {} comes after t[{}] = {}", where, i,
                              (*t)[i], i - 1, (*t)[i - 1]);
        return r;
      }
    ball.t = std::move(*t);
    ball.x = std::move(*x);
    ball.y = std::move(*y);
    track.balls.push_back(std::move(ball));
  }
  r.track = std::move(track);
  return r;
}

ShotDataRead prepare_shot(const Track& track, const phys::Scene& table, const TrackFrame& frame) {
  ShotDataRead out;
  const std::string shot = "shot " + track.id;
  if (track.balls.empty()) {
    out.error = shot + ": no balls";
    return out;
  }
  // The cue ball: the one that moves first (smallest second sample time).
  size_t cue = 0;
  double first = kInf;
  for (size_t k = 0; k < track.balls.size(); ++k) {
    const TrackedBall& b = track.balls[k];
    if (b.t.size() > 1 && b.t[1] < first) {
      first = b.t[1];
      cue = k;
    }
  }
  const TrackedBall& cb = track.balls[cue];
  if (cb.t.size() < 3) {
    out.error = shot_ball(track.id, cb.name) +
                ": the cue ball (the first to move) needs at least 3 samples, got " +
                std::to_string(cb.t.size());
    return out;
  }
  ShotData d;
  d.id = track.id;
  d.scene = table;
  d.scene.balls.clear();
  std::vector<size_t> order{cue};
  for (size_t k = 0; k < track.balls.size(); ++k)
    if (k != cue) order.push_back(k);
  const double off = table.contact_offset();
  for (size_t k : order) {
    const TrackedBall& b = track.balls[k];
    d.names.push_back(b.name);
    d.t.push_back(b.t);
    std::vector<phys::Vec2> p;
    for (size_t i = 0; i < b.t.size(); ++i) p.push_back(frame.to_table(b.x[i], b.y[i]));
    // The start must lie on the table (within a centimetre: tracking noise is nudged in).
    phys::Vec2& s = p.front();
    const double lo_x = off, hi_x = table.length - off, lo_y = off, hi_y = table.width - off;
    if (s.x < lo_x - kNudge || s.x > hi_x + kNudge || s.y < lo_y - kNudge || s.y > hi_y + kNudge) {
      out.error = fmt::format(
          "{}: starts off the table at ({:.4g}, {:.4g}) in the file's units, ({:.4g}, {:.4g}) m "
          "from the corner; the centre must lie within [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m",
          shot_ball(track.id, b.name), b.x[0], b.y[0], s.x, s.y, lo_x, hi_x, lo_y, hi_y);
      return out;
    }
    s.x = std::clamp(s.x, lo_x + 1e-6, hi_x - 1e-6);
    s.y = std::clamp(s.y, lo_y + 1e-6, hi_y - 1e-6);
    d.p.push_back(std::move(p));
  }
  // Overlapping balls: beyond tracking noise an error, within it pushed apart to touch.
  const double two_r = 2.0 * table.radius();
  for (size_t i = 0; i < d.p.size(); ++i)
    for (size_t j = i + 1; j < d.p.size(); ++j) {
      phys::Vec2& a = d.p[i].front();
      phys::Vec2& b = d.p[j].front();
      const double dx = b.x - a.x, dy = b.y - a.y, dist = std::hypot(dx, dy);
      if (dist < two_r - kNudge || dist == 0.0) {
        out.error = fmt::format(
            "{}: overlaps ball {} at the start: centres {:.4g} m apart, less than two radii "
            "({:.4g} m)",
            shot_ball(track.id, d.names[j]), d.names[i], dist, two_r);
        return out;
      }
      if (dist < two_r + 1e-6) {
        const double push = 0.5 * (two_r + 2e-6 - dist) / dist;
        a.x -= dx * push;
        a.y -= dy * push;
        b.x += dx * push;
        b.y += dy * push;
      }
    }
  d.cue_start = d.p[0].front();
  // A cue ball first seen moving after a gap in its samples was struck in the gap.
  const double t1 = d.t[0][1];
  if (t1 > 0.05) {
    d.strike_lo = t1 - 0.05;
    d.strike_extra = 0.05 - 0.02;  // window [t1 - 0.05, t1 - 0.05 + max_offset_s + 0.03]
  }
  d.first_other_motion = kInf;
  for (size_t k = 1; k < d.t.size(); ++k)
    for (size_t i = 1; i < d.t[k].size(); ++i)
      if (std::hypot(d.p[k][i].x - d.p[k][0].x, d.p[k][i].y - d.p[k][0].y) > 0.01) {
        d.first_other_motion = std::min(d.first_other_motion, d.t[k][i]);
        break;
      }
  for (size_t k = 1; k < d.p.size(); ++k)
    d.scene.balls.push_back({"ball" + d.names[k], d.p[k].front()});
  if (const phys::Validation error = d.scene.validate()) {
    out.error = shot + ": the table with the balls placed is unusable: " + error->rule_text();
    return out;
  }
  for (size_t k = 0; k < d.p.size(); ++k)
    if (const phys::Validation error = d.scene.check_position(
            d.p[k].front(), {k == 0 ? std::string("cue_ball") : "ball" + d.names[k]})) {
      // An object ball is checked against the others by validate(); the cue ball here.
      if (k == 0) {
        out.error = shot_ball(track.id, d.names[0]) + ": " + error->rule_text();
        return out;
      }
    }
  out.data = std::move(d);
  return out;
}

StrokeFit kinematic_guess(const ShotData& data, const FitOptions& options) {
  const std::vector<double>& t = data.t[0];
  const std::vector<phys::Vec2>& p = data.p[0];
  // The first moving samples (up to 5 after the start, and before any other ball moves,
  // at least 2): a least-squares line p = a + v t.
  size_t n = std::min<size_t>(5, t.size() - 1);
  while (n > 2 && t[n] >= data.first_other_motion - 0.01) --n;
  double st = 0, sx = 0, sy = 0, stt = 0, stx = 0, sty = 0;
  for (size_t i = 1; i <= n; ++i) {
    st += t[i];
    sx += p[i].x;
    sy += p[i].y;
    stt += t[i] * t[i];
    stx += t[i] * p[i].x;
    sty += t[i] * p[i].y;
  }
  const double m = static_cast<double>(n);
  const double den = m * stt - st * st;
  StrokeFit f;
  phys::Vec2 v, a;
  if (n >= 2 && den > 0) {
    v = {(m * stx - st * sx) / den, (m * sty - st * sy) / den};
    a = {(sx - v.x * st) / m, (sy - v.y * st) / m};
  } else {  // one sample: from the start
    const double dt = std::max(t[1] - t[0], 1e-3);
    v = {(p[1].x - p[0].x) / dt, (p[1].y - p[0].y) / dt};
    a = p[0];
  }
  const double speed = std::hypot(v.x, v.y);
  // The strike: where the line passes the start.
  const double lo = data.strike_lo, hi = data.strike_lo + options.max_offset_s + data.strike_extra;
  double t0 = 0.5 * (lo + hi);
  if (speed > 0) {
    const phys::Vec2 s = data.p[0].front();
    t0 = ((s.x - a.x) * v.x + (s.y - a.y) * v.y) / (speed * speed);
    t0 = std::clamp(t0, lo, hi);
  }
  // A centre-ball stroke slides, slowing at mu_s g, over the first samples: the line's
  // speed is the speed at their mean time.
  const double t_mean = n > 0 ? st / m : 0.0;
  const double decel = data.scene.cloth.mu_slide * data.scene.cloth.gravity;
  f.shot.speed = std::max(0.05, speed + decel * std::max(0.0, t_mean - t0));
  f.shot.aim_deg = std::atan2(v.y, v.x) * 180.0 / std::numbers::pi;
  f.offset_s = t0;
  return f;
}

StrokeFit evaluate_stroke(const phys::CompiledScene& scene, const ShotData& data,
                          const phys::Shot& shot, double offset_s, const FitOptions& options) {
  return score_stroke(scene, data, shot, offset_s, options, kInf);
}

StrokeFit score_stroke(const phys::CompiledScene& scene, const ShotData& data,
                       const phys::Shot& shot, double offset_s, const FitOptions& options,
                       double t_max) {
  StrokeFit f;
  f.shot = shot;
  f.offset_s = offset_s;
  f.evaluations = 1;
  phys::ShotResult r;
  // A windowed score needs the simulation only up to the window's last sample.
  const double horizon = options.horizon ? t_max - offset_s : kInf;
  const auto positions = simulated_positions(scene, data, f, &r, options.max_events,
                                             horizon > 0.0 ? horizon : kInf);
  if (positions.empty()) {
    f.loss = kFailedLoss;
    f.rmse_cue_m = f.rmse_all_m = kInf;
    return f;
  }
  f.simulated = true;
  double sum_cue = 0, sum_all = 0, loss = 0;
  size_t n_cue = 0, n_all = 0, n_loss = 0;
  for (size_t k = 0; k < positions.size(); ++k)
    for (size_t i = 0; i < positions[k].size(); ++i) {
      const double r2 = sq(positions[k][i].x - data.p[k][i].x) + sq(positions[k][i].y - data.p[k][i].y);
      sum_all += r2;
      ++n_all;
      if (k == 0) {
        sum_cue += r2;
        ++n_cue;
      }
      if ((k == 0 || options.all_balls) && data.t[k][i] <= t_max) {
        loss += huber(std::sqrt(r2), options.huber_delta);
        ++n_loss;
      }
    }
  f.rmse_cue_m = std::sqrt(sum_cue / static_cast<double>(std::max<size_t>(n_cue, 1)));
  f.rmse_all_m = std::sqrt(sum_all / static_cast<double>(std::max<size_t>(n_all, 1)));
  f.loss = loss / static_cast<double>(std::max<size_t>(n_loss, 1));
  return f;
}

std::vector<std::vector<phys::Vec2>> simulated_positions(const phys::CompiledScene& scene,
                                                         const ShotData& data,
                                                         const StrokeFit& fit,
                                                         phys::ShotResult* result, int max_events,
                                                         double max_time) {
  phys::SimulationOptions so;
  so.max_events = max_events;
  so.record_path = true;
  so.max_time = max_time;
  phys::ShotResult r = phys::simulate(scene, data.cue_start, fit.shot, so);
  std::vector<std::vector<phys::Vec2>> out;
  const bool followed =
      r.status == phys::ShotStatus::rest || r.status == phys::ShotStatus::time_limit;
  if (!followed || r.balls.size() != data.p.size()) {
    if (result) *result = std::move(r);
    return out;
  }
  out.resize(data.p.size());
  for (size_t k = 0; k < data.p.size(); ++k) {
    size_t seg = 0;
    out[k].reserve(data.t[k].size());
    for (double t : data.t[k]) out[k].push_back(position_at(r.balls[k], t - fit.offset_s, &seg));
  }
  if (result) *result = std::move(r);
  return out;
}

namespace {

// A local BOBYQA run from objective's best point so far, on the samples up to t_max, the
// box recentred on that point.
void local_stage(StrokeObjective& objective, double t_max, int budget, double step) {
  const StrokeFit from = objective.best;
  objective.t_max = t_max;
  objective.centre = from.shot;
  objective.best = score_stroke(*objective.scene, *objective.data, from.shot, from.offset_s,
                                *objective.options, t_max);
  std::vector<double> x = unit_of(from, from.shot, *objective.data, *objective.options);
  detail::StageSettings l;
  l.algorithm = NLOPT_LN_BOBYQA;
  l.max_evaluations = budget;
  l.x_tolerance = 1e-7;
  l.initial_step = step;
  detail::run_stage(l, &x, &objective);
}

// One whole search (global stages, continuation, spin starts), its random draws seeded
// by the shot and `restart`. The first global stage's box is centred on *centre (the
// first guess for the first restart), which it leaves at the last spin start's answer
// for the next restart; the second global stage's box is centred on the first guess.
// Returns the best stroke scored on every sample; *evaluations counts its simulations.
StrokeFit search_stroke(const phys::CompiledScene& scene, const ShotData& data,
                        const FitOptions& options, const StrokeFit& guess, int restart,
                        phys::Shot* centre, int* evaluations) {
  StrokeObjective objective{&scene, &data, &options, *centre, guess, 0};
  const auto local = [&](double t_max, int budget, double step) {
    local_stage(objective, t_max, budget, step);
  };
  // The same stroke gives the same answer on every run and thread (NLopt's seed is the
  // calling thread's).
  nlopt_srand((std::hash<std::string>{}(data.id) ^ 0x5eed) +
              0x9e3779b9ULL * static_cast<unsigned long long>(restart));
  // Continuation in time: the first samples, before kisses and cushions multiply the
  // minima, pin speed and aim; each longer window starts from the last answer.
  const double t0 = data.strike_lo;
  const double windows[] = {t0 + 0.6, t0 + 1.2, t0 + 2.5, t0 + 5.0, kInf};
  objective.t_max = windows[0];
  objective.best = score_stroke(scene, data, guess.shot, guess.offset_s, options, windows[0]);
  // Global: CRS2 over the box round the first guess (as `solve`'s global stage).
  detail::StageSettings g;
  g.algorithm = NLOPT_GN_CRS2_LM;
  g.max_evaluations = options.global_evaluations;
  std::vector<double> x = unit_of(guess, guess.shot, data, options);
  detail::run_stage(g, &x, &objective);
  for (double w : windows) local(w, options.local_evaluations / 2, 0.02);
  const StrokeFit continued = objective.best;
  // A second start: the global stage on every sample at once, then a local run.
  objective.t_max = kInf;
  objective.centre = guess.shot;
  objective.best = evaluate_stroke(scene, data, guess.shot, guess.offset_s, options);
  x = unit_of(guess, guess.shot, data, options);
  detail::run_stage(g, &x, &objective);
  local(kInf, options.local_evaluations / 2, 0.02);
  const StrokeFit second = objective.best;
  // Both answers scored on every sample; the better (the first on a tie) is the best so far.
  const StrokeFit bases[2] = {evaluate_stroke(scene, data, continued.shot, continued.offset_s, options),
                              evaluate_stroke(scene, data, second.shot, second.offset_s, options)};
  StrokeFit best = bases[1].loss < bases[0].loss ? bases[1] : bases[0];
  // Spin starts: speed, aim and strike pinned by the early samples, the spins (which rule
  // the path after the first cushion or kiss) restarted on two rings of values,
  // alternately from each global stage's answer, each continued over the later windows.
  const int n = options.spin_starts;
  const int per_ring = (n + 1) / 2;
  for (int k = 0; k < n; ++k) {
    const int ring = k % 2;
    // Each restart turns the rings a little, so that its starts are new ones.
    const double turn = 0.5 * ring + static_cast<double>(restart) / options.restarts;
    const double a = 2.0 * std::numbers::pi * ((k / 2) + turn) / per_ring;
    const double radius = ring == 0 ? options.spin_start_radius : options.spin_start_radius_outer;
    const StrokeFit& base = bases[(k / 2) % 2];
    StrokeFit from = base;
    from.shot.topspin_k = radius * std::cos(a);
    from.shot.sidespin_k = radius * std::sin(a);
    from.shot.aim_deg = base.shot.aim_deg + squirt_deg(data, base.shot.sidespin_k) -
                        squirt_deg(data, from.shot.sidespin_k);
    objective.best = from;
    for (double w : {windows[1], windows[2], kInf}) local(w, options.spin_start_evaluations, 0.02);
    const StrokeFit f = evaluate_stroke(scene, data, objective.best.shot, objective.best.offset_s, options);
    if (f.loss < best.loss) best = f;
  }
  *evaluations = objective.evaluations;
  *centre = objective.centre;
  return best;
}

}  // namespace

StrokeFit fit_stroke(const phys::CompiledScene& scene, const ShotData& data,
                     const FitOptions& options, const StrokeFit* start) {
  const StrokeFit guess = start ? *start : kinematic_guess(data, options);
  int evaluations = 0;
  StrokeFit best = guess;
  if (!start) {
    // Restarts: the search's minima differ with its random draws (CRS2's population) and
    // where its first box is centred (each later restart round a stroke the one before
    // found); the best on every sample is kept.
    phys::Shot centre = guess.shot;
    for (int r = 0; r < std::max(1, options.restarts); ++r) {
      int spent = 0;
      const StrokeFit found = search_stroke(scene, data, options, guess, r, &centre, &spent);
      evaluations += spent;
      if (r == 0 || found.loss < best.loss) best = found;
    }
  }
  // The polish, from the best (or from `start`: a refit after the constants changed).
  StrokeObjective objective{&scene, &data, &options, best.shot, best, 0};
  local_stage(objective, kInf, options.local_evaluations, start ? 0.01 : 0.005);
  evaluations += objective.evaluations;
  best = evaluate_stroke(scene, data, objective.best.shot, objective.best.offset_s, options);
  best.evaluations = evaluations + 1;
  return best;
}

// ---- The rolling resistance from final rolls ----

namespace {

// Ball k's final straight roll, measured: the deceleration's mu_roll, or NaN when the
// samples hold no roll long enough to say.
double final_roll_mu(const std::vector<double>& t, const std::vector<phys::Vec2>& p,
                     double gravity) {
  size_t n = t.size();
  // The samples after the ball stopped (a ball at rest is not sampled, but the last
  // sample may be its resting place, long after the one before).
  while (n >= 2 && std::hypot(p[n - 1].x - p[n - 2].x, p[n - 1].y - p[n - 2].y) <
                       0.01 * std::max(t[n - 1] - t[n - 2], 1e-9))
    --n;
  // A last sample long after the one before is the resting place too.
  if (n >= 12) {
    std::vector<double> gaps;
    for (size_t i = n - 11; i + 1 < n - 1; ++i) gaps.push_back(t[i + 1] - t[i]);
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    if (t[n - 1] - t[n - 2] > 3.0 * gaps[gaps.size() / 2]) --n;
  }
  if (n < 16) return std::nan("");
  // The straight tail: samples within 3 cm of a line, walking back from the last sample
  // until three in a row leave it. The line: first through the last sample along the
  // direction of its last 30 cm, then the principal axis of the tail found with it.
  const auto from_end = [&](size_t i) { return std::hypot(p[n - 1].x - p[i].x, p[n - 1].y - p[i].y); };
  size_t far = n - 1;
  while (far > 0 && from_end(far) < 0.30) --far;
  phys::Vec2 d{p[n - 1].x - p[far].x, p[n - 1].y - p[far].y};
  const double len = std::hypot(d.x, d.y);
  if (len < 0.10) return std::nan("");
  d = {d.x / len, d.y / len};
  phys::Vec2 o = p[n - 1];
  size_t first = n - 1;
  for (int pass = 0; pass < 2; ++pass) {
    first = n - 1;
    int misses = 0;
    for (size_t i = n - 1; i-- > 0;) {
      const double rx = p[i].x - o.x, ry = p[i].y - o.y;
      if (std::fabs(rx * d.y - ry * d.x) > 0.03) {
        if (++misses == 3) break;
        continue;
      }
      misses = 0;
      first = i;
    }
    // The tail's principal axis (its centroid, the larger eigenvector of its scatter).
    double cx = 0, cy = 0;
    const double count = static_cast<double>(n - first);
    for (size_t i = first; i < n; ++i) cx += p[i].x, cy += p[i].y;
    cx /= count;
    cy /= count;
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t i = first; i < n; ++i) {
      sxx += (p[i].x - cx) * (p[i].x - cx);
      sxy += (p[i].x - cx) * (p[i].y - cy);
      syy += (p[i].y - cy) * (p[i].y - cy);
    }
    const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    phys::Vec2 axis{std::cos(angle), std::sin(angle)};
    if (axis.x * d.x + axis.y * d.y < 0.0) axis = {-axis.x, -axis.y};
    d = axis;
    o = {cx, cy};
  }
  // The ball may slide for a while after the contact that set it on this line: its first
  // 0.5 s (and at least its first third) are left out.
  const double start = std::max(t[first] + 0.5, t[first] + (t[n - 1] - t[first]) / 3.0);
  std::vector<double> ts, ss;
  for (size_t i = first; i < n; ++i)
    if (t[i] >= start) {
      ts.push_back(t[i]);
      ss.push_back((p[i].x - o.x) * d.x + (p[i].y - o.y) * d.y);
    }
  if (ts.size() < 12 || ts.back() - ts.front() < 0.8) return std::nan("");
  // s(t) = a + b u + c u^2 by least squares (u = t - mean): the deceleration is -2c.
  double mean = 0;
  for (double v : ts) mean += v;
  mean /= static_cast<double>(ts.size());
  double m[3][4] = {};
  for (size_t i = 0; i < ts.size(); ++i) {
    const double u = ts[i] - mean, basis[3] = {1.0, u, u * u};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m[r][c] += basis[r] * basis[c];
      m[r][3] += basis[r] * ss[i];
    }
  }
  for (int col = 0; col < 3; ++col) {  // Gauss-Jordan on the 3 x 3 normal equations
    int pivot = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::fabs(m[r][col]) > std::fabs(m[pivot][col])) pivot = r;
    if (std::fabs(m[pivot][col]) < 1e-12) return std::nan("");
    std::swap(m[col], m[pivot]);
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      const double f = m[r][col] / m[col][col];
      for (int c = col; c < 4; ++c) m[r][c] -= f * m[col][c];
    }
  }
  const double c2 = m[2][3] / m[2][2];
  const double decel = -2.0 * c2;
  return decel > 0.0 ? decel / gravity : std::nan("");
}

}  // namespace

RollingMeasurement measure_rolling_resistance(const std::vector<ShotData>& shots,
                                              const std::vector<size_t>& which) {
  RollingMeasurement m;
  std::vector<double> values;
  for (size_t i : which) {
    const ShotData& d = shots[i];
    for (size_t k = 0; k < d.p.size(); ++k) {
      const double mu = final_roll_mu(d.t[k], d.p[k], d.scene.cloth.gravity);
      if (std::isfinite(mu) && mu > 0.0005 && mu < 0.05) values.push_back(mu);
    }
  }
  m.rolls = static_cast<int>(values.size());
  if (values.empty()) return m;
  std::sort(values.begin(), values.end());
  const size_t h = values.size() / 2;
  m.mu_roll = values.size() % 2 ? values[h] : 0.5 * (values[h - 1] + values[h]);
  m.quartiles = {values[values.size() / 4], values[(3 * values.size()) / 4]};
  return m;
}

// ---- Calibration ----

std::vector<std::string> constant_names(const phys::Scene& s) {
  std::vector<std::string> names(std::begin(kConstantNames), std::end(kConstantNames));
  if (s.ball_and_cushion.model == phys::CushionModel::stronge_compliant) names.push_back(kEtaSquaredName);
  return names;
}

std::vector<double> constants_of(const phys::Scene& s) {
  std::vector<double> c{s.cloth.mu_slide,
                        s.cloth.mu_roll,
                        s.cloth.mu_spin,
                        s.ball_and_cushion.mu_cushion,
                        s.ball_and_cushion.restitution,
                        s.ball_and_cushion.cushion_height,
                        s.ball_contact.mu_ball,
                        s.ball_contact.restitution};
  if (s.ball_and_cushion.model == phys::CushionModel::stronge_compliant)
    c.push_back(s.ball_and_cushion.eta_squared);
  return c;
}

void set_constants(const std::vector<double>& c, phys::Scene* s) {
  s->cloth.mu_slide = s->ball_and_cushion.mu_table = c[0];
  s->cloth.mu_roll = c[1];
  s->cloth.mu_spin = c[2];
  s->ball_and_cushion.mu_cushion = c[3];
  s->ball_and_cushion.restitution = c[4];
  s->ball_and_cushion.cushion_height = c[5];
  s->ball_contact.mu_ball = c[6];
  s->ball_contact.restitution = c[7];
  if (c.size() > static_cast<size_t>(kConstantCount)) s->ball_and_cushion.eta_squared = c[kConstantCount];
}

std::vector<double> constant_lower_bounds(size_t count) {
  std::vector<double> lo{0.05, 0.001, 0.001, 0.0, 0.5, 0.032, 0.0, 0.7};
  if (count > lo.size()) lo.push_back(0.9);  // eta_squared
  return lo;
}
std::vector<double> constant_upper_bounds(size_t count) {
  std::vector<double> hi{0.5, 0.02, 0.06, 0.5, 1.0, 0.042, 0.2, 1.0};
  if (count > hi.size()) hi.push_back(3.4);  // eta_squared
  return hi;
}

namespace {

// The summed loss of `shots` (indices into all) with their strokes fixed.
struct ConstantsObjective {
  const std::vector<ShotData>* all;
  const std::vector<size_t>* shots;
  const std::vector<StrokeFit>* strokes;
  const FitOptions* fit;
  unsigned threads;
  std::vector<double> lo, hi;
  int refit_evaluations = 0;  // > 0: each stroke refitted (local) at every evaluation
  double best = kInf;
  std::vector<double> best_c;
  std::vector<double> constants(const double* u) const {
    std::vector<double> c(lo.size());
    for (size_t i = 0; i < c.size(); ++i) c[i] = lo[i] + u[i] * (hi[i] - lo[i]);
    return c;
  }
  double loss_at(const std::vector<double>& c) const {
    std::vector<double> losses(shots->size(), 0.0);
    parallel_for(shots->size(), threads, [&](size_t i, unsigned) {
      const ShotData& d = (*all)[(*shots)[i]];
      phys::Scene s = d.scene;
      set_constants(c, &s);
      const phys::CompiledScene cs(s);
      if (!cs.ok()) {
        losses[i] = kFailedLoss;
        return;
      }
      const StrokeFit& st = (*strokes)[(*shots)[i]];
      if (refit_evaluations > 0) {  // the stroke refitted inside (a profile of the loss)
        FitOptions quick = *fit;
        quick.local_evaluations = refit_evaluations;
        losses[i] = fit_stroke(cs, d, quick, &st).loss;
      } else {
        losses[i] = evaluate_stroke(cs, d, st.shot, st.offset_s, *fit).loss;
      }
    });
    double sum = 0;
    for (double l : losses) sum += l;
    return sum;
  }
  double operator()(const double* u) {
    const std::vector<double> c = constants(u);
    const double l = loss_at(c);
    if (l < best) {
      best = l;
      best_c = c;
    }
    return l;
  }
};

// Fits strokes of `shots` with constants `c` (full fits, or refits from `strokes`).
void fit_strokes(const std::vector<ShotData>& all, const std::vector<size_t>& shots,
                 const std::vector<double>& c, const FitOptions& fit, unsigned threads,
                 bool refit, std::vector<StrokeFit>* strokes) {
  parallel_for(shots.size(), threads, [&](size_t i, unsigned) {
    const ShotData& d = all[shots[i]];
    phys::Scene s = d.scene;
    set_constants(c, &s);
    const phys::CompiledScene cs(s);
    StrokeFit& st = (*strokes)[shots[i]];
    if (!cs.ok()) {
      st.rmse_cue_m = st.rmse_all_m = kInf;
      st.loss = kFailedLoss;
      return;
    }
    st = refit ? fit_stroke(cs, d, fit, &st) : fit_stroke(cs, d, fit);
  });
}

// Alternates constants (strokes fixed) and strokes (constants fixed) on `shots`.
std::vector<double> fit_constants(const std::vector<ShotData>& all, const std::vector<size_t>& shots,
                                  std::vector<double> c, std::vector<StrokeFit>* strokes,
                                  const CalibrationOptions& o, unsigned threads,
                                  const std::function<void(const std::string&)>& progress,
                                  const std::string& label,
                                  const std::vector<double>& strokes_fitted_with) {
  // Strokes fitted with other constants are refitted (locally) with these first.
  if (c != strokes_fitted_with) fit_strokes(all, shots, c, o.fit, threads, true, strokes);
  for (int round = 1; round <= o.rounds; ++round) {
    ConstantsObjective obj{&all,
                           &shots,
                           strokes,
                           &o.fit,
                           threads,
                           constant_lower_bounds(c.size()),
                           constant_upper_bounds(c.size()),
                           o.refit_evaluations,
                           kInf,
                           {}};
    std::vector<double> u(c.size());
    for (size_t i = 0; i < c.size(); ++i) u[i] = (c[i] - obj.lo[i]) / (obj.hi[i] - obj.lo[i]);
    obj.best = obj.loss_at(c);
    obj.best_c = c;
    const double before = obj.best;
    detail::StageSettings l;
    l.algorithm = NLOPT_LN_BOBYQA;
    l.max_evaluations = o.constant_evaluations;
    l.initial_step = o.constant_step;
    l.x_tolerance = 1e-5;
    int calls = 0;
    auto counted = [&obj, &calls](const double* x) {
      ++calls;
      return obj(x);
    };
    const nlopt_result code = detail::run_stage(l, &u, &counted);
    c = obj.best_c;
    fit_strokes(all, shots, c, o.fit, threads, /*refit=*/true, strokes);
    double after = 0;
    for (size_t i : shots) after += (*strokes)[i].loss;
    if (progress)
      progress(fmt::format(
          "{}: round {}: loss {:.5g} -> {:.5g} (constants, {} evaluations, NLopt {}), {:.5g} "
          "(strokes)",
          label, round, before, obj.best, calls, static_cast<int>(code), after));
  }
  return c;
}

}  // namespace

CalibrationResult calibrate(const std::vector<ShotData>& shots, const phys::Scene& start,
                            const CalibrationOptions& o,
                            const std::function<void(const std::string&)>& progress) {
  CalibrationResult res;
  const unsigned threads = thread_count(o.threads);
  const size_t n = shots.size();
  const int folds = std::max(1, std::min<int>(o.folds, static_cast<int>(n)));
  const std::vector<double> c0 = constants_of(start);
  std::vector<size_t> every(n);
  for (size_t i = 0; i < n; ++i) {
    every[i] = i;
    res.ids.push_back(shots[i].id);
    res.fold_of.push_back(static_cast<int>(i % static_cast<size_t>(folds)));
  }
  // The strokes with the starting constants: the "before" errors and every fold's start.
  std::vector<StrokeFit> base(n);
  if (progress) progress(fmt::format("fitting {} shots with the starting constants", n));
  fit_strokes(shots, every, c0, o.fit, threads, false, &base);
  for (const StrokeFit& f : base) res.rmse_before_m.push_back(f.rmse_cue_m);
  res.rmse_heldout_m.assign(n, kInf);
  // The constants' search is local, and the strokes fitted with the starting constants
  // absorb much of a wrong rolling resistance (the loss is flat for it round the start),
  // so mu_roll starts from what the training shots' final rolls measure; their strokes
  // are refitted locally with it before the search.
  const auto measured_start = [&](const std::vector<size_t>& train, const std::string& label) {
    std::vector<double> c = c0;
    if (!o.measure_rolling) return c;
    const RollingMeasurement m = measure_rolling_resistance(shots, train);
    res.measured_mu_roll.push_back(m.mu_roll);
    res.measured_rolls.push_back(m.rolls);
    if (m.rolls < 5) return c;
    c[1] = std::clamp(m.mu_roll, constant_lower_bounds()[1], constant_upper_bounds()[1]);
    if (progress)
      progress(fmt::format("{}: mu_roll {:.5g} from {} final rolls (quartiles {:.5g}, {:.5g})",
                           label, c[1], m.rolls, m.quartiles[0], m.quartiles[1]));
    return c;
  };
  for (int f = 0; f < folds && folds > 1; ++f) {
    std::vector<size_t> train, test;
    for (size_t i = 0; i < n; ++i) (res.fold_of[i] == f ? test : train).push_back(i);
    std::vector<StrokeFit> strokes = base;
    const std::string label = fmt::format("fold {}/{}", f + 1, folds);
    const std::vector<double> c = fit_constants(shots, train, measured_start(train, label),
                                                &strokes, o, threads, progress, label, c0);
    res.fold_constants.push_back(c);
    // Held out: each test shot's stroke fitted afresh with the fold's constants.
    fit_strokes(shots, test, c, o.fit, threads, false, &strokes);
    for (size_t i : test) res.rmse_heldout_m[i] = strokes[i].rmse_cue_m;
  }
  // The constants written out: fitted on every shot.
  std::vector<StrokeFit> strokes = base;
  res.constants = fit_constants(shots, every, measured_start(every, "all shots"), &strokes, o,
                                threads, progress, "all shots", c0);
  for (size_t i = 0; i < n; ++i) res.rmse_all_shots_m.push_back(strokes[i].rmse_cue_m);
  // Uncertainties: the spread across folds, and the change of one constant (strokes and
  // the others fixed) that raises the all-shot loss by 1 %.
  ConstantsObjective obj{&shots,
                         &every,
                         &strokes,
                         &o.fit,
                         threads,
                         constant_lower_bounds(c0.size()),
                         constant_upper_bounds(c0.size()),
                         o.refit_evaluations,
                         kInf,
                         {}};
  const double l0 = obj.loss_at(res.constants);
  const std::vector<std::string> names = constant_names(start);
  for (size_t i = 0; i < c0.size(); ++i) {
    ConstantReport r;
    r.name = names[i];
    r.value = res.constants[i];
    if (!res.fold_constants.empty()) {
      double mean = 0, var = 0;
      for (const auto& fc : res.fold_constants) mean += fc[i];
      mean /= static_cast<double>(res.fold_constants.size());
      for (const auto& fc : res.fold_constants) var += sq(fc[i] - mean);
      r.fold_spread = std::sqrt(var / static_cast<double>(res.fold_constants.size()));
    }
    const double h = 0.05 * (obj.hi[i] - obj.lo[i]);
    std::vector<double> plus = res.constants, minus = res.constants;
    plus[i] = std::min(obj.hi[i], plus[i] + h);
    minus[i] = std::max(obj.lo[i], minus[i] - h);
    const double rise = 0.5 * (obj.loss_at(plus) + obj.loss_at(minus)) - l0;
    const double step = 0.5 * (plus[i] - minus[i]);
    r.half_width = rise > 0 ? step * std::sqrt(0.01 * l0 / rise) : kInf;
    // Constrained: a 1 % rise within a fifth of the value (and of the search range).
    r.constrained = r.half_width < 0.2 * std::min(std::fabs(r.value), obj.hi[i] - obj.lo[i]);
    res.report.push_back(r);
  }
  return res;
}

}  // namespace cueplan::planner
