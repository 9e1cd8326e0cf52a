#include "search_flags.hpp"

#include <CLI/CLI.hpp>

#include "cueplan/api/words.hpp"

namespace cueplan::cli {

void add_impact_flags(CLI::App& command, ImpactArgs* args, const char* group) {
  command
      .add_option("--method", args->method,
                  "Cushion impacts: table (precomputed surrogate, the fast path for the "
                  "thousands of shots a search needs; built once, about 30 s on 2 cores, then "
                  "loaded from the cache), exact (Taylor-series integrator with stick/slip "
                  "events), extrapolation (a second exact method, Gragg-Bulirsch-Stoer "
                  "extrapolation) or paper (the paper's fixed-step scheme)")
      ->type_name("table|exact|extrapolation|paper")
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--accuracy", args->accuracy,
                  "Relative error wanted from each cushion impact, in [1e-12, 0.1]. table: the "
                  "table answers only where its measured error is within it (else exact does); "
                  "without this flag it is the table's measured error. exact, extrapolation: "
                  "their tolerance follows it. Default 1e-09 (exact)")
      ->type_name("REL")
      ->group(group);
  command
      .add_option("--table-cache", args->table_cache,
                  "table: directory for the cached table (default: $CUEPLAN_CACHE_DIR, else "
                  "$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan)")
      ->type_name("DIR")
      ->group(group);
}

void add_planner_flags(CLI::App& c, PlannerArgs* args, const char* group) {
  c.add_option("--global", args->global,
               "Global search (NLopt): direct_l (DIRECT-L), crs2 (controlled random search), "
               "mlsl (multi-level single linkage) or isres (evolution strategy); or (OMPL) "
               "ompl_kpiece1 (a KPIECE1 tree of strokes spread by where they land)")
      ->type_name("direct_l|crs2|mlsl|isres|ompl_kpiece1")
      ->capture_default_str()
      ->group(group);
  c.add_option("--local", args->local,
               "Local polish (NLopt, derivative-free): bobyqa, sbplx (Subplex), cobyla or "
               "neldermead")
      ->type_name("bobyqa|sbplx|cobyla|neldermead")
      ->capture_default_str()
      ->group(group);
  c.add_option("--max-evaluations", args->max_evaluations,
               "Budget: shot simulations for the search, global and local together, >= 10")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--max-time", args->max_time_s,
               "Budget: wall-clock time for the whole command (s), > 0: loading the impact "
               "table (not a first build), the search (up to 75 % of it), the exact "
               "verification and the Monte Carlo (an estimate the clock cuts short counts the "
               "strokes it played). A plan the clock ends is no longer reproducible from its "
               "seed")
      ->type_name("S")
      ->capture_default_str()
      ->group(group);
  c.add_option("--starts", args->starts, "Distinct global candidates polished locally, >= 1")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--seed", args->seed,
               "Seed of the search's own random choices (the same seed and options give the same "
               "answer); a reference half of the search and the success draws do not depend on it")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--noise", args->noise,
               "Scale of the player's execution noise (Gaussian: aim 0.125 deg, speed "
               "0.075 m/s, tip offset 0.5 mm each way plus --tip-offset-relative of the "
               "offset, squirt misjudged by --squirt-judgement of it; all times this), >= 0; "
               "0 is a perfect cue")
      ->type_name("X")
      ->capture_default_str()
      ->group(group);
  c.add_option("--tip-offset-relative", args->tip_offset_relative,
               "Execution noise: the tip offset's deviation each way grows by this fraction of "
               "the offset intended that way (docs/squirt.md), >= 0")
      ->type_name("F")
      ->capture_default_str()
      ->group(group);
  c.add_option("--squirt-judgement", args->squirt_judgement,
               "Execution noise: the player's allowance for squirt errs by this fraction of "
               "the squirt (an aim deviation; docs/squirt.md), >= 0")
      ->type_name("F")
      ->capture_default_str()
      ->group(group);
  c.add_option("--bridge-length", args->bridge_length,
               "Execution noise: a sideways tip error turns the cue about the bridge this far "
               "behind the tip (m; docs/squirt.md), >= 0; 0 shifts the cue without turning it")
      ->type_name("M")
      ->capture_default_str()
      ->group(group);
  c.add_flag("--robust", args->robust,
             "Maximise the success probability under the noise rather than the nominal miss")
      ->group(group);
  c.add_option("--samples", args->samples,
               "Noisy strokes simulated per success probability (Monte Carlo), >= 0; 0 skips it "
               "(>= 1 with --robust)")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_flag("--enforce-rigid-limit", args->enforce_rigid_limit,
             "Reject strokes that meet a cushion faster than " +
                 number(physics::CushionParams{}.rigid_speed_limit, "m/s") +
                 " along its normal, where the rigid-cushion model is not trusted (otherwise "
                 "such strokes are only flagged)")
      ->group(group);
  c.add_option("--alternatives", args->alternatives,
               "Distinct solutions (other cushion routes, draw or follow, left or right) reported "
               "besides the best, >= 0")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
}

}  // namespace cueplan::cli
