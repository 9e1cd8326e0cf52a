#include "run_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <ostream>
#include <vector>

#include "cueplan/draw/table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/shot_report.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

constexpr const char* kCommandName = "cueplan run";

std::string position_text(phys::Vec2 p) { return fmt::format("({:.3f}, {:.3f}) m", p.x, p.y); }


const char* game_words(prob::Game game) {
  switch (game) {
    case prob::Game::any_order: return "pot every ball, any order";
    case prob::Game::nine_ball: return "the lowest ball first, the 9 last or on a combination";
    case prob::Game::eight_ball: return "the group, then the 8 in the called pocket";
    case prob::Game::snooker: return "a red then a colour, then the colours in order";
  }
  return "";
}

std::string stroke_words(const phys::Scene& scene, const phys::Shot& shot) {
  std::string words = plan::describe_stroke(shot) + fmt::format(", aim {:.2f} deg", shot.aim_deg);
  const std::string squirt = squirt_words(scene, shot);
  if (!squirt.empty()) words += "; " + squirt;
  return words;
}

std::string ended_text(const plan::RunPlan& p) {
  if (p.cleared) return "clears the table in " + std::to_string(p.shots.size()) + " shots";
  return "stops at shot " + std::to_string(p.shots.size() + (p.ended == "no pot on" ? 1 : 0)) + ": " + p.ended;
}

void write_text(std::ostream& out, const prob::Layout& layout, const prob::GameState& start,
                const plan::RunoutOptions& o, const plan::RunoutResult& r) {
  const auto line = [&](std::string_view label, const std::string& text) { report_line(out, label, text); };
  const prob::Problem& problem = layout.problem;
  line("layout", problem.name + "  (" + problem.source + ")");
  std::string game = std::string(prob::to_string(start.game)) + ": " + game_words(start.game);
  if (start.game == prob::Game::eight_ball) game += "; group " + std::string(prob::to_string(start.group));
  line("game", game);
  line("policy", o.policy == plan::RunPolicy::planner
                     ? "planner: the stroke most likely to pot and leave the next " +
                           std::to_string(o.lookahead) + (o.lookahead == 1 ? " pot" : " pots") + " on"
                     : std::string("greedy: the likeliest pot, no position"));
  line("cue ball", position_text(problem.cue_ball));
  for (size_t i = 0; i < r.plan.shots.size(); ++i) {
    const plan::RunShot& s = r.plan.shots[i];
    line("shot " + std::to_string(i + 1), s.ball + " into " + s.pocket_name);
    if (s.route != "direct") line("    route", s.route + ": " + s.route_words);
    line("    stroke", stroke_words(problem.scene, s.shot));
    line("    P(pot)", estimate_text(s.pot) + " of " + std::to_string(s.pot.samples) + " noisy strokes");
    std::string zone = "cue ball to " + position_text(s.cue_to);
    if (!s.next_ball.empty()) zone += " for " + s.next_ball;
    if (s.verdict != "potted") zone += "; " + s.verdict;
    line("    position", zone);
  }
  line("plan", ended_text(r.plan) +
                   (start.game == prob::Game::snooker ? ", break " + std::to_string(r.plan.score) : std::string()));
  if (o.samples > 0) {
    line("P(run-out)", estimate_text(r.runout) + " of " + std::to_string(r.runout.samples) +
                           " runs played under the noise (" + noise_text(o.noise) + ")");
    line("mean potted", fmt::format("{:.2f} balls", r.mean_potted));
    if (start.game == prob::Game::snooker) line("mean break", fmt::format("{:.1f}", r.mean_score));
    for (size_t i = 0; i < r.deaths.size() && i < 6; ++i) {
      const plan::RunDeath& d = r.deaths[i];
      line(i == 0 ? "runs end" : "", fmt::format("shot {}: {} ({} of {})", d.shot, d.reason, d.count,
                                                 r.runout.samples));
    }
  }
  line("time", fmt::format("{:.2f} s (first decision {:.2f} s); seed {}", r.time_s, r.decision_time_s, o.seed));
}

draw::TableScene drawing_of(const prob::Layout& layout, const prob::GameState& start,
                            const plan::RunoutResult& r) {
  const prob::Problem& problem = layout.problem;
  draw::TableScene d = draw::problem_table(problem);
  // Each shot from where the balls stand: the cue ball's path numbered, the potted ball's
  // path in its colour.
  phys::SimulationOptions exact;
  std::vector<phys::ObjectBall> balls = problem.scene.balls;
  prob::GameState state = start;
  phys::Vec2 cue = problem.cue_ball;
  for (size_t i = 0; i < r.plan.shots.size(); ++i) {
    const plan::RunShot& s = r.plan.shots[i];
    phys::Scene scene = problem.scene;
    scene.balls = balls;
    const phys::ShotResult sim = phys::simulate(scene, cue, s.shot, exact);
    d.balls.front().paths.push_back({sim.path, sim.events, false, static_cast<int>(i) + 1});
    for (size_t k = 1; k < sim.balls.size(); ++k) {
      if (!sim.balls[k].pocketed) continue;
      for (draw::DrawnBall& b : d.balls)
        if (b.name == sim.balls[k].name)
          b.paths.push_back({sim.balls[k].path, sim.balls[k].events, false, 0, b.colour});
    }
    const prob::ShotJudgement j = prob::judge_stroke(state, scene, {s.ball, s.pocket}, sim);
    if (!j.continues) break;
    state = j.next;
    balls = j.balls;
    cue = sim.final_position;
  }
  d.title = problem.name + ": " + ended_text(r.plan);
  for (size_t i = 0; i < r.plan.shots.size(); ++i) {
    const plan::RunShot& s = r.plan.shots[i];
    const std::string route = s.route == "direct" ? std::string() : ", " + s.route;
    d.caption.push_back(fmt::format("{}. {} into {}{} ({}); P(pot) {:.0f} %.", i + 1, s.ball, s.pocket_name, route,
                                    plan::describe_stroke(s.shot), 100.0 * s.pot.p));
  }
  if (r.runout.samples > 0)
    d.caption.push_back(fmt::format("P(run-out) {:.0f} % of {} runs under the noise.", 100.0 * r.runout.p,
                                    r.runout.samples));
  return d;
}

}  // namespace

RunCommand::RunCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "run",
      "Plan a run-out from a layout under a game's rules: which ball into which pocket, "
      "shot by shot, each stroke chosen for the chance of finishing the run, and how often "
      "the run clears the table under a player's execution noise.");
  CLI::App& c = *command_;
  c.add_option("LAYOUT", args_.layout_file,
               "Layout file (YAML): a problem file with named balls, the cue ball and no pot; "
               "may give game: and group:")
      ->required()
      ->type_name("FILE.yaml");
  c.add_option("--game", args_.game, "any_order, nine_ball, eight_ball or snooker (default: the file's game, else any_order)")
      ->type_name("NAME");
  c.add_option("--lookahead", args_.lookahead, "Pots scored beyond the one played, 1-5")->capture_default_str();
  c.add_option("--policy", args_.policy, "planner (pot and position) or greedy (the likeliest pot)")
      ->capture_default_str();
  c.add_option("--samples", args_.samples, "Runs played under the noise for P(run-out), 0-100000 (0: the plan only)")
      ->capture_default_str();
  c.add_option("--seed", args_.seed, "Seed of every random choice")->capture_default_str();
  c.add_option("--threads", args_.threads, "Threads (0: one per core); the answer does not depend on it")
      ->capture_default_str();
  c.add_option("--noise", args_.noise, "Scale of the player's execution noise, >= 0")->capture_default_str();
  c.add_flag("--json", args_.json, "Print one JSON object: plan, runout, mean_potted, deaths, policy, ...");
  c.add_option("--svg", args_.svg_file, "Draw the pattern: each shot's cue-ball path numbered (SVG, PNG or PDF by extension)")
      ->type_name("FILE");
  c.add_option("--png", args_.png_file, "The same drawing as a PNG")->type_name("FILE.png");
  c.footer("Exit 0 when the planned run (without noise) clears the table, 1 when it does not, 2 on bad input.\n"
           "Example: cueplan run problems/runs/nine_ball_four.yaml --samples 200 --svg run.svg");
}

bool RunCommand::selected() const { return command_->parsed(); }

int RunCommand::read(std::ostream& err, prob::Layout* layout, prob::GameState* start,
                     plan::RunoutOptions* o) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  std::optional<prob::Game> game;
  if (!args_.game.empty()) {
    prob::Game g;
    if (!prob::parse_game(args_.game, &g))
      return usage("--game must be any_order, nine_ball, eight_ball or snooker, got '" + args_.game + "'");
    game = g;
  }
  if (!plan::parse_run_policy(args_.policy, &o->policy))
    return usage("--policy must be planner or greedy, got '" + args_.policy + "'");
  if (args_.lookahead < 1 || args_.lookahead > 5)
    return usage("--lookahead must be 1 to 5, got " + std::to_string(args_.lookahead));
  if (args_.samples < 0 || args_.samples > 100000)
    return usage("--samples must be 0 to 100000, got " + std::to_string(args_.samples));
  if (args_.threads < 0) return usage("--threads must be >= 0, got " + std::to_string(args_.threads));
  if (!(args_.noise >= 0.0) || !std::isfinite(args_.noise))
    return usage("--noise must be a number >= 0, got " + fmt::format("{}", args_.noise));
  if (!args_.svg_file.empty())
    if (std::string why = check_picture_file("--svg", args_.svg_file); !why.empty()) return usage(why);
  if (!args_.png_file.empty()) {
    if (args_.png_file.size() < 4 || args_.png_file.substr(args_.png_file.size() - 4) != ".png")
      return usage("--png must name a .png file, got '" + args_.png_file + "'");
    if (std::string why = check_output_file(args_.png_file); !why.empty()) return usage("--png: " + why);
  }
  o->lookahead = args_.lookahead;
  o->samples = args_.samples;
  o->seed = args_.seed;
  o->threads = args_.threads;
  o->noise.scale = args_.noise;
  prob::LayoutResult loaded = prob::load_layout(args_.layout_file);
  if (!loaded.ok()) return usage(loaded.error);
  *layout = std::move(*loaded.layout);
  const prob::Game chosen = game ? *game : layout->game.value_or(prob::Game::any_order);
  if (std::string why = prob::check_game_balls(layout->problem.scene.balls, chosen); !why.empty())
    return usage(layout->problem.source + ": " + why);
  if (layout->group && chosen != prob::Game::eight_ball)
    return usage(layout->problem.source + ": group: is for eight_ball only, the game is " + prob::to_string(chosen));
  *start = prob::initial_state(chosen, layout->group);
  return kExitOk;
}

int RunCommand::validate(std::ostream& err) const {
  prob::Layout layout;
  prob::GameState start;
  plan::RunoutOptions o;
  return read(err, &layout, &start, &o);
}

int RunCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  prob::Layout layout;
  prob::GameState start;
  plan::RunoutOptions o;
  if (const int code = read(err, &layout, &start, &o); code != kExitOk) return code;
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  int shown = -1;
  o.progress = [&](int done, int total) {
    const int tenth = total > 0 ? done * 10 / total : 10;
    if (!terminal || tenth == shown) return;
    shown = tenth;
    err << '\r' << kCommandName << ": " << done << " of " << total << " runs played" << std::flush;
  };
  if (terminal) err << kCommandName << ": planning the run" << std::flush;
  const plan::RunoutResult result = plan::plan_runout(layout.problem, start, o);
  if (terminal) err << "\r\033[K" << std::flush;
  for (const std::string* file : {&args_.svg_file, &args_.png_file}) {
    if (file->empty()) continue;
    const draw::Picture picture = draw::table_picture(drawing_of(layout, start, result));
    if (std::string why = write_picture(*file, picture); !why.empty())
      return usage((file == &args_.svg_file ? "--svg: " : "--png: ") + why);
  }
  if (args_.json)
    out << run_json(layout, start, o, result).dump(2) << '\n';
  else
    write_text(out, layout, start, o, result);
  if (!out) return kExitFailed;
  return result.plan.cleared ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
