#include "calibrate_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <vector>

#include "cueplan/planner/fit.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "fit_command.hpp"
#include "cueplan/api/output_file.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;

constexpr const char* kCommandName = "cueplan calibrate";

double quantile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

std::string stats(const std::vector<double>& v) {
  return fmt::format("median {:.2f} cm, 90th percentile {:.2f} cm, mean {:.2f} cm",
                     100 * quantile(v, 0.5), 100 * quantile(v, 0.9), [&] {
                       double s = 0;
                       int n = 0;
                       for (double x : v)
                         if (std::isfinite(x)) s += 100 * x, ++n;
                       return n ? s / n : NAN;
                     }());
}

}  // namespace

CalibrateCommand::CalibrateCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "calibrate",
      "Fit the carom table's shared constants (cloth sliding, rolling and spin friction, "
      "cushion friction, restitution and height, ball-ball friction and restitution) to "
      "recorded shots, each shot's stroke refitted inside, with k-fold cross-validation.");
  CLI::App& c = *command_;
  c.add_option("TRACKS", args_.tracks_file, "Tracks file, one shot a JSON line ('-': stdin)")
      ->required()
      ->type_name("TRACKS.jsonl");
  c.add_option("--folds", args_.folds,
               "Cross-validation folds (shot i goes to fold i mod K); 1: no cross-validation")
      ->capture_default_str();
  c.add_option("--rounds", args_.rounds, "Alternations of constants and strokes")
      ->capture_default_str();
  c.add_option("--evaluations", args_.evaluations,
               "Loss evaluations of the constants' local search per round")
      ->capture_default_str();
  c.add_option("--refit-evaluations", args_.refit_evaluations,
               "Local evaluations of each stroke's refit inside every evaluation of the "
               "constants")
      ->capture_default_str();
  c.add_option("--out", args_.out_file,
               "Write the constants as a physics: block (for problem files and `fit --physics`)")
      ->type_name("physics.yaml");
  c.add_option("--physics", args_.physics_file,
               "Start from this physics: block instead of the carom preset's constants")
      ->type_name("FILE");
  c.add_option("--threads", args_.threads, "Threads (0: one per core)")->capture_default_str();
  c.add_option("--constant-step", args_.constant_step,
               "The constants' search's first step, as a fraction of each constant's range")
      ->capture_default_str();
  c.add_flag("--keep-mu-roll", args_.keep_mu_roll,
             "Start mu_roll's search from the starting constants' value, not from the "
             "rolling resistance measured on the training shots' final straight rolls");
  add_stroke_search_flags(c, &args_.search);
}

bool CalibrateCommand::selected() const { return command_->parsed(); }

int CalibrateCommand::validate(std::ostream& err) const {
  if (args_.folds < 1) return usage_error(err, kCommandName, "--folds must be >= 1");
  if (args_.rounds < 1) return usage_error(err, kCommandName, "--rounds must be >= 1");
  if (args_.evaluations < 1) return usage_error(err, kCommandName, "--evaluations must be >= 1");
  if (args_.refit_evaluations < 0)
    return usage_error(err, kCommandName, "--refit-evaluations must be >= 0");
  if (args_.threads < 0) return usage_error(err, kCommandName, "--threads must be >= 0");
  if (!(args_.constant_step > 0.0 && args_.constant_step <= 0.5))
    return usage_error(err, kCommandName, "--constant-step must be in (0, 0.5]");
  if (std::string why = check_stroke_search(args_.search); !why.empty())
    return usage_error(err, kCommandName, why);
  if (!args_.out_file.empty())
    if (std::string why = check_output_file(args_.out_file); !why.empty())
      return usage_error(err, kCommandName, "--out: " + why);
  phys::Scene scene;
  if (std::string why = carom_table(args_.physics_file, &scene); !why.empty())
    return usage_error(err, kCommandName, why);
  return kExitOk;
}

int CalibrateCommand::run(std::ostream& out, std::ostream& err) const {
  if (const int code = validate(err); code != kExitOk) return code;
  phys::Scene table;
  carom_table(args_.physics_file, &table);
  int bad = 0;
  const std::vector<plan::ShotData> shots =
      read_tracks(args_.tracks_file, table, plan::TrackFrame{}, kCommandName, err, &bad);
  if (bad < 0 || shots.empty()) return kExitUsage;
  plan::CalibrationOptions o;
  o.folds = args_.folds;
  o.rounds = args_.rounds;
  o.constant_evaluations = args_.evaluations;
  o.refit_evaluations = args_.refit_evaluations;
  o.threads = args_.threads;
  apply_stroke_search(args_.search, &o.fit);
  o.measure_rolling = !args_.keep_mu_roll;
  o.constant_step = args_.constant_step;
  const plan::CalibrationResult r = plan::calibrate(
      shots, table, o, [&err](const std::string& line) { err << kCommandName << ": " << line << '\n'; });

  out << "shots: " << r.ids.size() << ", folds: " << args_.folds << "\n";
  out << "cue-ball RMSE, starting constants:      " << stats(r.rmse_before_m) << "\n";
  if (args_.folds > 1)
    out << "cue-ball RMSE, held out (cross-valid.): " << stats(r.rmse_heldout_m) << "\n";
  out << "cue-ball RMSE, all-shot constants:      " << stats(r.rmse_all_shots_m)
      << " (fitted on these shots)\n\n";
  out << fmt::format("{:<18} {:>11} {:>11} {:>12} {:>12}  {}\n", "constant", "start", "fitted",
                     "fold spread", "1% loss +-", "constrained");
  const std::vector<double> start = plan::constants_of(table);
  for (size_t i = 0; i < r.report.size(); ++i) {
    const plan::ConstantReport& c = r.report[i];
    out << fmt::format("{:<18} {:>11.5g} {:>11.5g} {:>12.3g} {:>12.3g}  {}\n", c.name, start[i],
                       c.value, c.fold_spread, c.half_width, c.constrained ? "yes" : "no (flat)");
  }
  if (!r.measured_mu_roll.empty()) {
    // The start of mu_roll's search: the final rolls of each fold's training shots, then
    // of all shots.
    out << "\nrolling resistance from final rolls (mu_roll's start, from 5 rolls on):";
    for (size_t i = 0; i < r.measured_mu_roll.size(); ++i) {
      const int rolls = r.measured_rolls[i];
      out << fmt::format(" {}{:.5g} ({} roll{}{})",
                         i + 1 < r.measured_mu_roll.size() ? fmt::format("fold {}: ", i + 1)
                                                             : std::string("all shots: "),
                         r.measured_mu_roll[i], rolls, rolls == 1 ? "" : "s",
                         rolls < 5 ? ", not used" : "");
    }
    out << "\n";
  }
  out << "\nper shot (cm): id fold before held_out all_shots\n";
  for (size_t i = 0; i < r.ids.size(); ++i)
    out << fmt::format("{} {} {:.2f} {:.2f} {:.2f}\n", r.ids[i], r.fold_of[i],
                       100 * r.rmse_before_m[i], 100 * r.rmse_heldout_m[i],
                       100 * r.rmse_all_shots_m[i]);
  if (!args_.out_file.empty()) {
    phys::Scene s = table;
    plan::set_constants(r.constants, &s);
    std::string text =
        fmt::format("# cueplan calibrate {}: {} shots, {} folds; held-out cue-ball RMSE {}\n",
                    args_.tracks_file, r.ids.size(), args_.folds,
                    args_.folds > 1 ? stats(r.rmse_heldout_m) : std::string("(none)"));
    text += "physics:\n";
    const nlohmann::ordered_json block = physics_json(s);
    for (const auto& [key, value] : block.items()) {
      text += "  " + key + ": " + value.dump();
      for (const plan::ConstantReport& c : r.report)
        if (c.name == key)
          text += fmt::format("  # fold spread {:.3g}, 1% loss +-{:.3g}{}", c.fold_spread,
                              c.half_width, c.constrained ? "" : ", not constrained");
      text += "\n";
    }
    if (std::string why = write_file_atomically(args_.out_file, text); !why.empty()) {
      err << kCommandName << ": --out: " << why << '\n';
      return kExitFailed;
    }
  }
  return bad > 0 ? kExitUsage : kExitOk;
}

}  // namespace cueplan::cli
