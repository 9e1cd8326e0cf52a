#include "rebound_command.hpp"

#include "flag_table.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/output_file.hpp"
#include "rebound_batch.hpp"
#include "cueplan/api/rebound_inputs.hpp"
#include "cueplan/api/words.hpp"
#include "cueplan/api/table_cache.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // batch streaming (batch/)
namespace {

namespace phys = cueplan::physics;

constexpr const char* kCommandName = "cueplan rebound";

std::string transition_text(const phys::SlipTransition& t) {
  return std::string(phys::to_string(t.contact)) + (t.sticking ? " sticks" : " slips") +
         " at P_I = " + number(t.impulse, "N s");
}

std::string rigid_limit_warning(const phys::CushionParams& params, const Incidence& in) {
  const double normal_speed = phys::incoming_state(in.speed, in.angle_deg, 0.0, 0.0).velocity.y;
  return "warning: normal speed V0 sin(alpha) = " + number(normal_speed, "m/s") +
         " exceeds the rigid-cushion limit of " + number(params.rigid_speed_limit, "m/s") +
         "; the model trusts a rigid cushion only below it";
}

void write_text(std::ostream& out, const phys::CushionParams& params, const Incidence& in,
                const phys::ImpactResult& r) {
  const auto line = [&](std::string_view label, const std::string& text) {
    report_line(out, label, text);
  };
  const double spin_unit = in.speed / params.radius;  // rad/s per unit of k
  line("incoming",
       "V0 = " + number(in.speed, "m/s") + " at alpha = " + number(in.angle_deg, "deg") +
           ", w_T = " + number(in.topspin, "rad/s") + " (k_T = " + number(in.topspin / spin_unit) +
           "), w_S = " + number(in.sidespin, "rad/s") +
           " (k_S = " + number(in.sidespin / spin_unit) + ")");
  const phys::Vec3& v = r.outgoing.velocity;
  const phys::Vec3& w = r.outgoing.spin;
  line("rebound speed", number(r.rebound_speed, "m/s"));
  line("rebound angle", number(r.rebound_angle_deg, "deg"));
  line("velocity", "vx = " + number(v.x, "m/s") + ", vy = " + number(v.y, "m/s") +
                       "  (cushion frame: X along the cushion, Y into it, Z up)");
  line("spin", "wx = " + number(w.x, "rad/s") + ", wy = " + number(w.y, "rad/s") +
                   ", wz = " + number(w.z, "rad/s") + "  (cushion frame)");
  line("status", phys::to_string(r.status));
  line("model", phys::to_string(r.model));
  const bool interpolated = r.method_used == phys::ImpactMethod::table;
  // The work: right-hand-side calls, or for the Taylor method series orders (each
  // about one call's work).
  const char* work = r.method_used == phys::ImpactMethod::exact ? " series orders)"
                                                                : " right-hand-side evaluations)";
  if (r.method_used == phys::ImpactMethod::closed_form)
    line("method", "closed_form (one impulse)");
  else
    line("method", interpolated ? std::string("table (interpolated)")
                                : std::string(phys::to_string(r.method_used)) + " (" +
                                      std::to_string(r.rhs_evaluations) + work);
  line("impulse", "compression " + number(r.impulse_compression, "N s") + ", total " +
                      number(r.impulse_total, "N s"));
  if (r.method_used == phys::ImpactMethod::closed_form)
    line("work", r.model == phys::CushionModel::stronge_compliant
                     ? "none (Newton's restitution and a tangential spring: no work integral)"
                     : "none (Newton's restitution: the model has no work integral)");
  else
    line("work",
         "compression " + number(r.work_compression, "J") + ", total " + number(r.work_total, "J"));
  line("at start", std::string("cushion ") +
                       (r.cushion_slipping_at_start ? "slipping" : "sticking") + ", table " +
                       (r.table_slipping_at_start ? "slipping" : "sticking (rolling)"));
  if (interpolated)
    line("transitions", "not recorded by the table method");
  else if (r.transition_count == 0)
    line("transitions", "none");
  for (int i = 0; i < r.transition_count; ++i)
    line(i == 0 ? "transitions" : "", transition_text(r.transitions[i]));
  if (r.status == phys::ImpactStatus::rigid_limit_exceeded)
    out << rigid_limit_warning(params, in) << '\n';
  else if (!phys::usable(r.status))
    line("message", r.message);
}

}  // namespace

nlohmann::ordered_json rebound_json(const phys::CushionParams& params, const Incidence& in,
                const phys::ImpactOptions& options, const phys::ImpactResult& r) {
  using nlohmann::ordered_json;
  const double spin_unit = in.speed / params.radius;
  const phys::Vec3& v = r.outgoing.velocity;
  const phys::Vec3& w = r.outgoing.spin;

  ordered_json transitions = ordered_json::array();
  for (int i = 0; i < r.transition_count; ++i)
    transitions.push_back({{"contact", phys::to_string(r.transitions[i].contact)},
                           {"state", r.transitions[i].sticking ? "stick" : "slip"},
                           {"impulse", r.transitions[i].impulse}});

  ordered_json j;
  j["status"] = phys::to_string(r.status);
  j["message"] = r.message;
  if (r.status == phys::ImpactStatus::rigid_limit_exceeded)
    j["warning"] = rigid_limit_warning(params, in);
  j["cushion_model"] = phys::to_string(r.model);
  j["method"] = phys::to_string(r.method_used);
  j["rebound_speed"] = r.rebound_speed;
  j["rebound_angle_deg"] = r.rebound_angle_deg;
  j["velocity"] = {v.x, v.y};
  j["spin"] = {w.x, w.y, w.z};
  j["impulse_compression"] = r.impulse_compression;
  j["impulse_total"] = r.impulse_total;
  j["work_compression"] = r.work_compression;
  j["work_total"] = r.work_total;
  j["slipping_at_start"] = {{"cushion", r.cushion_slipping_at_start},
                            {"table", r.table_slipping_at_start}};
  j["transitions"] = transitions;
  j["transitions_recorded"] = r.method_used != phys::ImpactMethod::table;
  j["rhs_evaluations"] = r.rhs_evaluations;
  j["input"] = {{"speed", in.speed},
                {"angle_deg", in.angle_deg},
                {"topspin", in.topspin},
                {"sidespin", in.sidespin},
                {"topspin_k", in.topspin / spin_unit},
                {"sidespin_k", in.sidespin / spin_unit},
                {"cushion_model", phys::to_string(params.model)},
                {"method", phys::to_string(options.method)},
                {"steps", options.paper_steps},
                {"tolerance", options.tolerance},
                {"mass", params.mass},
                {"radius", params.radius},
                {"cushion_height", params.cushion_height},
                {"mu_cushion", params.mu_cushion},
                {"mu_table", params.mu_table},
                {"restitution", params.restitution},
                {"rigid_speed_limit", params.rigid_speed_limit}};
  j["units"] = {{"frame", "cushion: X along the cushion, Y from the ball into it, Z up"},
                {"rebound_speed", "m/s"},
                {"rebound_angle_deg", "deg, from +X (mirror reflection: equal to angle_deg)"},
                {"velocity", "m/s"},
                {"spin", "rad/s"},
                {"impulse", "N s"},
                {"work", "J"},
                {"speed", "m/s"},
                {"angle_deg", "deg"},
                {"topspin", "rad/s"},
                {"sidespin", "rad/s, > 0 right spin"},
                {"mass", "kg"},
                {"radius", "m"},
                {"cushion_height", "m"}};
  return j;
}

namespace {

}  // namespace

ReboundCommand::ReboundCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "rebound",
      "Resolve a ball-cushion impact (Mathavan, Jackson & Parkin 2010; Han 2005 with "
      "--cushion-model han_2005; a Stronge compliant cushion with --cushion-model "
      "stronge_compliant) and print the outgoing velocity and spin.");
  CLI::App& c = *command_;
  const phys::CushionParams snooker;

  const char* ball = "Incoming ball";
  c.add_option("--speed", args_.speed,
               "Incoming speed V0 (m/s), > 0. Required unless --batch is given.")
      ->type_name("m/s")
      ->group(ball);
  c.add_option("--angle", args_.angle_deg,
               "Incidence angle alpha (deg) between the velocity and the cushion, in (0, 180); "
               "90 is head-on. Required unless --batch is given.")
      ->type_name("deg")
      ->group(ball);
  add_spin_flags(c, &args_.spin, ball, "V0", "");

  const char* method = "Method";
  c.add_option("--cushion-model", args_.cushion_model,
               "mathavan_2010 (friction at the cushion and the cloth over the impulse; the "
               "methods below solve it) or han_2005 (Han's closed form: one impulse with "
               "Newton's restitution --restitution and Coulomb friction --mu-cushion; "
               "--method, --steps and --tolerance play no part) or stronge_compliant (Han's "
               "normal impulse with a tangential spring at the contact, stiffness ratio "
               "--eta-squared: the slip can stick and reverse; also a closed form). "
               "docs/cushion_models.md")
      ->type_name("mathavan_2010|han_2005|stronge_compliant")
      ->capture_default_str()
      ->group(method);
  c.add_option("--method", args_.method,
               "exact (Taylor-series integrator with stick/slip events), extrapolation (a "
               "second exact method: Gragg-Bulirsch-Stoer extrapolation with the same events), "
               "paper (the paper's fixed-step scheme) or table (precomputed surrogate; falls "
               "back to exact outside its domain)")
      ->type_name("exact|extrapolation|paper|table")
      ->capture_default_str()
      ->group(method);
  c.add_option("--steps", args_.steps, "paper: number of impulse steps N, >= 1")
      ->type_name("N")
      ->capture_default_str()
      ->group(method);
  c.add_option("--tolerance", args_.tolerance,
               "exact, extrapolation: local error per step relative to V0, in [1e-15, 1e-2]; "
               "with --method table, for the impacts the table does not answer (default: "
               "matched to the table's accuracy, 1e-9)")
      ->type_name("TOL")
      ->capture_default_str()
      ->group(method);
  c.add_option("--table-cache", args_.table_cache,
               "table: directory for the cached table (default: $CUEPLAN_CACHE_DIR, else "
               "$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan)")
      ->type_name("DIR")
      ->group(method);

  // Physical parameters bind straight into CushionParams: its defaults are the help's.
  const char* physical = "Physical parameters (snooker defaults, from the paper)";
  using P = Flag<phys::CushionParams>;
  register_flags<phys::CushionParams>(c, &args_.params, {
      P{"--mass", &phys::CushionParams::mass, "kg", "Ball mass M (kg), > 0"},
      P{"--radius", &phys::CushionParams::radius, "m", "Ball radius R (m), > 0"},
      P{"--cushion-height", &phys::CushionParams::cushion_height, "m",
        "Height h of the cushion contact above the cloth (m), in (R, 2R); default 7R/5 "
        "of the radius in use (" + number(snooker.cushion_height) + " for the default radius)",
        false},
      P{"--mu-cushion", &phys::CushionParams::mu_cushion, "mu_w",
        "Ball-cushion sliding friction mu_w, >= 0 and below tan(theta)"},
      P{"--mu-table", &phys::CushionParams::mu_table, "mu_s", "Ball-cloth sliding friction mu_s, >= 0"},
      P{"--restitution", &phys::CushionParams::restitution, "e_e",
        "Energetic coefficient of restitution e_e, in (0, 1]"},
      P{"--eta-squared", &phys::CushionParams::eta_squared, "eta^2",
        "stronge_compliant only: the cushion contact's normal over tangential "
        "stiffness, in (0.875, 3.5)"},
  }, physical);

  const char* output = "Output";
  auto* json = c.add_flag("--json", args_.json,
                          "Print one JSON object (cushion frame, SI units) instead of text")
                   ->group(output);
  auto* batch =
      c.add_option("--batch", args_.batch_file,
                   "Resolve every row of a CSV file with header "
                   "'speed,angle_deg,topspin_k,sidespin_k' (m/s, deg, k_T, k_S) and write CSV "
                   "to stdout: the input columns, then rebound_speed,rebound_angle_deg,vx,vy,"
                   "wx,wy,wz,status,message, each block of rows as it is done; '-' reads "
                   "standard input. A bad row gets its own error status and the rest go on; a "
                   "summary (rows, rows of each status) goes to stderr.")
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
  for (const char* flag : {"--speed", "--angle", "--topspin", "--sidespin"})
    batch->excludes(c.get_option(flag));

  c.footer(
      "Frames: the cushion frame has X along the cushion, Y from the ball into the cushion and "
      "Z up; the rebound angle is measured from +X like alpha (a mirror reflection gives "
      "rebound angle = alpha).\n"
      "Normal speeds V0 sin(alpha) above " +
      number(physics::CushionParams{}.rigid_speed_limit, "m/s") +
      " are solved but flagged: the rigid-cushion model is not trusted there.\n"
      "Exit codes: 0 done (also when only flagged), 1 no usable result (--batch: some row "
      "without one, or a bad row), 2 bad input (--batch: the command line, or a file that "
      "cannot be opened or has the wrong header).\n"
      "Example: cueplan rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0");
}

bool ReboundCommand::selected() const { return command_->parsed(); }

bool ReboundCommand::given(const char* flag) const { return command_->count(flag) > 0; }

std::string ReboundCommand::read_options(phys::ImpactOptions* options) const {
  if (!phys::parse_method(args_.method, &options->method))
    return "--method must be one of exact, extrapolation, paper, table, got '" + args_.method +
           "'";
  options->paper_steps = args_.steps;
  options->tolerance = args_.tolerance;
  // With the table, a tolerance given is the one of the impacts it does not answer;
  // otherwise those match the table's accuracy.
  if (options->method == phys::ImpactMethod::table && given("--tolerance"))
    options->table_fallback_tolerance = args_.tolerance;
  if (std::string why = check_options(*options); !why.empty()) return why;
  if (args_.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args_.threads);
  return {};
}

std::string ReboundCommand::read_params(phys::CushionParams* params) const {
  *params = args_.params;
  if (!phys::parse_cushion_model(args_.cushion_model, &params->model))
    return "--cushion-model must be one of mathavan_2010, han_2005, stronge_compliant, got '" +
           args_.cushion_model + "'";
  // The cushion height follows the radius unless given.
  if (!given("--cushion-height"))
    params->cushion_height = phys::params_for_radius(params->radius).cushion_height;
  return check_params(*params);
}

std::string ReboundCommand::read_incidence(const phys::CushionParams& params, Incidence* in) const {
  if (!given("--speed")) return "--speed is required (m/s) unless --batch is given";
  if (!given("--angle")) return "--angle is required (deg) unless --batch is given";
  if (std::string why = check_incidence(args_.speed, args_.angle_deg, 0.0, 0.0, kFlagNames);
      !why.empty())
    return why;
  double topspin = 0.0, sidespin = 0.0;
  if (std::string why =
          read_spins(*command_, args_.spin, args_.speed, params.radius, &topspin, &sidespin);
      !why.empty())
    return why;
  *in = {args_.speed, args_.angle_deg, topspin, sidespin};
  return {};
}

struct ReboundCommand::Inputs {
  phys::ImpactOptions options;
  phys::CushionParams params;
  bool batch = false;
  bool check_only = false;             // validate(): standard input is not read
  std::unique_ptr<BatchReader> reader;  // with --batch, past its header
  Incidence in;                         // without
};

std::string ReboundCommand::read_inputs(Inputs* inputs) const {
  if (std::string why = read_options(&inputs->options); !why.empty()) return why;
  if (std::string why = read_params(&inputs->params); !why.empty()) return why;
  // The incoming ball(s): whole-input errors come before any table is built.
  inputs->batch = given("--batch");
  if (inputs->batch) {
    if (inputs->check_only && args_.batch_file == "-") return {};
    inputs->reader = std::make_unique<BatchReader>(args_.batch_file, kBatchInputHeader);
    return inputs->reader->error();
  }
  return read_incidence(inputs->params, &inputs->in);
}

int ReboundCommand::validate(std::ostream& err) const {
  Inputs inputs;
  inputs.check_only = true;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int ReboundCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };

  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty()) return usage(why);
  phys::ImpactOptions& options = inputs.options;
  const phys::CushionParams& params = inputs.params;
  const bool batch = inputs.batch;
  const Incidence& in = inputs.in;

  // The surrogate, built or loaded once for every impact of this run.
  std::optional<phys::ImpactTable> table;
  // (The table is the Mathavan model's: han_2005 and stronge_compliant are closed forms.)
  if (options.method == phys::ImpactMethod::table &&
      params.model == phys::CushionModel::mathavan_2010) {
    const std::string cache_dir =
        args_.table_cache.empty() ? default_table_cache_dir() : args_.table_cache;
    if (std::string why = ensure_directory(cache_dir); !why.empty())
      return usage("--table-cache: " + why);
    std::string note;
    std::string error;
    table = acquire_table(params, cache_dir, args_.threads, &note, &error);
    if (!table) {
      err << kCommandName << ": " << error << '\n';
      return kExitFailed;
    }
    if (!note.empty()) err << kCommandName << ": " << note << '\n';
    options.table = &*table;
  }

  if (batch) {
    return run_batch_command(*inputs.reader, rebound_batch_job(params, options, args_.threads),
                             out, err);
  }

  const phys::ImpactResult result = phys::resolve_impact(
      params, phys::incoming_state(in.speed, in.angle_deg, in.topspin, in.sidespin), options);
  if (result.status == phys::ImpactStatus::invalid_input)
    return usage(result.error ? message_in(*result.error, kCushionFlags) : result.message);
  if (args_.json)
    out << rebound_json(params, in, options, result).dump(2) << '\n';
  else
    write_text(out, params, in, result);
  return phys::usable(result.status) ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
