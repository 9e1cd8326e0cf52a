// Run-outs: the planner policy against the greedy one on generated layouts (issue 29,
// bench/README.md "Run-outs"). For each layout both policies are played `rollouts`
// times under the default noise with the same seed (the same execution draws), and the
// fraction of clears is averaged over the layouts; the first decision's time is timed
// on one thread.
//
//   bench_runout [--kind any5|nine|snooker] [--layouts N] [--rollouts M] [--seed S]
//                [--threads T] [--lookahead K] [--only K] [--show-plan 1]
// --only K plays only layout K of the set; --show-plan 1 prints each layout's plan (the
// policy without noise: ball, pocket, route, P(pot) while choosing, verdict).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "cueplan/planner/runout.hpp"
#include "cueplan/problems/game.hpp"

namespace {

using namespace cueplan;

const char* kPoolTable = R"(table: {length: 2.54, width: 1.27, pockets: pool}
ball: {radius: 0.028575, mass: 0.17}
physics: {mu_slide: 0.2, mu_roll: 0.01, mu_spin: 0.0117, mu_cushion: 0.14, restitution: 0.98, gravity: 9.81}
cue: pool
)";

struct Generated {
  problems::Layout layout;
  problems::Game game;
};

// A place for a ball: on the table, clear of the pockets and of the balls placed.
bool place(std::mt19937_64& rng, double length, double width, double r, double xlo, double xhi,
           std::vector<physics::Vec2>& taken, physics::Vec2* out) {
  std::uniform_real_distribution<double> ux(std::max(xlo, 2 * r), std::min(xhi, length - 2 * r));
  std::uniform_real_distribution<double> uy(2 * r, width - 2 * r);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const physics::Vec2 p{ux(rng), uy(rng)};
    bool ok = true;
    for (double px : {0.0, length / 2, length})
      for (double py : {0.0, width})
        if (std::hypot(p.x - px, p.y - py) < 0.15) ok = false;
    for (const physics::Vec2& q : taken)
      if (std::hypot(p.x - q.x, p.y - q.y) < 2.5 * r) ok = false;
    if (ok) {
      taken.push_back(p);
      *out = p;
      return true;
    }
  }
  return false;
}

std::string ball_line(const std::string& name, physics::Vec2 p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "  \"%s\": [%.4f, %.4f]\n", name.c_str(), p.x, p.y);
  return buf;
}

Generated generate(const std::string& kind, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<physics::Vec2> taken;
  std::string text = "name: generated\n";
  physics::Vec2 cue;
  problems::Game game = problems::Game::any_order;
  if (kind == "snooker") {
    game = problems::Game::snooker;
    const double L = 3.569, W = 1.778, r = 0.02625;
    physics::Scene scene;
    scene.length = L;
    scene.width = W;
    text += "balls:\n";
    const char* colours[] = {"yellow", "green", "brown", "blue", "pink", "black"};
    for (int v = 2; v <= 7; ++v) {
      const physics::Vec2 s = problems::colour_spot(scene, v);
      taken.push_back(s);
      text += ball_line(colours[v - 2], s);
    }
    for (int i = 1; i <= 3; ++i) {
      physics::Vec2 p;
      place(rng, L, W, r, L / 2, L, taken, &p);
      text += ball_line("red" + std::to_string(i), p);
    }
    std::uniform_real_distribution<double> a(0.0, 3.14159), d(0.05, 0.27);
    const double t = a(rng), rr = d(rng);
    cue = {0.737 - rr * std::sin(t), W / 2 + rr * std::cos(t)};
  } else {
    const double L = 2.54, W = 1.27, r = 0.028575;
    text += kPoolTable;
    text += "balls:\n";
    const int n = kind == "nine" ? 9 : 5;
    game = kind == "nine" ? problems::Game::nine_ball : problems::Game::any_order;
    for (int i = 1; i <= n; ++i) {
      physics::Vec2 p;
      place(rng, L, W, r, 0.0, L, taken, &p);
      text += ball_line(std::to_string(i), p);
    }
    place(rng, L, W, r, 0.0, L, taken, &cue);
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "cue_ball: [%.4f, %.4f]\n", cue.x, cue.y);
  text += buf;
  problems::LayoutResult loaded = problems::parse_layout(text, "generated");
  if (!loaded.ok()) {
    std::fprintf(stderr, "bench_runout: %s\n", loaded.error.c_str());
    std::exit(2);
  }
  return {std::move(*loaded.layout), game};
}

}  // namespace

int main(int argc, char** argv) {
  std::string kind = "any5";
  int layouts = 20, rollouts = 40, threads = 0, lookahead = 2, only = -1, show_plan = 0;
  uint64_t seed = 29;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--kind") kind = value;
    else if (flag == "--layouts") layouts = std::stoi(value);
    else if (flag == "--rollouts") rollouts = std::stoi(value);
    else if (flag == "--seed") seed = std::stoull(value);
    else if (flag == "--threads") threads = std::stoi(value);
    else if (flag == "--lookahead") lookahead = std::stoi(value);
    else if (flag == "--only") only = std::stoi(value);
    else if (flag == "--show-plan") show_plan = std::stoi(value);
    else {
      std::fprintf(stderr, "bench_runout: unknown flag %s\n", flag.c_str());
      return 2;
    }
  }
  std::printf("kind %s, %d layouts, %d rollouts each, seed %llu, look-ahead %d\n", kind.c_str(), layouts,
              rollouts, static_cast<unsigned long long>(seed), lookahead);
  std::printf("layout  planner  greedy  potted(p)  potted(g)  decision_s  rollouts_s  rollouts_cpu_s\n");
  double sum_p = 0, sum_g = 0, pot_p = 0, pot_g = 0;
  std::vector<double> decisions;
  double total_rollout_s = 0;
  int played = 0;
  for (int k = 0; k < layouts; ++k) {
    if (only >= 0 && k != only) continue;
    ++played;
    const Generated g = generate(kind, seed * 1000 + static_cast<uint64_t>(k));
    const problems::GameState start = problems::initial_state(g.game, std::nullopt);
    planner::RunoutOptions o;
    o.lookahead = lookahead;
    o.samples = rollouts;
    o.seed = seed + static_cast<uint64_t>(k);
    o.threads = threads;
    o.report_samples = 0;
    // The first decision on one thread.
    const auto d0 = std::chrono::steady_clock::now();
    (void)planner::choose_stroke(g.layout.problem, start, g.layout.problem.scene.balls, g.layout.problem.cue_ball,
                                 o, o.seed, 1);
    decisions.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - d0).count());
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const planner::RunoutResult rp = planner::plan_runout(g.layout.problem, start, o);
    const double cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    total_rollout_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o.policy = planner::RunPolicy::greedy;
    const planner::RunoutResult rg = planner::plan_runout(g.layout.problem, start, o);
    sum_p += rp.runout.p;
    sum_g += rg.runout.p;
    pot_p += rp.mean_potted;
    pot_g += rg.mean_potted;
    std::printf("%6d  %7.3f  %6.3f  %9.2f  %9.2f  %10.3f  %10.1f  %14.1f\n", k, rp.runout.p, rg.runout.p,
                rp.mean_potted, rg.mean_potted, decisions.back(), rp.time_s, cpu_s);
    if (show_plan)
      for (const planner::RunShot& s : rp.plan.shots)
        std::printf("        %s into %s, %s, P(pot) %.3f, score %.3f: %s\n", s.ball.c_str(), s.pocket_name.c_str(),
                    s.route.c_str(), s.p_pot, s.score, s.verdict.c_str());
    if (show_plan > 1)
      for (uint64_t sd = 1; sd <= 12; ++sd) {
        planner::RunoutOptions q = o;
        q.policy = planner::RunPolicy::planner;
        const auto c = planner::choose_stroke(g.layout.problem, start, g.layout.problem.scene.balls,
                                              g.layout.problem.cue_ball, q, sd * 7919, 2);
        if (c) std::printf("        seed %llu: %s into %s, %s, P(pot) %.3f, score %.3f\n", (unsigned long long)sd,
                           c->ball.c_str(), c->pocket_name.c_str(), c->route.c_str(), c->p_pot, c->score);
      }
    if (show_plan)
      for (const planner::RunDeath& d : rp.deaths)
        std::printf("        runs end at shot %d: %s (%d)\n", d.shot, d.reason.c_str(), d.count);
    std::fflush(stdout);
  }
  layouts = played;
  std::sort(decisions.begin(), decisions.end());
  std::printf("mean P(run-out): planner %.3f, greedy %.3f (difference %.3f); mean potted %.2f vs %.2f\n",
              sum_p / layouts, sum_g / layouts, (sum_p - sum_g) / layouts, pot_p / layouts, pot_g / layouts);
  std::printf("first decision (1 thread): median %.3f s, max %.3f s; planner rollouts: %.1f s per %d\n",
              decisions[decisions.size() / 2], decisions.back(), total_rollout_s / layouts, rollouts);
  return 0;
}
