#include "collide_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <memory>
#include <optional>
#include <ostream>
#include <string_view>
#include <vector>

#include "batch_csv.hpp"
#include "collide_batch.hpp"
#include "csv.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // batch streaming (batch/)
namespace {

namespace phys = cueplan::physics;

constexpr const char* kCommandName = "cueplan collide";
constexpr CutNames kFlagNames = {"--speed", "--cut"};

// The shot as resolved from the flags.
struct CutShotInput {
  double speed = 0.0;    // m/s
  double cut_deg = 0.0;  // deg
  phys::Vec3 spin;       // rad/s, table frame
};

// The event in the command's words: ball i is the cue ball, ball j the object ball.
const char* event_key(phys::CollisionEvent event) {
  switch (event) {
    case phys::CollisionEvent::balls_geared: return "balls_geared";
    case phys::CollisionEvent::cloth_i_through_zero: return "cue_ball_cloth_through_zero";
    case phys::CollisionEvent::cloth_j_through_zero: return "object_ball_cloth_through_zero";
  }
  return "unknown";
}

const char* event_words(phys::CollisionEvent event) {
  switch (event) {
    case phys::CollisionEvent::balls_geared:
      return "the balls gear (no slip between them from here)";
    case phys::CollisionEvent::cloth_i_through_zero: return "the cue ball's cloth slip passes zero";
    case phys::CollisionEvent::cloth_j_through_zero:
      return "the object ball's cloth slip passes zero";
  }
  return "?";
}

std::string method_text(const phys::BallBallParams& params, const phys::CollisionResult& r) {
  if (params.model == phys::BallModel::frictional_inelastic)
    return params.friction == phys::BallFriction::speed_dependent
               ? "frictional_inelastic (closed form, Alciatore's speed-dependent ball friction)"
               : fmt::format("frictional_inelastic (closed form, ball friction {})",
                             number(params.mu_ball));
  return fmt::format("mathavan_2014, {} ({} right-hand-side evaluations)",
                     phys::to_string(r.method_used), r.rhs_evaluations);
}

void write_text(std::ostream& out, const phys::BallBallParams& params, const CutShotInput& in,
                const CutOutcome& o) {
  const auto line = [&](std::string_view label, const std::string& text) {
    out << fmt::format("{:<16}{}\n", label, text);
  };
  const phys::CollisionResult& r = o.result;
  const double spin_unit = in.speed / params.radius;  // rad/s per unit of k
  line("incoming", fmt::format("V = {} along +x, cut {} ({}), spin wx = {}, wy = {}, wz = {} "
                               "(k_T = {}, k_S = {})",
                               number(in.speed, "m/s"), number(in.cut_deg, "deg"),
                               in.cut_deg > 0.0   ? "to the right"
                               : in.cut_deg < 0.0 ? "to the left"
                                                  : "full ball",
                               number(in.spin.x), number(in.spin.y), number(in.spin.z, "rad/s"),
                               number(in.spin.y / spin_unit), number(in.spin.z / spin_unit)));
  const auto ball = [&](std::string_view name, const BallReport& b) {
    line(name, fmt::format("velocity vx = {}, vy = {}; spin wx = {}, wy = {}, wz = {}",
                           number(b.velocity.x, "m/s"), number(b.velocity.y, "m/s"),
                           number(b.spin.x), number(b.spin.y), number(b.spin.z, "rad/s")));
    line("  rolls at",
         fmt::format("{} at {} from +x (vx = {}, vy = {})", number(b.rolling_speed, "m/s"),
                     number(b.rolling_angle_deg, "deg"), number(b.rolling.x, "m/s"),
                     number(b.rolling.y, "m/s")));
  };
  ball("cue ball", o.cue);
  ball("object ball", o.object);
  line("throw", fmt::format("{} (the object ball's direction against the line of centres, "
                            "counter-clockwise)",
                            number(o.throw_deg, "deg")));
  line("status", phys::to_string(r.status));
  line("model", method_text(params, r));
  line("impulse", fmt::format("compression {}, total {}", number(r.impulse_compression, "N s"),
                              number(r.impulse_total, "N s")));
  line("work", fmt::format("compression {}, total {}", number(r.work_compression, "J"),
                           number(r.work_total, "J")));
  line("at start", fmt::format("balls {}; on the cloth the cue ball {}, the object ball {}",
                               r.balls_slipping_at_start ? "slipping" : "geared",
                               r.cloth_i_slipping_at_start ? "slides" : "rolls or rests",
                               r.cloth_j_slipping_at_start ? "slides" : "rolls or rests"));
  if (params.model == phys::BallModel::frictional_inelastic)
    line("transitions", "none in the closed form");
  else if (r.transition_count == 0)
    line("transitions", "none");
  for (int k = 0; k < r.transition_count; ++k)
    line(k == 0 ? "transitions" : "",
         fmt::format("{} at P = {}", event_words(r.transitions[k].event),
                     number(r.transitions[k].impulse, "N s")));
  line("frame", "table: x along the cue ball's line, y to its left, z up");
  if (!phys::usable(r.status)) line("message", r.message);
}

void write_json(std::ostream& out, const phys::BallBallParams& params,
                const phys::CollisionOptions& options, const CutShotInput& in,
                const CutOutcome& o) {
  using nlohmann::ordered_json;
  const phys::CollisionResult& r = o.result;
  const double spin_unit = in.speed / params.radius;
  const auto ball = [](const BallReport& b) {
    return ordered_json{{"velocity", {b.velocity.x, b.velocity.y}},
                        {"spin", {b.spin.x, b.spin.y, b.spin.z}},
                        {"rolling_velocity", {b.rolling.x, b.rolling.y}},
                        {"rolling_speed", b.rolling_speed},
                        {"rolling_angle_deg", b.rolling_angle_deg}};
  };
  ordered_json transitions = ordered_json::array();
  for (int k = 0; k < r.transition_count; ++k)
    transitions.push_back(
        {{"event", event_key(r.transitions[k].event)}, {"impulse", r.transitions[k].impulse}});

  ordered_json j;
  j["status"] = phys::to_string(r.status);
  j["message"] = r.message;
  j["model"] = phys::to_string(params.model);
  j["cue_ball"] = ball(o.cue);
  j["object_ball"] = ball(o.object);
  j["throw_deg"] = o.throw_deg;
  j["impulse_compression"] = r.impulse_compression;
  j["impulse_total"] = r.impulse_total;
  j["work_compression"] = r.work_compression;
  j["work_total"] = r.work_total;
  j["slipping_at_start"] = {{"balls", r.balls_slipping_at_start},
                            {"cue_ball_cloth", r.cloth_i_slipping_at_start},
                            {"object_ball_cloth", r.cloth_j_slipping_at_start}};
  j["transitions"] = transitions;
  j["rhs_evaluations"] = r.rhs_evaluations;
  j["input"] = {{"speed", in.speed},
                {"cut_deg", in.cut_deg},
                {"spin", {in.spin.x, in.spin.y, in.spin.z}},
                {"topspin_k", in.spin.y / spin_unit},
                {"sidespin_k", in.spin.z / spin_unit},
                {"model", phys::to_string(params.model)},
                {"ball_friction", phys::to_string(params.friction)},
                {"method", phys::to_string(options.method)},
                {"steps", options.paper_steps},
                {"tolerance", options.tolerance},
                {"mass", params.mass},
                {"radius", params.radius},
                {"mu_ball", params.mu_ball},
                {"ball_restitution", params.restitution},
                {"mu_table", params.mu_table}};
  j["units"] = {{"frame", "table: x along the cue ball's line, y to its left, z up"},
                {"velocity", "m/s"},
                {"spin", "rad/s"},
                {"rolling_velocity", "m/s, once the ball rolls again on the cloth"},
                {"rolling_speed", "m/s"},
                {"rolling_angle_deg", "deg from +x"},
                {"throw_deg",
                 "deg, the object ball's direction against the line of centres, "
                 "counter-clockwise"},
                {"impulse", "N s"},
                {"work", "J"},
                {"speed", "m/s"},
                {"cut_deg", "deg; the object ball's centre at 2R (cos c, -sin c)"},
                {"mass", "kg"},
                {"radius", "m"}};
  out << j.dump(2) << '\n';
}

// "WX,WY,WZ" as three finite numbers.
std::optional<phys::Vec3> parse_spin(const std::string& text) {
  const std::vector<std::string> parts = split_csv_line(text);
  if (parts.size() != 3) return std::nullopt;
  double w[3];
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> x = parse_number(parts[k]);
    if (!x || !std::isfinite(*x)) return std::nullopt;
    w[k] = *x;
  }
  return phys::Vec3{w[0], w[1], w[2]};
}

}  // namespace

CollideCommand::CollideCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "collide",
      "Resolve a cue ball striking an object ball at rest (ball-ball collision of Mathavan, "
      "Jackson & Parkin 2014, or its closed form) and print both balls' velocity and spin.");
  CLI::App& c = *command_;

  const char* ball = "Cue ball";
  c.add_option("--speed", args_.speed,
               "Cue ball speed V (m/s) along +x, > 0. Required unless --batch is given.")
      ->type_name("m/s")
      ->group(ball);
  c.add_option("--cut", args_.cut_deg,
               "Cut angle c (deg), in (-90, 90): the object ball's centre lies at 2R (cos c, "
               "-sin c); 0 is a full-ball hit, c > 0 cuts it to the right. Required unless "
               "--batch is given.")
      ->type_name("deg")
      ->group(ball);
  const SpinFlags spin_flags =
      add_spin_flags(c, &args_.spins, ball, "V", " about the horizontal axis across the motion");
  c.add_option("--spin", args_.spin,
               "Any spin vector (rad/s, table frame: x along the motion, y to its left, z up) "
               "instead of the topspin and sidespin flags, as a ball has after a cushion")
      ->type_name("WX,WY,WZ")
      ->excludes(spin_flags.topspin_k)
      ->excludes(spin_flags.sidespin_k)
      ->excludes(spin_flags.topspin)
      ->excludes(spin_flags.sidespin)
      ->group(ball);

  const char* model = "Model";
  c.add_option("--model", args_.model,
               "mathavan_2014 (friction between the balls and at the cloth over the normal "
               "impulse) or frictional_inelastic (one impulse, Alciatore's closed form)")
      ->type_name("mathavan_2014|frictional_inelastic")
      ->capture_default_str()
      ->group(model);
  c.add_option("--ball-friction", args_.ball_friction,
               "frictional_inelastic: constant (--mu-ball) or speed_dependent (Alciatore's fit "
               "0.00995 + 0.108 exp(-1.088 |slip|))")
      ->type_name("constant|speed_dependent")
      ->capture_default_str()
      ->group(model);
  c.add_option("--method", args_.method,
               "mathavan_2014: exact (Taylor series landing on its events), extrapolation (a "
               "second exact method: adaptive extrapolation) or paper (N fixed impulse steps)")
      ->type_name("exact|extrapolation|paper")
      ->capture_default_str()
      ->group(model);
  c.add_option("--steps", args_.steps, "paper: number of impulse steps N, >= 1")
      ->type_name("N")
      ->capture_default_str()
      ->group(model);
  c.add_option("--tolerance", args_.tolerance,
               "exact: local error per step relative to V, in [1e-15, 1e-2]")
      ->type_name("TOL")
      ->capture_default_str()
      ->group(model);

  // Physical parameters bind straight into BallBallParams: its defaults are the help's.
  const char* physical = "Physical parameters (snooker defaults, the paper's)";
  c.add_option("--mu-ball", args_.params.mu_ball, "Ball-ball sliding friction mu_b, >= 0")
      ->type_name("mu_b")
      ->capture_default_str()
      ->group(physical);
  c.add_option("--ball-restitution", args_.params.restitution,
               "Energetic coefficient of restitution between the balls e_b, in (0, 1]")
      ->type_name("e_b")
      ->capture_default_str()
      ->group(physical);
  c.add_option("--mu-table", args_.params.mu_table, "Ball-cloth sliding friction mu_s, >= 0")
      ->type_name("mu_s")
      ->capture_default_str()
      ->group(physical);
  c.add_option("--mass", args_.params.mass, "Ball mass M (kg), > 0")
      ->type_name("kg")
      ->capture_default_str()
      ->group(physical);
  c.add_option("--radius", args_.params.radius, "Ball radius R (m), > 0")
      ->type_name("m")
      ->capture_default_str()
      ->group(physical);

  const char* output = "Output";
  auto* json = c.add_flag("--json", args_.json,
                          "Print one JSON object (table frame, SI units) instead of text")
                   ->group(output);
  auto* batch = c.add_option("--batch", args_.batch_file,
                             fmt::format("Resolve every row of a CSV file with header '{}' (m/s, "
                                         "deg, k_T, k_S) and write CSV to stdout: the input "
                                         "columns, then {}, each block of rows as it is done; '-' reads "
                                         "standard input. A bad row gets its own error status "
                                         "and the rest go on; a summary (rows, rows of each "
                                         "status) goes to stderr.",
                                         kCollideBatchHeader, kCollideBatchResultHeader))
                    ->type_name("FILE.csv")
                    ->group(output);
  c.add_option("--threads", args_.threads,
               "Batch: threads to spread the rows over (0: one per core); the output is the "
               "same for any count")
      ->type_name("N")
      ->capture_default_str()
      ->needs(batch)
      ->group(output);
  batch->excludes(json);
  for (const char* flag : {"--speed", "--cut", "--topspin", "--sidespin", "--spin"})
    batch->excludes(c.get_option(flag));

  c.footer(
      "Frame: the table's, x along the cue ball's line, y to its left, z up; directions are "
      "in degrees from +x. The rolling velocity is where each ball's sliding on the cloth "
      "ends, v - 2/7 u for the contact-point velocity u, nothing else intervening.\n"
      "Exit codes: 0 done, 1 no usable result (--batch: some row without one, or a bad "
      "row), 2 bad input (--batch: the command line, or a file that cannot be opened or has "
      "the wrong header).\n"
      "Example: cueplan collide --speed 1 --cut 30 --topspin-k 1");
}

bool CollideCommand::selected() const { return command_->parsed(); }

bool CollideCommand::given(const char* flag) const { return command_->count(flag) > 0; }

struct CollideCommand::Inputs {
  phys::CollisionOptions options;
  phys::BallBallParams params;
  bool batch = false;
  bool check_only = false;             // validate(): standard input is not read
  std::unique_ptr<BatchReader> reader;  // with --batch, past its header
  CutShotInput shot;                    // without
};

std::string CollideCommand::read_options(phys::CollisionOptions* options) const {
  if (!phys::parse_collision_method(args_.method, &options->method))
    return fmt::format("--method must be exact, extrapolation or paper, got '{}'", args_.method);
  options->paper_steps = args_.steps;
  options->tolerance = args_.tolerance;
  // Both the paper's and the exact method's settings are checked whatever the method, so
  // that a bad value is not silently ignored.
  phys::CollisionOptions each = *options;
  for (phys::CollisionMethod method :
       {phys::CollisionMethod::paper, phys::CollisionMethod::exact,
        phys::CollisionMethod::extrapolation}) {
    each.method = method;
    if (phys::Validation why = each.validate()) return flag_message(*why);
  }
  if (args_.threads < 0)
    return fmt::format("--threads must be 0 (one per core) or more, got {}", args_.threads);
  return {};
}

std::string CollideCommand::read_params(phys::BallBallParams* params) const {
  *params = args_.params;
  if (!phys::parse_ball_model(args_.model, &params->model))
    return fmt::format("--model must be mathavan_2014 or frictional_inelastic, got '{}'",
                       args_.model);
  if (!phys::parse_ball_friction(args_.ball_friction, &params->friction))
    return fmt::format("--ball-friction must be constant or speed_dependent, got '{}'",
                       args_.ball_friction);
  if (phys::Validation why = params->validate()) return flag_message(*why);
  return {};
}

std::string CollideCommand::read_shot(const phys::BallBallParams& params, Inputs* inputs) const {
  if (!given("--speed")) return "--speed is required (m/s) unless --batch is given";
  if (!given("--cut")) return "--cut is required (deg) unless --batch is given";
  if (std::string why = check_cut(args_.speed, args_.cut_deg, kFlagNames); !why.empty()) return why;
  CutShotInput& in = inputs->shot;
  in.speed = args_.speed;
  in.cut_deg = args_.cut_deg;
  if (given("--spin")) {
    const std::optional<phys::Vec3> spin = parse_spin(args_.spin);
    if (!spin)
      return fmt::format("--spin must be three finite numbers WX,WY,WZ (rad/s), got '{}'",
                         args_.spin);
    in.spin = *spin;
    return {};
  }
  double topspin = 0.0, sidespin = 0.0;
  if (std::string why =
          read_spins(*command_, args_.spins, args_.speed, params.radius, &topspin, &sidespin);
      !why.empty())
    return why;
  in.spin = {0.0, topspin, sidespin};
  return {};
}

std::string CollideCommand::read_inputs(Inputs* inputs) const {
  if (std::string why = read_options(&inputs->options); !why.empty()) return why;
  if (std::string why = read_params(&inputs->params); !why.empty()) return why;
  inputs->batch = given("--batch");
  if (inputs->batch) {
    if (inputs->check_only && args_.batch_file == "-") return {};
    inputs->reader = std::make_unique<BatchReader>(args_.batch_file, kCollideBatchHeader);
    return inputs->reader->error();
  }
  return read_shot(inputs->params, inputs);
}

int CollideCommand::validate(std::ostream& err) const {
  Inputs inputs;
  inputs.check_only = true;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int CollideCommand::run(std::ostream& out, std::ostream& err) const {
  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty())
    return usage_error(err, kCommandName, why);
  if (inputs.batch) {
    return run_batch_command(
        *inputs.reader, collide_batch_job(inputs.params, inputs.options, args_.threads), out, err);
  }
  const CutShotInput& in = inputs.shot;
  const CutOutcome o = collide_cut(inputs.params, inputs.options, in.speed, in.cut_deg, in.spin);
  if (o.result.status == phys::CollisionStatus::invalid_input)
    return usage_error(err, kCommandName,
                       o.result.error ? flag_message(*o.result.error) : o.result.message);
  if (args_.json)
    write_json(out, inputs.params, inputs.options, in, o);
  else
    write_text(out, inputs.params, in, o);
  return phys::usable(o.result.status) ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
