// Pots that the table's geometry rules out: another ball in the way of every straight
// line the pot's ball could take into its pocket, or of every straight path of the
// cue ball to a ghost ball that could send it there.
//
// The object ball's centre drops once it enters the pocket's capture circle (radius
// r_p around C), so from its centre O it must leave along a direction inside the cone
// that the circle subtends, widened by kDirectionMargin for the throw that the
// collision gives it and the slight swerve of a thrown ball. Along each such direction
// it travels at least |OC| - r_p before it can drop; a ball B whose centre comes within
// 2R of that segment is touched first. Directions are sampled every `step` radians:
// between samples the segment's end moves by at most L step / 2, so a blocker closer
// than 2R - L step / 2 at every sample blocks every direction in between (the distance
// from a point to a segment changes no faster than the segment's end moves).
//
// The cue ball strikes the object ball from the ghost position G = O - 2R d for a
// leaving direction d; its path from the strike to the contact is a straight line (a
// struck ball slides and rolls along its aim until its first event), so a ball within
// 2R of the segment from the cue ball to G, or a cut beyond 90 degrees (the cue ball
// cannot reach G's side of the object ball), rules out that ghost; the same sampling
// argument covers the arc of ghosts.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cueplan/physics/vec2.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::problems {
namespace {

using physics::Vec2;

constexpr double kDirectionMargin = 3.0 * std::numbers::pi / 180.0;  // rad, each side
constexpr int kSamples = 2048;  // directions across the cone
constexpr double kImpossibleCut = -0.05;  // cos of the cut: beyond about 93 degrees

using physics::vec2::operator-;
using physics::vec2::dot;
using physics::vec2::norm;

// Distance from p to the segment [a, b].
double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(p - Vec2{a.x + t * ab.x, a.y + t * ab.y});
}

struct Blocker {
  std::string name;
  Vec2 centre;
};

// The first blocker within `reach` of [a, b], or null.
const Blocker* blocking(const std::vector<Blocker>& blockers, Vec2 a, Vec2 b, double reach) {
  for (const Blocker& k : blockers)
    if (segment_distance(k.centre, a, b) < reach) return &k;
  return nullptr;
}

std::string names(const std::set<std::string>& set) {
  std::string text;
  size_t i = 0;
  for (const std::string& n : set) {
    text += (i == 0 ? "" : i + 1 == set.size() ? " and " : ", ") + n;
    ++i;
  }
  return text;
}

}  // namespace

std::optional<PotScreen> screened_pot(const Problem& problem) {
  if (!problem.pot || problem.required_first_contact() != problem.pot->ball) return std::nullopt;
  const physics::Scene& scene = problem.scene;
  const int pocket = problem.pot->pocket;
  if (pocket < 0 || pocket >= static_cast<int>(scene.pockets.size())) return std::nullopt;
  const double radius = scene.radius();
  const Vec2 c = scene.pockets[static_cast<size_t>(pocket)].centre;
  const double capture = scene.pockets[static_cast<size_t>(pocket)].radius;
  Vec2 o;
  std::vector<Blocker> blockers;
  for (const physics::ObjectBall& b : scene.balls) {
    if (b.name == problem.pot->ball) o = b.position;
    else blockers.push_back({b.name, b.position});
  }
  for (size_t i = 0; i < scene.obstacles.size(); ++i)
    blockers.push_back({fmt::format("obstacles[{}]", i), scene.obstacles[i]});

  const Vec2 oc = c - o;
  const double distance = norm(oc);
  if (!(distance > capture)) return std::nullopt;
  const double centre_angle = std::atan2(oc.y, oc.x);
  const double half = std::asin(capture / distance) + kDirectionMargin;
  const double step = 2.0 * half / (kSamples - 1);
  const double travel = distance - capture;  // the least it travels before it can drop
  const std::string pocket_words = "the " + pocket_name(scene, pocket) + " pocket";

  // The object ball's lines into the pocket.
  std::set<std::string> by;
  bool all_blocked = true;
  for (int i = 0; i < kSamples && all_blocked; ++i) {
    const double a = centre_angle - half + step * i;
    const Vec2 end{o.x + travel * std::cos(a), o.y + travel * std::sin(a)};
    const Blocker* k = blocking(blockers, o, end, 2.0 * radius - 0.5 * travel * step);
    if (k == nullptr) all_blocked = false;
    else by.insert(k->name);
  }
  if (all_blocked)
    return PotScreen{"the object ball's path", names(by),
                     fmt::format("no direct pot: {}'s path to {} is screened by {}",
                                 problem.pot->ball, pocket_words, names(by))};

  // The cue ball's paths to the ghost balls of those lines.
  by.clear();
  bool too_thin = false;
  all_blocked = true;
  const Vec2 q = problem.cue_ball;
  for (int i = 0; i < kSamples && all_blocked; ++i) {
    const double a = centre_angle - half + step * i;
    const Vec2 d{std::cos(a), std::sin(a)};
    const Vec2 ghost{o.x - 2.0 * radius * d.x, o.y - 2.0 * radius * d.y};
    const Vec2 path = ghost - q;
    const double length = norm(path);
    if (length > 0.0 && dot(path, d) / length < kImpossibleCut) {
      too_thin = true;
      continue;
    }
    const double slack = radius * step;  // the ghost moves 2R step between samples
    const Blocker* k = blocking(blockers, q, ghost, 2.0 * radius - slack);
    if (k == nullptr) all_blocked = false;
    else by.insert(k->name);
  }
  if (!all_blocked) return std::nullopt;
  std::string why;
  if (!by.empty())
    why = fmt::format("the cue ball's path to every ghost ball that sends {} into {} is screened by {}",
                      problem.pot->ball, pocket_words, names(by));
  if (too_thin)
    why += std::string(why.empty() ? "" : ", and ") +
           fmt::format("the cut to send {} into {} is {}more than 90 degrees", problem.pot->ball,
                       pocket_words, by.empty() ? "" : "elsewhere ");
  return PotScreen{"the cue ball's path", by.empty() ? std::string("the cut") : names(by),
                   "no direct pot: " + why};
}

}  // namespace cueplan::problems
