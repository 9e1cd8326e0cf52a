// Kicks, banks and escapes: mirror-image seeds per cushion sequence, the aim solved on
// the simulator for a small grid of speeds and spins.
#include "kick.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "cueplan/problems/ball_names.hpp"
#include "outcome.hpp"
#include "pot_aim.hpp"
#include "search_space.hpp"
#include "task.hpp"

namespace cueplan::planner::detail {
namespace {

using physics::Vec2;

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kMaxCut = 80.0;          // deg: a thinner cut is not a route
constexpr double kClearSlack = 1e-4;      // m: a leg passing exactly two radii off a ball is clear
constexpr double kOffsetTolerance = 5e-4;  // m: the cue ball's line against the one sought
constexpr double kPocketTolerance = 1e-3;  // m: the pot's ball's line against its pocket's centre
constexpr int kRootIterations = 8;
constexpr double kMaxAimStep = 3.0;       // deg
// Escapes may strike the ball on off its centre when the full-ball line is screened.
constexpr double kEscapeOffsets[] = {0.0, 1.3, -1.3};  // of R

Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 add(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 scale(Vec2 a, double s) { return {a.x * s, a.y * s}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 unit(Vec2 a) {
  const double n = norm(a);
  return n > 0.0 ? Vec2{a.x / n, a.y / n} : Vec2{1.0, 0.0};
}
Vec2 left_of(Vec2 u) { return {-u.y, u.x}; }

// The lines a ball's centre meets the cushions on (ShotEvent::cushion numbering).
struct Cushions {
  double length = 0.0, width = 0.0, inset = 0.0;
  double line(int c) const {
    switch (c) {
      case 0: return inset;
      case 1: return length - inset;
      case 2: return width - inset;
      default: return inset;
    }
  }
  static bool horizontal(int c) { return c == 0 || c == 2; }
  Vec2 reflect(Vec2 p, int c) const {
    const double k = line(c);
    return horizontal(c) ? Vec2{p.x, 2.0 * k - p.y} : Vec2{2.0 * k - p.x, p.y};
  }
  // Where the segment from p toward q crosses cushion c's line; empty when it does not
  // (ahead of p, before q).
  std::optional<Vec2> cross_line(Vec2 p, Vec2 q, int c) const {
    const double k = line(c);
    const double a = horizontal(c) ? p.y : p.x, b = horizontal(c) ? q.y : q.x;
    if (std::abs(b - a) < 1e-12) return std::nullopt;
    const double t = (k - a) / (b - a);
    if (!(t > 1e-9 && t < 1.0)) return std::nullopt;
    return add(p, scale(sub(q, p), t));
  }
};

// The ways a mirror line fails, counted per family for the ruled-out reasons.
struct Blocks {
  int lines = 0;
  std::set<std::string> screened_by;
  int screened = 0;
  int off_cushion = 0;
  int too_thin = 0;
};


class Geometry {
 public:
  explicit Geometry(const problems::Problem& problem)
      : problem_(problem), scene_(problem.scene), radius_(problem.scene.radius()) {
    cushions_ = {scene_.length, scene_.width, scene_.contact_offset()};
  }

  // The first ball (other than those skipped) within two radii of the segment, by name.
  std::optional<std::string> screen(Vec2 p, Vec2 q, const std::set<std::string>& skip,
                                    bool skip_cue) const {
    const auto near = [&](Vec2 c) {
      const Vec2 d = sub(q, p);
      const double len2 = dot(d, d);
      const double t = len2 > 0.0 ? std::clamp(dot(sub(c, p), d) / len2, 0.0, 1.0) : 0.0;
      return norm(sub(c, add(p, scale(d, t)))) < 2.0 * radius_ - kClearSlack;
    };
    for (const physics::ObjectBall& b : scene_.balls)
      if (!skip.count(b.name) && near(b.position)) return b.name;
    for (size_t i = 0; i < scene_.obstacles.size(); ++i)
      if (near(scene_.obstacles[i])) return fmt::format("obstacle {}", i);
    if (!skip_cue && near(problem_.cue_ball)) return std::string("the cue ball");
    return std::nullopt;
  }

  // Whether a bounce at x on cushion c meets the cushion's straight nose, out of every
  // pocket's mouth.
  bool on_nose(Vec2 x, int c) const {
    const bool h = Cushions::horizontal(c);
    const double along = h ? x.x : x.y;
    const double extent = h ? scene_.length : scene_.width;
    if (along < cushions_.inset || along > extent - cushions_.inset) return false;
    for (const physics::Pocket& p : scene_.pockets) {
      if (p.jaws) {
        for (int k = 0; k < 2; ++k) {
          if (p.jaws->cushion[k] != c) continue;
          const Vec2 t = p.jaws->nose_tangent[k];
          const double t_along = h ? t.x : t.y;
          const double pocket_along = h ? p.centre.x : p.centre.y;
          const double toward = pocket_along > t_along ? 1.0 : -1.0;
          // Past the straight nose toward the pocket, not beyond its centre (a middle
          // pocket's other side is the other point's).
          const double into = (along - t_along) * toward;
          if (into > -radius_ && into < std::abs(pocket_along - t_along) + radius_) return false;
        }
      } else {
        const double across = h ? std::abs(p.centre.y - (c == 0 ? 0.0 : scene_.width))
                                : std::abs(p.centre.x - (c == 3 ? 0.0 : scene_.length));
        const double pocket_along = h ? p.centre.x : p.centre.y;
        if (across < p.radius + radius_ && std::abs(along - pocket_along) < p.radius + radius_)
          return false;
      }
    }
    return true;
  }

  // The path from `from` off `sequence` to `to` by mirror images: the bounce points,
  // the first leg's direction and the last's, and the length. Empty with the reason
  // counted in *blocks when a bounce falls off a nose or a leg is screened.
  struct Path {
    std::vector<Vec2> bounces;
    Vec2 first, last;
    double length = 0.0;
  };
  std::optional<Path> mirror_path(Vec2 from, const std::vector<int>& sequence, Vec2 to,
                                  const std::set<std::string>& skip_early,
                                  const std::set<std::string>& skip_last, bool skip_cue,
                                  Blocks* blocks, bool screen_legs = true) const {
    std::vector<Vec2> images(sequence.size() + 1);
    images[sequence.size()] = to;
    for (size_t j = sequence.size(); j-- > 0;) images[j] = cushions_.reflect(images[j + 1], sequence[j]);
    Path path;
    Vec2 p = from;
    for (size_t j = 0; j < sequence.size(); ++j) {
      const std::optional<Vec2> x = cushions_.cross_line(p, images[j], sequence[j]);
      if (!x || !on_nose(*x, sequence[j])) {
        if (blocks) ++blocks->off_cushion;
        return std::nullopt;
      }
      path.bounces.push_back(*x);
      p = *x;
    }
    path.first = unit(sub(sequence.empty() ? to : path.bounces.front(), from));
    path.last = unit(sub(to, p));
    // Legs: every one but the last avoids skip_early's complement, the last skip_last's.
    Vec2 a = from;
    for (size_t j = 0; j <= path.bounces.size(); ++j) {
      const Vec2 b = j < path.bounces.size() ? path.bounces[j] : to;
      const bool last = j == path.bounces.size();
      if (const auto by = screen_legs ? screen(a, b, last ? skip_last : skip_early, skip_cue)
                                      : std::nullopt) {
        if (blocks) {
          ++blocks->screened;
          blocks->screened_by.insert(*by);
        }
        return std::nullopt;
      }
      path.length += norm(sub(b, a));
      a = b;
    }
    return path;
  }

  const Cushions& cushions() const { return cushions_; }
  double radius() const { return radius_; }

 private:
  const problems::Problem& problem_;
  const physics::Scene& scene_;
  double radius_;
  Cushions cushions_;
};

// Every sequence of n cushions with no cushion twice in a row.
std::vector<std::vector<int>> sequences(int n) {
  std::vector<std::vector<int>> out{{}};
  for (int k = 0; k < n; ++k) {
    std::vector<std::vector<int>> next;
    for (const std::vector<int>& s : out)
      for (int c = 0; c < 4; ++c)
        if (s.empty() || s.back() != c) {
          next.push_back(s);
          next.back().push_back(c);
        }
    out = std::move(next);
  }
  return out;
}

const char* count_word(int n) {
  static constexpr const char* kWords[] = {"no", "one", "two", "three", "four", "five"};
  return n >= 0 && n < 6 ? kWords[n] : "many";
}

std::string join(const std::set<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string why_not(const Blocks& b) {
  if (b.lines == 0) return "no ball to strike";
  std::vector<std::string> parts;
  if (b.screened > 0) parts.push_back(fmt::format("{} screened by {}", b.screened, join(b.screened_by)));
  if (b.off_cushion > 0)
    parts.push_back(fmt::format("{} bounce{} in a pocket's mouth or off the cushion", b.off_cushion,
                                b.off_cushion == 1 ? "s" : ""));
  if (b.too_thin > 0)
    parts.push_back(fmt::format("{} ask{} a cut thinner than {:.0f} deg", b.too_thin,
                                b.too_thin == 1 ? "s" : "", kMaxCut));
  std::string s = fmt::format("{} mirror line{}: ", b.lines, b.lines == 1 ? "" : "s");
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? "; " : "") + parts[i];
  return s;
}

// The signed offset (m, > 0 to the left) of `centre` from ball `b`'s path on its leg after
// `after` cushions: where the ball passes abeam of it, or, when the leg ends first (a
// contact, a cushion, the pocket, rest), where it ends, along its direction there.
std::optional<double> leg_offset(const physics::BallOutcome& b, int after, Vec2 centre) {
  if (b.path.empty()) return std::nullopt;
  // The leg starts where the ball was set moving (the strike, or the contact that
  // struck an object ball), or at its `after`-th cushion.
  double t_start = b.events.empty() ? 0.0 : b.events.front().time;
  int met = 0;
  if (after > 0) {
    bool found = false;
    for (const physics::ShotEvent& e : b.events)
      if (e.type == physics::EventType::cushion && ++met == after) {
        t_start = e.time;
        found = true;
        break;
      }
    if (!found) return std::nullopt;
  }
  double t_end = std::numeric_limits<double>::infinity();
  for (const physics::ShotEvent& e : b.events) {
    if (e.time <= t_start + 1e-12) continue;
    using physics::EventType;
    if (e.type == EventType::cushion || e.type == EventType::ball_contact ||
        e.type == EventType::pocket || e.type == EventType::jaw || e.type == EventType::obstacle ||
        e.type == EventType::rest) {
      t_end = e.time;
      break;
    }
  }
  const auto offset_at = [&](const physics::PathSegment& s, double t) -> std::optional<double> {
    Vec2 v = add(s.v0, scale(s.accel, t - s.t0));
    if (norm(v) < 1e-9) v = s.v0;
    if (norm(v) < 1e-9) return std::nullopt;
    return cross(unit(v), sub(centre, s.at(t)));
  };
  const physics::PathSegment* last = nullptr;
  double last_t = 0.0;
  bool first = true;
  for (const physics::PathSegment& s : b.path) {
    if (s.t1 <= t_start || s.t0 >= t_end) continue;
    const double a = std::max(s.t0, t_start), z = std::min(s.t1, t_end);
    const auto g = [&](double t) {
      return dot(sub(s.at(t), centre), add(s.v0, scale(s.accel, t - s.t0)));
    };
    if (first && g(a) >= 0.0) return offset_at(s, a);
    first = false;
    constexpr int kSamples = 8;
    double lo = a;
    for (int i = 1; i <= kSamples; ++i) {
      const double t = a + (z - a) * i / kSamples;
      if (g(t) >= 0.0) {
        double hi = t;
        for (int k = 0; k < 40; ++k) {
          const double mid = 0.5 * (lo + hi);
          (g(mid) >= 0.0 ? hi : lo) = mid;
        }
        return offset_at(s, hi);
      }
      lo = t;
    }
    last = &s;
    last_t = z;
  }
  if (last == nullptr) return std::nullopt;
  return offset_at(*last, last_t);
}

// A 1-D root of err in the aim: Newton from x0 with `slope` (per deg) until the error
// changes sign, then regula falsi (Illinois). Returns the aim at which |err| <= tol.
struct Root {
  double x = 0.0;
  bool found = false;
  physics::ShotResult result;  // the simulation at x
};
template <class Err>
Root solve_root(Err&& err, double x0, std::optional<double> slope, double tol,
                std::chrono::steady_clock::time_point deadline) {
  Root out;
  physics::ShotResult r;
  std::optional<double> e = err(x0, &r);
  if (!e) return out;
  double x = x0;
  std::optional<std::pair<double, double>> lo, hi;  // (aim, error) with error < 0, > 0
  std::optional<std::pair<double, double>> prev;
  int side_kept = 0;  // Illinois: the end kept twice in a row has its error halved
  for (int i = 0; i < kRootIterations; ++i) {
    if (std::abs(*e) <= tol) {
      out = {x, true, std::move(r)};
      return out;
    }
    if (std::chrono::steady_clock::now() >= deadline) return out;
    (*e < 0.0 ? lo : hi) = std::make_pair(x, *e);
    double next;
    if (lo && hi) {
      double elo = lo->second, ehi = hi->second;
      if (side_kept >= 2) elo *= 0.5;
      if (side_kept <= -2) ehi *= 0.5;
      next = lo->first + (hi->first - lo->first) * elo / (elo - ehi);
    } else {
      double m = slope.value_or(0.0);
      if (prev && prev->first != x) m = (*e - prev->second) / (x - prev->first);
      if (!(std::abs(m) > 1e-9)) {
        next = x + 0.02;  // probe for the slope
      } else {
        next = x + std::clamp(-*e / m, -kMaxAimStep, kMaxAimStep);
      }
    }
    prev = std::make_pair(x, *e);
    physics::ShotResult rn;
    std::optional<double> en = err(next, &rn);
    if (!en) {
      next = 0.5 * (x + next);
      en = err(next, &rn);
      if (!en) return out;
    }
    if (lo && hi) side_kept = *en < 0.0 ? std::min(side_kept, 0) - 1 : std::max(side_kept, 0) + 1;
    x = next;
    e = en;
    r = std::move(rn);
  }
  if (std::abs(*e) <= tol) out = {x, true, std::move(r)};
  return out;
}

// The ball's index in ShotResult::balls (1 + its index in Scene::balls); 0 when absent.
int ball_index(const physics::Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.balls.size(); ++i)
    if (scene.balls[i].name == name) return static_cast<int>(i) + 1;
  return 0;
}

}  // namespace

std::string family_name(int cue_cushions, int object_cushions, bool pot) {
  std::string s = cue_cushions == 0 ? std::string("direct")
                                    : fmt::format("{} cushion{}", count_word(cue_cushions),
                                                  cue_cushions == 1 ? "" : "s");
  if (pot && object_cushions > 0)
    s += fmt::format(", then a double off {} cushion{}", count_word(object_cushions),
                     object_cushions == 1 ? "" : "s");
  return s;
}

KickFamilies kick_families(const problems::Problem& problem, bool direct) {
  KickFamilies out;
  const Geometry geo(problem);
  const physics::Scene& scene = problem.scene;
  const double r = geo.radius();
  const problems::Limits& l = problem.limits;
  const bool pot = problem.pot.has_value();
  // The balls the cue ball may strike first.
  std::vector<std::string> targets;
  const std::string rule = problem.required_first_contact();
  for (const physics::ObjectBall& b : scene.balls)
    if (rule.empty() ? !pot : problems::contact_allowed(rule, b.name, scene.balls))
      targets.push_back(b.name);
  const int o_min = pot ? l.object_cushions_min : 0, o_max = pot ? l.object_cushions_max : 0;
  struct Ranked {
    KickRoute route;
    int cushions;
    double length;
  };
  std::vector<Ranked> found, bent;
  // The cue ball's mirror path to `to`, its failures counted in *blocks; a path whose
  // legs only other balls screen (its bounces on the noses) in *screened.
  const auto cue_path = [&](const std::vector<int>& seq, Vec2 to,
                            const std::set<std::string>& skip_last, Blocks* blocks,
                            std::optional<Geometry::Path>* screened) {
    Blocks local;
    std::optional<Geometry::Path> path =
        geo.mirror_path(problem.cue_ball, seq, to, {}, skip_last, true, &local);
    blocks->screened += local.screened;
    blocks->off_cushion += local.off_cushion;
    blocks->screened_by.insert(local.screened_by.begin(), local.screened_by.end());
    if (!path && local.screened > 0 && local.off_cushion == 0 && !seq.empty())
      *screened = geo.mirror_path(problem.cue_ball, seq, to, {}, skip_last, true, nullptr, false);
    return path;
  };
  for (int c = l.cushions_before_contact_min; c <= l.cushions_before_contact_max && c <= 3; ++c) {
    const std::vector<std::vector<int>> cue_sequences = sequences(c);
    for (int o = o_min; o <= o_max && o <= 2; ++o) {
      if (!direct && c == 0 && o == 0) continue;
      ++out.families;
      Blocks blocks;
      bool any = false;
      for (const std::string& name : targets) {
        const int index = ball_index(scene, name);
        const Vec2 centre = scene.balls[static_cast<size_t>(index - 1)].position;
        const std::set<std::string> skip_last{name};
        const std::set<std::string> skip_none;
        if (!pot) {
          for (const std::vector<int>& seq : cue_sequences) {
            for (double k : kEscapeOffsets) {
              ++blocks.lines;
              // The line passing `centre` at offset b: iterate its last leg's direction.
              const double b = k * r;
              std::optional<Geometry::Path> path = geo.mirror_path(
                  problem.cue_ball, seq, centre, skip_none, skip_last, true, nullptr, false);
              Vec2 u = path ? path->last : unit(sub(centre, problem.cue_ball));
              Vec2 contact = centre;
              for (int it = 0; it < 3; ++it) {
                const Vec2 n = left_of(u);
                contact = sub(sub(centre, scale(n, b)), scale(u, std::sqrt(4 * r * r - b * b)));
                path = geo.mirror_path(problem.cue_ball, seq, contact, skip_none, skip_last, true,
                                       nullptr, false);
                if (!path) break;
                u = path->last;
              }
              std::optional<Geometry::Path> screened;
              path = cue_path(seq, contact, skip_last, &blocks, &screened);
              if (!path) {
                if (screened && k == 0.0) {
                  KickRoute route;
                  route.cue_cushions = seq;
                  route.cue_bounces = screened->bounces;
                  route.ball = index;
                  route.ball_name = name;
                  route.seed_aim_deg =
                      wrap_degrees(std::atan2(screened->first.y, screened->first.x) * kDeg);
                  route.cue_length = screened->length;
                  route.screened = true;
                  bent.push_back({route, c, screened->length});
                }
                continue;
              }
              KickRoute route;
              route.cue_cushions = seq;
              route.cue_bounces = path->bounces;
              route.ball = index;
              route.ball_name = name;
              route.offset_m = b;
              route.seed_aim_deg = wrap_degrees(std::atan2(path->first.y, path->first.x) * kDeg);
              route.cue_length = path->length;
              found.push_back({route, c, path->length + std::abs(k) * 0.05});
              any = true;
              break;  // the fullest clear hit of this sequence and ball
            }
          }
          continue;
        }
        // A pot: the pot's ball off its sequence to the pocket, then the cue ball to its ghost.
        const physics::Pocket& pocket = scene.pockets.at(static_cast<size_t>(problem.pot->pocket));
        for (const std::vector<int>& oseq : sequences(o)) {
          Blocks object_blocks;
          const std::optional<Geometry::Path> opath =
              geo.mirror_path(centre, oseq, pocket.centre, skip_last, skip_last, true, &object_blocks);
          if (!opath) {
            blocks.lines += static_cast<int>(cue_sequences.size());
            blocks.screened += object_blocks.screened ? static_cast<int>(cue_sequences.size()) : 0;
            blocks.off_cushion += object_blocks.off_cushion ? static_cast<int>(cue_sequences.size()) : 0;
            blocks.screened_by.insert(object_blocks.screened_by.begin(), object_blocks.screened_by.end());
            continue;
          }
          const Vec2 d = opath->first;
          const Vec2 ghost = sub(centre, scale(d, 2.0 * r));
          for (const std::vector<int>& seq : cue_sequences) {
            ++blocks.lines;
            std::optional<Geometry::Path> screened;
            std::optional<Geometry::Path> path = cue_path(seq, ghost, skip_last, &blocks, &screened);
            const bool clear = path.has_value();
            if (!clear) path = screened;
            if (!path) continue;
            const Vec2 u = path->last;
            const double cut = std::acos(std::clamp(dot(u, d), -1.0, 1.0)) * kDeg;
            if (cut > kMaxCut) {
              if (clear) ++blocks.too_thin;
              continue;
            }
            KickRoute route;
            route.cue_cushions = seq;
            route.cue_bounces = path->bounces;
            route.ball = index;
            route.ball_name = name;
            route.offset_m = 2.0 * r * cross(u, d);
            route.object_cushions = oseq;
            route.object_bounces = opath->bounces;
            route.seed_aim_deg = wrap_degrees(std::atan2(path->first.y, path->first.x) * kDeg);
            route.cue_length = path->length;
            route.object_length = opath->length;
            route.cut_deg = cut;
            route.screened = !clear;
            (clear ? found : bent).push_back({route, c + o, path->length + opath->length + 0.01 * cut});
            any = any || clear;
          }
        }
      }
      if (!any) out.ruled_out.push_back(family_name(c, o, pot) + ": " + why_not(blocks));
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const Ranked& a, const Ranked& b) {
    if (a.cushions != b.cushions) return a.cushions < b.cushions;
    return a.length < b.length;
  });
  for (Ranked& f : found) out.routes.push_back(std::move(f.route));
  std::stable_sort(bent.begin(), bent.end(), [](const Ranked& a, const Ranked& b) {
    if (a.cushions != b.cushions) return a.cushions < b.cushions;
    return a.length < b.length;
  });
  for (Ranked& f : bent) out.screened.push_back(std::move(f.route));
  return out;
}

std::vector<physics::Shot> solve_kick(const Task& task, const KickRoute& route,
                                      const physics::SimulationOptions& simulation,
                                      std::chrono::steady_clock::time_point deadline, int keep,
                                      int* simulations) {
  const problems::Problem& problem = task.problem;
  const physics::Scene& scene = problem.scene;
  const problems::Limits& l = problem.limits;
  physics::SimulationOptions sim = simulation;
  sim.record_path = true;
  const Vec2 centre = scene.balls.at(static_cast<size_t>(route.ball - 1)).position;
  const int c = static_cast<int>(route.cue_cushions.size());
  const int o = static_cast<int>(route.object_cushions.size());
  const bool pot = problem.pot.has_value();
  // Speeds: enough to carry the cue ball (and a pot's ball, slowed by the cut) there.
  const double reach = route.cue_length +
                       (pot ? route.object_length /
                                  std::max(0.35, std::cos(route.cut_deg / kDeg))
                            : 0.0);
  const double base = std::clamp(0.9 + 0.45 * reach + 0.15 * (c + o), l.speed_min, l.speed_max);
  const std::vector<double> speeds{base, std::clamp(1.4 * base, l.speed_min, l.speed_max)};
  // Spins, centre ball first; scaled into the spin limit.
  const std::vector<std::pair<double, double>> spins{
      {0.0, 0.0}, {0.5, 0.0}, {-0.5, 0.0}, {0.0, 0.5}, {0.0, -0.5}, {0.0, 1.0}, {0.0, -1.0}};
  std::vector<physics::Shot> solved;
  std::set<std::pair<double, double>> tried;
  const physics::Pocket* pocket =
      pot ? &scene.pockets.at(static_cast<size_t>(problem.pot->pocket)) : nullptr;
  for (const auto& [kt0, ks0] : spins) {
    const double k = std::hypot(kt0, ks0);
    const double shrink = k > l.spin_max ? l.spin_max / k : 1.0;
    const double kt = kt0 * shrink, ks = ks0 * shrink;
    if (!tried.insert({kt, ks}).second) continue;
    for (double speed : speeds) {
      if (std::chrono::steady_clock::now() >= deadline ||
          static_cast<int>(solved.size()) >= keep)
        return solved;
      physics::Shot shot{speed, route.seed_aim_deg, kt, ks, l.elevation_min_deg};
      const auto play = [&](double aim, physics::ShotResult* r) {
        shot.aim_deg = wrap_degrees(aim);
        *r = task.simulate(shot, sim);
        ++*simulations;
      };
      // The cue ball's line to the ball, then (a pot) the pot's ball's to its pocket.
      const auto cue_error = [&](double aim, physics::ShotResult* r) -> std::optional<double> {
        play(aim, r);
        if (r->balls.empty()) return std::nullopt;
        const std::optional<double> off = leg_offset(r->balls.front(), c, centre);
        if (!off) return std::nullopt;
        return route.offset_m - *off;
      };
      // Counter-clockwise aim moves the line left of the ball: the centre falls to its
      // right (offset down), and each cushion mirrors that.
      const double slope = (c % 2 == 0 ? 1.0 : -1.0) * route.cue_length / kDeg;
      const double x0 = route.seed_aim_deg - squirt_of(problem, shot);
      Root root = solve_root(cue_error, x0, slope, pot ? 4.0 * kOffsetTolerance : kOffsetTolerance,
                             deadline);
      if (!root.found) continue;
      if (pot) {
        const auto object_error = [&](double aim, physics::ShotResult* r) -> std::optional<double> {
          play(aim, r);
          if (r->balls.size() <= static_cast<size_t>(route.ball)) return std::nullopt;
          if (r->first_contact != route.ball) return std::nullopt;
          return leg_offset(r->balls[static_cast<size_t>(route.ball)], o, pocket->centre);
        };
        root = solve_root(object_error, root.x, std::nullopt, kPocketTolerance, deadline);
        if (!root.found) continue;
      }
      shot.aim_deg = wrap_degrees(root.x);
      if (problems::check_stroke(problem, shot, root.result).solves()) {
        solved.push_back(shot);
        break;  // this spin works: the next spin
      }
    }
  }
  return solved;
}

namespace {

struct Combination {
  Vec2 cue, first, ball, pocket;  // the cue ball, the two balls' centres, the pocket's
  Vec2 cue_ghost, ball_ghost;     // where the cue ball strikes the first, the first the pot's ball
  double length = 0.0;
  double cue_cut_deg = 0.0;
};

constexpr double kMaxCombinationCut = 60.0;        // deg: the cue ball on the first ball
constexpr double kMaxCombinationSecondCut = 45.0;  // deg: the first ball on the pot's ball

std::optional<Combination> combination(const problems::Problem& problem) {
  if (!problem.pot || !problem.first_contact) return std::nullopt;
  const physics::Scene& scene = problem.scene;
  const int a = ball_index(scene, *problem.first_contact), b = ball_index(scene, problem.pot->ball);
  if (a == 0 || b == 0 || a == b || problem.pot->pocket < 0 ||
      problem.pot->pocket >= static_cast<int>(scene.pockets.size()))
    return std::nullopt;
  const double r = scene.radius();
  Combination c;
  c.cue = problem.cue_ball;
  c.first = scene.balls[static_cast<size_t>(a - 1)].position;
  c.ball = scene.balls[static_cast<size_t>(b - 1)].position;
  c.pocket = scene.pockets[static_cast<size_t>(problem.pot->pocket)].centre;
  const Vec2 u = unit(sub(c.pocket, c.ball));
  c.ball_ghost = sub(c.ball, scale(u, 2.0 * r));
  const Vec2 d = unit(sub(c.ball_ghost, c.first));
  c.cue_ghost = sub(c.first, scale(d, 2.0 * r));
  const Vec2 v = unit(sub(c.cue_ghost, c.cue));
  c.cue_cut_deg = std::acos(std::clamp(dot(v, d), -1.0, 1.0)) * kDeg;
  const double second_cut = std::acos(std::clamp(dot(d, u), -1.0, 1.0)) * kDeg;
  if (c.cue_cut_deg > kMaxCombinationCut || second_cut > kMaxCombinationSecondCut) return std::nullopt;
  if (dot(sub(c.ball_ghost, c.first), d) <= 0.0 || norm(sub(c.ball_ghost, c.first)) < 2.0 * r)
    return std::nullopt;
  const Geometry geo(problem);
  const std::string& first = *problem.first_contact;
  const std::string& pot = problem.pot->ball;
  if (geo.screen(c.cue, c.cue_ghost, {first}, true) || geo.screen(c.first, c.ball_ghost, {first, pot}, true) ||
      geo.screen(c.ball, c.pocket, {pot}, true))
    return std::nullopt;
  c.length = norm(sub(c.cue_ghost, c.cue)) + norm(sub(c.ball_ghost, c.first)) + norm(sub(c.pocket, c.ball));
  return c;
}

}  // namespace

std::optional<double> combination_length(const problems::Problem& problem) {
  const std::optional<Combination> c = combination(problem);
  if (!c) return std::nullopt;
  return c->length;
}

std::vector<physics::Shot> solve_combination(const Task& task, const physics::SimulationOptions& simulation,
                                             int keep, int* simulations) {
  std::vector<physics::Shot> solved;
  const problems::Problem& problem = task.problem;
  const std::optional<Combination> c = combination(problem);
  if (!c) return solved;
  const problems::Limits& l = problem.limits;
  const int first = ball_index(problem.scene, *problem.first_contact);
  const int pot = ball_index(problem.scene, problem.pot->ball);
  physics::SimulationOptions sim = simulation;
  sim.record_path = true;
  // Enough speed to carry both balls, slowed by the two cuts.
  const double base = std::clamp(1.2 + 0.6 * c->length / std::max(0.4, std::cos(c->cue_cut_deg / kDeg)),
                                 l.speed_min, l.speed_max);
  const double seed_aim = std::atan2(c->cue_ghost.y - c->cue.y, c->cue_ghost.x - c->cue.x) * kDeg;
  const std::vector<std::pair<double, double>> spins{{0.0, 0.0}, {0.5, 0.0}, {-0.5, 0.0}};
  for (const auto& [kt0, ks] : spins) {
    const double kt = std::clamp(kt0, -l.spin_max, l.spin_max);
    for (double speed : {base, std::clamp(1.4 * base, l.speed_min, l.speed_max)}) {
      if (static_cast<int>(solved.size()) >= keep) return solved;
      physics::Shot shot{speed, seed_aim, kt, ks, l.elevation_min_deg};
      const auto error = [&](double aim, physics::ShotResult* r) -> std::optional<double> {
        shot.aim_deg = wrap_degrees(aim);
        *r = task.simulate(shot, sim);
        ++*simulations;
        if (r->first_contact != first || r->balls.size() <= static_cast<size_t>(pot)) return std::nullopt;
        return leg_offset(r->balls[static_cast<size_t>(pot)], 0, c->pocket);
      };
      const Root root = solve_root(error, seed_aim - squirt_of(problem, shot), std::nullopt, kPocketTolerance,
                                   std::chrono::steady_clock::time_point::max());
      if (!root.found) continue;
      shot.aim_deg = wrap_degrees(root.x);
      if (problems::check_stroke(problem, shot, root.result).solves()) {
        solved.push_back(shot);
        break;
      }
    }
  }
  return solved;
}

namespace {

std::string cushion_words(int c) {
  switch (c) {
    case 0: return "the bottom cushion";
    case 1: return "the right end cushion";
    case 2: return "the top cushion";
    case 3: return "the left end cushion";
  }
  return "a cushion";
}

std::string cushion_list(const std::vector<int>& cushions) {
  std::string s;
  for (size_t i = 0; i < cushions.size(); ++i)
    s += (i == 0 ? "" : i + 1 == cushions.size() ? " and " : ", ") + cushion_words(cushions[i]);
  return s;
}

std::string pocket_words(const physics::Scene& scene, int pocket) {
  std::string name = problems::pocket_name(scene, pocket);
  std::replace(name.begin(), name.end(), '_', ' ');
  if (name.find("middle") == std::string::npos && name.rfind("pocket", 0) != 0)
    name += " corner";
  return "the " + name + " pocket";
}

std::string thickness_words(double cut_deg) {
  const std::string t = thickness_of(cut_deg);
  if (t == "full") return "full";
  if (t == "3/4") return "three-quarter ball";
  if (t == "half") return "half ball";
  if (t == "1/4") return "quarter ball";
  return "thin";
}

}  // namespace

std::string route_words(const problems::Problem& problem, const physics::Shot& shot,
                        const physics::ShotResult& result) {
  if (problem.required_first_contact().empty() || result.balls.empty()) return {};
  const physics::BallOutcome& cue = result.balls.front();
  std::vector<int> before;
  const physics::ShotEvent* contact = nullptr;
  const physics::ShotEvent* incoming = nullptr;
  for (const physics::ShotEvent& e : cue.events) {
    if (e.type == physics::EventType::ball_contact) {
      contact = &e;
      break;
    }
    if (e.type == physics::EventType::cushion) before.push_back(e.cushion);
    incoming = &e;
  }
  std::string s = before.empty() ? std::string("direct")
                                 : fmt::format("{} cushion{} off {}", count_word(static_cast<int>(before.size())),
                                               before.size() == 1 ? "" : "s", cushion_list(before));
  if (shot.sidespin_k >= kCentreK) s += ", right-hand side";
  if (shot.sidespin_k <= -kCentreK) s += ", left-hand side";
  if (contact == nullptr || result.first_contact <= 0 ||
      result.first_contact >= static_cast<int>(result.balls.size()))
    return s + ", striking no ball";
  const physics::BallOutcome& struck = result.balls[static_cast<size_t>(result.first_contact)];
  double cut = 0.0;
  if (incoming != nullptr && norm(incoming->velocity) > 0.0) {
    const Vec2 centres = unit(sub(struck.start, contact->position));
    cut = std::acos(std::clamp(dot(unit(incoming->velocity), centres), -1.0, 1.0)) * kDeg;
  }
  s += fmt::format(", to hit the {} {}", struck.name, thickness_words(cut));
  if (!problem.pot) return s;
  const physics::BallOutcome* ball = nullptr;
  for (const physics::BallOutcome& b : result.balls)
    if (b.name == problem.pot->ball) ball = &b;
  if (ball == nullptr) return s;
  std::vector<int> off;
  for (const physics::ShotEvent& e : ball->events)
    if (e.type == physics::EventType::cushion) off.push_back(e.cushion);
  const problems::BallKind kind = problems::identify_ball(ball->name).kind;
  const bool pool = kind == problems::BallKind::pool_solid || kind == problems::BallKind::pool_eight ||
                    kind == problems::BallKind::pool_stripe;
  if (!ball->pocketed) return s + fmt::format("; the {} stays out", ball->name);
  s += "; the " + ball->name;
  if (!off.empty()) s += fmt::format(" {} off {}", pool ? "banks" : "doubles", cushion_list(off));
  s += " into " + pocket_words(problem.scene, ball->pocket);
  return s;
}

double easiest_pot(const problems::Problem& problem, const physics::ShotResult& result,
                   double aim_sigma_deg) {
  if (result.status != physics::ShotStatus::rest || result.balls.empty()) return 0.0;
  const physics::Scene& scene = problem.scene;
  const double r = scene.radius();
  const Vec2 cue = result.balls.front().final_position;
  std::vector<Vec2> at;  // every ball left on the table, the cue ball first
  at.push_back(cue);
  for (size_t k = 1; k < result.balls.size(); ++k)
    if (!result.balls[k].pocketed) at.push_back(result.balls[k].final_position);
  const size_t balls_end = at.size();  // obstacles are in the way, never potted
  for (const Vec2& o : scene.obstacles) at.push_back(o);
  const auto clear = [&](Vec2 p, Vec2 q, size_t skip_a, size_t skip_b) {
    const Vec2 d = sub(q, p);
    const double len2 = dot(d, d);
    for (size_t i = 0; i < at.size(); ++i) {
      if (i == skip_a || i == skip_b) continue;
      const double t = len2 > 0.0 ? std::clamp(dot(sub(at[i], p), d) / len2, 0.0, 1.0) : 0.0;
      if (norm(sub(at[i], add(p, scale(d, t)))) < 2.0 * r) return false;
    }
    return true;
  };
  const double sigma = std::max(1e-6, aim_sigma_deg / kDeg);
  double best = 0.0;
  for (size_t b = 1; b < balls_end; ++b) {
    for (const physics::Pocket& pocket : scene.pockets) {
      const Vec2 to_pocket = sub(pocket.centre, at[b]);
      const double d_op = norm(to_pocket);
      if (!(d_op > 0.0)) continue;
      const Vec2 dir = scale(to_pocket, 1.0 / d_op);
      const Vec2 ghost = sub(at[b], scale(dir, 2.0 * r));
      const Vec2 to_ghost = sub(ghost, cue);
      const double d_cp = norm(to_ghost);
      if (!(d_cp > 0.0)) continue;
      const double cos_cut = dot(scale(to_ghost, 1.0 / d_cp), dir);
      if (cos_cut < std::cos(75.0 / kDeg)) continue;
      if (!clear(at[b], pocket.centre, b, b) || !clear(cue, ghost, 0, b)) continue;
      const double margin = std::atan(std::max(0.0, pocket.radius - 0.5 * r) / d_op);
      const double aim_margin = margin * 2.0 * r * cos_cut / d_cp;
      best = std::max(best, std::erf(aim_margin / (std::sqrt(2.0) * sigma)));
    }
  }
  return best;
}

}  // namespace cueplan::planner::detail
