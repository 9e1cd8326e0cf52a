// Run-outs: the policy (a stroke chosen among legal pots by the value of where the cue
// ball stops) and its rollouts under the execution noise. See runout.hpp.
#include "cueplan/planner/runout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "cueplan/planner/position.hpp"

#include "cueplan/physics/parallel.hpp"
#include "kick.hpp"
#include "pot_aim.hpp"
#include "robustness.hpp"
#include "task.hpp"

namespace cueplan::planner {
namespace {

using physics::Vec2;

Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 add(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 mul(Vec2 a, double k) { return {a.x * k, a.y * k}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 unit(Vec2 a) {
  const double n = norm(a);
  return n > 0.0 ? mul(a, 1.0 / n) : Vec2{1.0, 0.0};
}

const physics::ObjectBall* find_ball(const std::vector<physics::ObjectBall>& balls, const std::string& name) {
  for (const physics::ObjectBall& b : balls)
    if (b.name == name) return &b;
  return nullptr;
}

Vec2 clamp_to_table(const physics::Scene& scene, Vec2 p) {
  const double r = 1.5 * scene.radius();
  return {std::clamp(p.x, r, scene.length - r), std::clamp(p.y, r, scene.width - r)};
}

// Places the cue ball could be sent to after potting `ball` (at b) into the pocket at
// `pocket_centre` from `from`: the ghost ball, drawn back, and along the tangent line.
std::vector<Vec2> places_after(const physics::Scene& scene, Vec2 from, Vec2 b, Vec2 pocket_centre) {
  const double R = scene.radius();
  const Vec2 u = unit(sub(pocket_centre, b));
  const Vec2 g = sub(b, mul(u, 2.0 * R));
  const Vec2 v = unit(sub(g, from));
  Vec2 t = sub(v, mul(u, dot(v, u)));
  std::vector<Vec2> out{g, sub(g, mul(v, 0.3))};
  if (norm(t) < 1e-6) {  // a straight pot: either side is as near
    const Vec2 n{-u.y, u.x};
    for (double s : {0.35, -0.35}) out.push_back(add(g, mul(n, s)));
  } else {
    t = unit(t);
    for (double s : {0.3, 0.7, 1.1}) out.push_back(add(g, mul(t, s)));
    out.push_back(add(g, mul(u, 0.25)));
  }
  for (Vec2& p : out) p = clamp_to_table(scene, p);
  return out;
}

}  // namespace

const char* to_string(RunPolicy policy) { return policy == RunPolicy::greedy ? "greedy" : "planner"; }

bool parse_run_policy(const std::string& name, RunPolicy* policy) {
  if (name == "planner") *policy = RunPolicy::planner;
  else if (name == "greedy") *policy = RunPolicy::greedy;
  else return false;
  return true;
}

double pot_chance_estimate(const physics::Scene& scene, Vec2 cue, const std::string& ball, int pocket,
                           const std::vector<physics::ObjectBall>& balls, const NoiseModel& noise) {
  if (find_ball(balls, ball) == nullptr || pocket < 0 || pocket >= static_cast<int>(scene.pockets.size()))
    return 0.0;
  physics::Scene layout = scene;
  layout.balls = balls;
  return PositionField::pot_chance(layout, cue, ball, pocket, noise);
}

namespace {

// The position fields of single pots (PositionField, no grid), kept per layout of the
// balls: the noisy strokes of one decision leave the same balls again and again, and
// the look-ahead asks each layout's pots from several places. A layout's field of a pot
// is built at the first question about that pot (under its std::call_once) and never
// changes after: reading it takes no lock. Thread-safe; owned by the PositionValue that
// uses it.
class PotFields {
 public:
  // Every pot of one layout: slot ball index x pockets + pocket, the balls as given.
  struct Layout {
    struct Slot {
      std::once_flag once;
      std::optional<PositionField> field;
    };
    std::vector<physics::ObjectBall> balls;
    const PotFields* owner = nullptr;
    std::unique_ptr<Slot[]> slots;

    // P(pot balls[index] into `pocket`) from `cue`.
    double chance(size_t index, int pocket, Vec2 cue) const {
      const size_t pockets = owner->scene_.pockets.size();
      Slot& slot = slots[index * pockets + static_cast<size_t>(pocket)];
      std::call_once(slot.once, [&] {
        physics::Scene s = owner->scene_;
        s.balls = balls;
        slot.field.emplace(s, std::vector<problems::NextPot>{{balls[index].name, pocket}}, owner->noise_, 0.02,
                           FieldGrid::lazy);
      });
      return slot.field->next_shot(cue).p;
    }
    // The index of `ball`, or balls.size() without it.
    size_t index_of(const std::string& ball) const {
      for (size_t i = 0; i < balls.size(); ++i)
        if (balls[i].name == ball) return i;
      return balls.size();
    }
  };

  PotFields(const physics::Scene& scene, const NoiseModel& noise) : scene_(scene), noise_(noise) {
    scene_.balls.clear();
  }

  const Layout& layout(const std::vector<physics::ObjectBall>& balls) {
    const uint64_t h = hash_of(balls);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (const Layout* l = find(h, balls)) return *l;
    }
    auto built = std::make_unique<Layout>();
    built->balls = balls;
    built->owner = this;
    built->slots = std::make_unique<Layout::Slot[]>(balls.size() * scene_.pockets.size());
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const Layout* l = find(h, balls)) return *l;
    layouts_[h].push_back(std::move(built));
    return *layouts_[h].back();
  }

  // P(pot `ball` into `pocket`) from `cue` with `balls` on the table (0 without the ball
  // or the pocket).
  double chance(Vec2 cue, const std::string& ball, int pocket, const std::vector<physics::ObjectBall>& balls) {
    if (pocket < 0 || static_cast<size_t>(pocket) >= scene_.pockets.size()) return 0.0;
    const Layout& l = layout(balls);
    const size_t i = l.index_of(ball);
    return i < l.balls.size() ? l.chance(i, pocket, cue) : 0.0;
  }

 private:
  static uint64_t hash_of(const std::vector<physics::ObjectBall>& balls) {
    uint64_t h = 1469598103934665603ULL;  // FNV-1a
    const auto mix = [&h](const void* data, size_t n) {
      const auto* p = static_cast<const unsigned char*>(data);
      for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
    };
    for (const physics::ObjectBall& b : balls) {
      mix(b.name.data(), b.name.size());
      mix(&b.position.x, sizeof b.position.x);
      mix(&b.position.y, sizeof b.position.y);
    }
    return h;
  }
  // Under the lock.
  const Layout* find(uint64_t h, const std::vector<physics::ObjectBall>& balls) const {
    const auto it = layouts_.find(h);
    if (it == layouts_.end()) return nullptr;
    for (const std::unique_ptr<Layout>& l : it->second) {
      bool same = l->balls.size() == balls.size();
      for (size_t i = 0; same && i < balls.size(); ++i)
        same = l->balls[i].name == balls[i].name && l->balls[i].position.x == balls[i].position.x &&
               l->balls[i].position.y == balls[i].position.y;
      if (same) return l.get();
    }
    return nullptr;
  }

  physics::Scene scene_;  // the table; its balls come with each layout
  NoiseModel noise_;
  std::mutex mutex_;
  std::unordered_map<uint64_t, std::vector<std::unique_ptr<Layout>>> layouts_;
};

}  // namespace

namespace {

// The POSITION OBJECTIVE of position_estimate, on the fields `fields` keeps.
PositionValue position_value(std::shared_ptr<PotFields> fields, const physics::Scene& scene, int lookahead,
                             int beam) {
  lookahead = std::max(1, lookahead);
  beam = std::max(1, beam);
  return [scene, fields = std::move(fields), lookahead, beam](
             Vec2 cue, const problems::GameState& state,
             const std::vector<physics::ObjectBall>& balls) -> double {
    if (state.cleared) return 1.0;
    struct Node {
      double value = 1.0;
      std::vector<Vec2> places;  // where the cue ball may be
      problems::GameState state;
      std::vector<physics::ObjectBall> balls;
    };
    std::vector<Node> frontier{{1.0, {cue}, state, balls}};
    double best = 0.0;
    for (int depth = 0; depth < lookahead && !frontier.empty(); ++depth) {
      std::vector<Node> next;
      for (const Node& node : frontier) {
        const PotFields::Layout& layout = fields->layout(node.balls);
        for (const std::string& ball : problems::balls_on(node.state, node.balls)) {
          const size_t index = layout.index_of(ball);
          if (index == layout.balls.size()) continue;
          const physics::ObjectBall* ob = &node.balls[index];
          for (int k = 0; k < static_cast<int>(scene.pockets.size()); ++k) {
            double p = 0.0;
            Vec2 from = node.places.front();
            for (const Vec2& place : node.places) {
              const double q = layout.chance(index, k, place);
              if (q > p) {
                p = q;
                from = place;
              }
            }
            if (p < 0.01) continue;
            Node child;
            child.value = node.value * p;
            child.balls = node.balls;
            child.state = problems::after_pot(node.state, scene, ball, &child.balls);
            if (child.state.cleared || child.balls.empty()) {
              best = std::max(best, child.value);
              continue;
            }
            child.places = places_after(scene, from, ob->position, scene.pockets[static_cast<size_t>(k)].centre);
            next.push_back(std::move(child));
          }
        }
      }
      std::stable_sort(next.begin(), next.end(),
                       [](const Node& a, const Node& b) { return a.value > b.value; });
      if (next.size() > static_cast<size_t>(beam)) next.resize(static_cast<size_t>(beam));
      frontier = std::move(next);
    }
    for (const Node& node : frontier) best = std::max(best, node.value);
    return best;
  };
}

}  // namespace

PositionValue position_estimate(const physics::Scene& scene, const NoiseModel& noise, int lookahead,
                                int beam) {
  // P(each pot) from the position field (PositionField::next_shot), the fields kept per
  // layout for as long as the returned function lives.
  return position_value(std::make_shared<PotFields>(scene, noise), scene, lookahead, beam);
}

namespace {

const char* count_words(int n) {
  switch (n) {
    case 1: return "one";
    case 2: return "two";
    case 3: return "three";
  }
  return "many";
}

// The route a stroke took, from its result: "direct", "one-cushion bank", "two-cushion
// kick", "one-cushion kick and one-cushion bank", "combination off the 1".
std::string route_of(const problems::Problem& problem, const physics::ShotResult& result) {
  if (result.first_contact <= 0 || result.first_contact >= static_cast<int>(result.balls.size()))
    return "direct";
  const std::string& first = result.balls[static_cast<size_t>(result.first_contact)].name;
  const int kick = problems::cushions_before_contact(result);
  int bank = 0;
  for (const physics::BallOutcome& b : result.balls)
    if (problem.pot && b.name == problem.pot->ball)
      for (const physics::ShotEvent& e : b.events)
        if (e.type == physics::EventType::cushion) ++bank;
  std::string s;
  if (kick > 0) s = fmt::format("{}-cushion kick", count_words(kick));
  if (bank > 0) s += fmt::format("{}{}-cushion bank", s.empty() ? "" : " and ", count_words(bank));
  if (problem.pot && first != problem.pot->ball)
    s += (s.empty() ? "" : ", ") + std::string("combination off the ") + first;
  return s.empty() ? "direct" : s;
}

}  // namespace

std::optional<RunShot> choose_stroke(const problems::Problem& layout, const problems::GameState& state,
                                     const std::vector<physics::ObjectBall>& balls, Vec2 cue,
                                     const RunoutOptions& options, uint64_t seed, int threads) {
  problems::Problem base = layout;
  base.scene.balls = balls;
  base.cue_ball = cue;
  base.has_target = false;
  base.first_contact.reset();
  base.pot.reset();
  const physics::Scene& scene = base.scene;
  const auto fields = std::make_shared<PotFields>(scene, options.noise);
  const PositionValue value =
      options.position ? options.position : position_value(fields, scene, options.lookahead, 4);
  const std::vector<std::string> on = problems::balls_on(state, balls);

  // Legal pots, the likeliest first, at most eight of them.
  struct Cand {
    problems::Candidate pot;
    double quick = 0.0;
  };
  std::vector<Cand> cands;
  for (const std::string& ball : on)
    for (int k = 0; k < static_cast<int>(scene.pockets.size()); ++k) {
      const double q = fields->chance(cue, ball, k, balls);
      if (q > 0.02) cands.push_back({{ball, k}, q});
    }
  std::stable_sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.quick > b.quick; });
  if (cands.size() > 8) cands.resize(8);

  // Stroke families: speeds by the distance to travel, and draw, stun or follow.
  constexpr double kSpeeds[] = {1.0, 1.7, 2.6, 3.6};
  constexpr double kSpins[] = {-0.9, 0.0, 0.7};
  struct Trial {
    size_t problem = 0;  // index into problems_of
    physics::Shot shot;
    bool ok = false;
    double p_pot = 0.0;
    double score = -1.0;
  };
  // One problem per pot tried: its pot, and the ball the cue ball must strike first.
  std::vector<problems::Problem> problems_of(cands.size(), base);
  std::vector<Trial> trials;
  for (size_t c = 0; c < cands.size(); ++c) {
    problems_of[c].pot = problems::Pot{cands[c].pot.ball, cands[c].pot.pocket};
    problems_of[c].first_contact = cands[c].pot.ball;
    for (double speed : kSpeeds)
      for (double spin : kSpins) {
        Trial t;
        t.problem = c;
        t.shot.speed = speed;
        t.shot.topspin_k = spin;
        trials.push_back(t);
      }
  }
  const std::vector<detail::NoiseDraw> draws = detail::noise_draws(options.pot_samples, seed);
  physics::SimulationOptions quiet = options.simulation;
  quiet.record_path = false;
  const auto candidate_of = [&](const problems::Problem& p) -> problems::Candidate {
    return {p.pot->ball, p.pot->pocket};
  };

  // Scores a stroke that pots without noise: P(pot) and the mean value of where the cue
  // ball stops over the noisy strokes.
  const auto score = [&](Trial& t, const detail::Task& task) {
    const problems::Problem& problem = problems_of[t.problem];
    const problems::Candidate pot = candidate_of(problem);
    const double miscue = detail::miscue_limit(problem);
    const double squirt = detail::intended_squirt_deg(problem, t.shot);
    int pots = 0;
    double total = 0.0;
    for (const detail::NoiseDraw& draw : draws) {
      physics::Shot noisy;
      if (!detail::noisy_stroke(t.shot, draw, options.noise, scene.radius(), miscue, squirt, &noisy))
        continue;
      const physics::ShotResult r = task.simulate(noisy, quiet);
      const problems::ShotJudgement j = problems::judge_stroke(state, scene, pot, r);
      if (!j.continues) continue;
      ++pots;
      if (options.policy == RunPolicy::planner)
        total += j.next.cleared ? 1.0 : value(r.final_position, j.next, j.balls);
    }
    const double n = static_cast<double>(std::max<size_t>(draws.size(), 1));
    t.p_pot = pots / n;
    t.score = options.policy == RunPolicy::planner ? total / n : t.p_pot;
  };
  // Whether the stroke, played without noise, drops the pot's ball in its pocket and the
  // run goes on.
  const auto pots_legally = [&](const problems::Problem& problem, const physics::ShotResult& r) {
    const problems::Candidate pot = candidate_of(problem);
    if (!problems::judge_stroke(state, scene, pot, r).continues) return false;
    for (const physics::BallOutcome& b : r.balls)
      if (b.name == pot.ball) return b.pocketed && b.pocket == pot.pocket;
    return false;
  };

  physics::parallel_for(trials.size(), physics::thread_count(threads, trials.size()),
                        [&](size_t i, unsigned) {
    Trial& t = trials[i];
    const detail::Task task(problems_of[t.problem]);
    const detail::PotAim::Aimed aimed = task.pot_aim->aim(task, t.shot, quiet);
    if (!aimed.found || !pots_legally(task.problem, aimed.result)) return;
    t.shot = aimed.shot;
    t.ok = true;
    score(t, task);
  });
  const auto best_of = [&]() {
    const Trial* best = nullptr;
    for (const Trial& t : trials)
      if (t.ok && (best == nullptr || t.score > best->score)) best = &t;
    return best;
  };

  // No direct pot on, or none that pots under the noise: banks, kicks and combinations
  // as well.
  double direct_p = 0.0;
  for (const Trial& t : trials)
    if (t.ok) direct_p = std::max(direct_p, t.p_pot);
  if (direct_p < kFallbackBelow) {
    // Routes (kick.hpp) of every legal (ball, pocket), off one or two cushions in all.
    struct Route {
      size_t problem = 0;
      detail::KickRoute route;  // empty cue_cushions and object_cushions: a combination
      int cushions = 0;
      double length = 0.0;
      std::string first;        // a combination: the ball struck first
    };
    std::vector<Route> routes;
    for (const std::string& ball : on)
      for (int k = 0; k < static_cast<int>(scene.pockets.size()); ++k) {
        problems::Problem p = base;
        p.pot = problems::Pot{ball, k};
        p.first_contact = ball;
        p.limits.cushions_before_contact_min = 0;
        p.limits.cushions_before_contact_max = 2;
        p.limits.object_cushions_min = 0;
        p.limits.object_cushions_max = 2;
        const detail::KickFamilies families = detail::kick_families(p, false);
        bool any = false;
        for (const detail::KickRoute& r : families.routes) {
          const int c = static_cast<int>(r.cue_cushions.size() + r.object_cushions.size());
          if (c < 1 || c > 2) continue;
          routes.push_back({problems_of.size(), r, c, r.cue_length + r.object_length, {}});
          any = true;
        }
        if (any) problems_of.push_back(std::move(p));
      }
    if (state.game == problems::Game::nine_ball && !on.empty()) {
      // Combinations: the lowest ball onto another that drops.
      const std::string& low = on.front();
      const physics::ObjectBall* lb = find_ball(balls, low);
      for (const physics::ObjectBall& b : balls) {
        if (b.name == low || lb == nullptr) continue;
        for (int k = 0; k < static_cast<int>(scene.pockets.size()); ++k) {
          problems::Problem p = base;
          p.pot = problems::Pot{b.name, k};
          p.first_contact = low;
          const std::optional<double> length = detail::combination_length(p);
          if (!length) continue;
          Route r;
          r.problem = problems_of.size();
          r.cushions = 2;  // ranked with the two-cushion routes
          r.length = *length;
          r.first = low;
          routes.push_back(std::move(r));
          problems_of.push_back(std::move(p));
        }
      }
    }
    std::stable_sort(routes.begin(), routes.end(), [](const Route& a, const Route& b) {
      if (a.cushions != b.cushions) return a.cushions < b.cushions;
      return a.length < b.length;
    });
    if (routes.size() > static_cast<size_t>(kMostRoutes)) routes.resize(static_cast<size_t>(kMostRoutes));
    // Each route's strokes, the aim solved on the simulator (no deadline: the answer
    // must not depend on the clock).
    constexpr int kStrokesPerRoute = 2;
    std::vector<std::vector<physics::Shot>> solved(routes.size());
    physics::parallel_for(routes.size(), physics::thread_count(threads, routes.size()),
                          [&](size_t i, unsigned) {
      const detail::Task task(problems_of[routes[i].problem], false);
      int simulations = 0;
      solved[i] = routes[i].first.empty()
                      ? detail::solve_kick(task, routes[i].route, options.simulation,
                                           std::chrono::steady_clock::time_point::max(), kStrokesPerRoute,
                                           &simulations)
                      : detail::solve_combination(task, options.simulation, kStrokesPerRoute, &simulations);
    });
    const size_t first_trial = trials.size();
    for (size_t i = 0; i < routes.size(); ++i)
      for (const physics::Shot& shot : solved[i]) {
        Trial t;
        t.problem = routes[i].problem;
        t.shot = shot;
        trials.push_back(t);
      }
    physics::parallel_for(trials.size() - first_trial, physics::thread_count(threads, trials.size() - first_trial),
                          [&](size_t i, unsigned) {
      Trial& t = trials[first_trial + i];
      const detail::Task task(problems_of[t.problem], false);
      physics::SimulationOptions sim = options.simulation;
      sim.record_path = false;
      if (!pots_legally(task.problem, task.simulate(t.shot, sim))) return;
      t.ok = true;
      score(t, task);
    });
  }

  const Trial* best = best_of();
  if (best == nullptr) return std::nullopt;

  RunShot out;
  const problems::Problem& chosen = problems_of[best->problem];
  const problems::Candidate pot = candidate_of(chosen);
  out.ball = pot.ball;
  out.pocket = pot.pocket;
  out.pocket_name = problems::pocket_name(scene, pot.pocket);
  out.shot = best->shot;
  out.cue_from = cue;
  out.p_pot = best->p_pot;
  out.p_samples = static_cast<int>(draws.size());
  out.score = best->score;
  const physics::ShotResult r = physics::simulate(scene, cue, best->shot, options.simulation);
  out.cue_to = r.final_position;
  out.path = r.path;
  out.route = route_of(chosen, r);
  out.route_words = detail::route_words(chosen, best->shot, r);
  const problems::ShotJudgement j = problems::judge_stroke(state, scene, pot, r);
  out.verdict = j.continues ? "potted" : j.reason;
  out.points = j.points;
  if (j.continues && !j.next.cleared) {
    // The ball the position aims at: the likeliest next pot from where it stops.
    double p = 0.0;
    for (const std::string& ball : problems::balls_on(j.next, j.balls))
      for (int k = 0; k < static_cast<int>(scene.pockets.size()); ++k) {
        const double q = fields->chance(r.final_position, ball, k, j.balls);
        if (q > p) {
          p = q;
          out.next_ball = ball + " into " + problems::pocket_name(scene, k);
        }
      }
  }
  return out;
}

namespace {

struct Rollout {
  bool cleared = false;
  int potted = 0;
  int score = 0;
  int died_at = 0;
  std::string reason;
};

constexpr uint64_t kDecisionStream = 0x646563ULL;   // "dec"
constexpr uint64_t kExecutionStream = 0x657865ULL;  // "exe"

Rollout play(const problems::Problem& layout, const problems::GameState& start,
             const RunoutOptions& options, uint64_t rollout) {
  Rollout out;
  problems::GameState state = start;
  std::vector<physics::ObjectBall> balls = layout.scene.balls;
  Vec2 cue = layout.cue_ball;
  physics::SimulationOptions quiet = options.simulation;
  quiet.record_path = false;
  for (int shot = 1; shot <= options.max_shots; ++shot) {
    const uint64_t key = rollout * 1000003ULL + static_cast<uint64_t>(shot);
    const std::optional<RunShot> chosen =
        choose_stroke(layout, state, balls, cue, options,
                      detail::stream_seed(detail::stream_seed(options.seed, kDecisionStream), key), 1);
    if (!chosen) {
      out.died_at = shot;
      out.reason = "no pot on";
      return out;
    }
    problems::Problem p = layout;
    p.scene.balls = balls;
    p.cue_ball = cue;
    p.pot = problems::Pot{chosen->ball, chosen->pocket};
    const detail::NoiseDraw draw = detail::noise_draws(
        1, detail::stream_seed(detail::stream_seed(options.seed, kExecutionStream), key))[0];
    physics::Shot noisy;
    if (!detail::noisy_stroke(chosen->shot, draw, options.noise, p.scene.radius(),
                              detail::miscue_limit(p), detail::intended_squirt_deg(p, chosen->shot),
                              &noisy)) {
      out.died_at = shot;
      out.reason = "miscue";
      return out;
    }
    const physics::ShotResult r = physics::simulate(p.scene, cue, noisy, quiet);
    const problems::ShotJudgement j =
        problems::judge_stroke(state, p.scene, {chosen->ball, chosen->pocket}, r);
    if (!j.continues) {
      out.died_at = shot;
      out.reason = j.reason;
      return out;
    }
    state = j.next;
    balls = j.balls;
    cue = r.final_position;
    out.potted = state.potted;
    out.score = state.score;
    if (state.cleared || balls.empty()) {
      out.cleared = true;
      return out;
    }
  }
  out.died_at = options.max_shots;
  out.reason = "shot limit";
  return out;
}

// P(the stroke pots legally and the run goes on) from report_samples noisy strokes.
Estimate pot_estimate(const problems::Problem& p, const problems::GameState& state,
                      const problems::Candidate& pot, const physics::Shot& shot,
                      const RunoutOptions& options, uint64_t seed) {
  const std::vector<detail::NoiseDraw> draws = detail::noise_draws(options.report_samples, seed);
  std::vector<char> ok(draws.size(), 0);
  physics::SimulationOptions quiet = options.simulation;
  quiet.record_path = false;
  const physics::CompiledScene scene(p.scene);
  const double miscue = detail::miscue_limit(p);
  const double squirt = detail::intended_squirt_deg(p, shot);
  physics::parallel_for(draws.size(), physics::thread_count(options.threads, draws.size()),
                        [&](size_t i, unsigned) {
    physics::Shot noisy;
    if (!detail::noisy_stroke(shot, draws[i], options.noise, p.scene.radius(), miscue, squirt, &noisy))
      return;
    const physics::ShotResult r = physics::simulate(scene, p.cue_ball, noisy, quiet);
    ok[i] = problems::judge_stroke(state, p.scene, pot, r).continues ? 1 : 0;
  });
  return wilson_estimate(static_cast<int>(std::count(ok.begin(), ok.end(), 1)),
                         static_cast<int>(draws.size()));
}

}  // namespace

RunoutResult plan_runout(const problems::Problem& layout, const problems::GameState& start,
                         const RunoutOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  RunoutResult result;
  // The plan: the policy played without noise.
  {
    problems::GameState state = start;
    std::vector<physics::ObjectBall> balls = layout.scene.balls;
    Vec2 cue = layout.cue_ball;
    for (int shot = 1; shot <= options.max_shots; ++shot) {
      const auto d0 = Clock::now();
      const std::optional<RunShot> chosen = choose_stroke(
          layout, state, balls, cue, options,
          detail::stream_seed(detail::stream_seed(options.seed, kDecisionStream), static_cast<uint64_t>(shot)),
          options.threads);
      if (shot == 1) result.decision_time_s = std::chrono::duration<double>(Clock::now() - d0).count();
      if (!chosen) {
        result.plan.ended = "no pot on";
        break;
      }
      result.plan.shots.push_back(*chosen);
      problems::Problem p = layout;
      p.scene.balls = balls;
      p.cue_ball = cue;
      result.plan.shots.back().pot = pot_estimate(
          p, state, {chosen->ball, chosen->pocket}, chosen->shot, options,
          detail::stream_seed(options.seed, 0x706f74ULL + static_cast<uint64_t>(shot)));
      const physics::ShotResult r = physics::simulate(p.scene, cue, chosen->shot, options.simulation);
      const problems::ShotJudgement j = problems::judge_stroke(state, p.scene, {chosen->ball, chosen->pocket}, r);
      if (!j.continues) {
        result.plan.ended = j.reason;
        break;
      }
      state = j.next;
      balls = j.balls;
      cue = r.final_position;
      result.plan.potted = state.potted;
      result.plan.score = state.score;
      if (state.cleared || balls.empty()) {
        result.plan.cleared = true;
        break;
      }
      if (shot == options.max_shots) result.plan.ended = "shot limit";
    }
  }
  // The rollouts.
  if (options.samples > 0) {
    std::vector<Rollout> rollouts(static_cast<size_t>(options.samples));
    const auto work = [&](size_t i, unsigned) { rollouts[i] = play(layout, start, options, i); };
    const unsigned threads = physics::thread_count(options.threads, rollouts.size());
    if (options.progress)
      physics::parallel_for(rollouts.size(), threads, work, [&](size_t done) {
        options.progress(static_cast<int>(done), options.samples);
      });
    else
      physics::parallel_for(rollouts.size(), threads, work);
    int clears = 0;
    double potted = 0.0, score = 0.0;
    std::map<std::pair<int, std::string>, int> deaths;
    for (const Rollout& r : rollouts) {
      clears += r.cleared ? 1 : 0;
      potted += r.potted;
      score += r.score;
      if (!r.cleared) ++deaths[{r.died_at, r.reason}];
    }
    result.runout = wilson_estimate(clears, options.samples);
    result.mean_potted = potted / options.samples;
    result.mean_score = score / options.samples;
    for (const auto& [key, count] : deaths) result.deaths.push_back({key.first, key.second, count});
    std::stable_sort(result.deaths.begin(), result.deaths.end(),
                     [](const RunDeath& a, const RunDeath& b) { return a.count > b.count; });
  }
  result.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace cueplan::planner
