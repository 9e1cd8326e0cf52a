#include "search_flags.hpp"

#include <CLI/CLI.hpp>

#include "cueplan/api/words.hpp"
#include "flag_table.hpp"

namespace cueplan::cli {

void add_impact_flags(CLI::App& command, ImpactArgs* args, const char* group) {
  using F = Flag<ImpactArgs>;
  register_flags<ImpactArgs>(command, args, {
      F{"--method", &ImpactArgs::method, "table|exact|extrapolation|paper",
        "Cushion impacts: table (precomputed surrogate, the fast path for the "
        "thousands of shots a search needs; built once, about 30 s on 2 cores, then "
        "loaded from the cache), exact (Taylor-series integrator with stick/slip "
        "events), extrapolation (a second exact method, Gragg-Bulirsch-Stoer "
        "extrapolation) or paper (the paper's fixed-step scheme)"},
      F{"--accuracy", &ImpactArgs::accuracy, "REL",
        "Relative error wanted from each cushion impact, in [1e-12, 0.1]. table: the "
        "table answers only where its measured error is within it (else exact does); "
        "without this flag it is the table's measured error. exact, extrapolation: "
        "their tolerance follows it. Default 1e-09 (exact)",
        false},
      F{"--table-cache", &ImpactArgs::table_cache, "DIR",
        "table: directory for the cached table (default: $CUEPLAN_CACHE_DIR, else "
        "$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan)",
        false},
  }, group);
}

void add_planner_flags(CLI::App& c, PlannerArgs* args, const char* group) {
  using F = Flag<PlannerArgs>;
  register_flags<PlannerArgs>(c, args, {
      F{"--global", &PlannerArgs::global, "direct_l|crs2|mlsl|isres|ompl_kpiece1",
        "Global search (NLopt): direct_l (DIRECT-L), crs2 (controlled random search), "
        "mlsl (multi-level single linkage) or isres (evolution strategy); or (OMPL) "
        "ompl_kpiece1 (a KPIECE1 tree of strokes spread by where they land)"},
      F{"--local", &PlannerArgs::local, "bobyqa|sbplx|cobyla|neldermead",
        "Local polish (NLopt, derivative-free): bobyqa, sbplx (Subplex), cobyla or "
        "neldermead"},
      F{"--max-evaluations", &PlannerArgs::max_evaluations, "N",
        "Budget: shot simulations for the search, global and local together, >= 10"},
      F{"--max-time", &PlannerArgs::max_time_s, "S",
        "Budget: wall-clock time for the whole command (s), > 0: loading the impact "
        "table (not a first build), the search (up to 75 % of it), the exact "
        "verification and the Monte Carlo (an estimate the clock cuts short counts the "
        "strokes it played). A plan the clock ends is no longer reproducible from its "
        "seed"},
      F{"--starts", &PlannerArgs::starts, "N", "Distinct global candidates polished locally, >= 1"},
      F{"--seed", &PlannerArgs::seed, "N",
        "Seed of the search's own random choices (the same seed and options give the same "
        "answer); a reference half of the search and the success draws do not depend on it"},
      F{"--noise", &PlannerArgs::noise, "X",
        "Scale of the player's execution noise (Gaussian: aim 0.125 deg, speed "
        "0.075 m/s, tip offset 0.5 mm each way plus --tip-offset-relative of the "
        "offset, squirt misjudged by --squirt-judgement of it; all times this), >= 0; "
        "0 is a perfect cue"},
      F{"--tip-offset-relative", &PlannerArgs::tip_offset_relative, "F",
        "Execution noise: the tip offset's deviation each way grows by this fraction of "
        "the offset intended that way (docs/squirt.md), >= 0"},
      F{"--squirt-judgement", &PlannerArgs::squirt_judgement, "F",
        "Execution noise: the player's allowance for squirt errs by this fraction of "
        "the squirt (an aim deviation; docs/squirt.md), >= 0"},
      F{"--bridge-length", &PlannerArgs::bridge_length, "M",
        "Execution noise: a sideways tip error turns the cue about the bridge this far "
        "behind the tip (m; docs/squirt.md), >= 0; 0 shifts the cue without turning it"},
      F{"--robust", &PlannerArgs::robust, "",
        "Maximise the success probability under the noise rather than the nominal miss"},
      F{"--samples", &PlannerArgs::samples, "N",
        "Noisy strokes simulated per success probability (Monte Carlo), >= 0; 0 skips it "
        "(>= 1 with --robust)"},
      F{"--enforce-rigid-limit", &PlannerArgs::enforce_rigid_limit, "",
        "Reject strokes that meet a cushion faster than " +
            number(physics::CushionParams{}.rigid_speed_limit, "m/s") +
            " along its normal, where the rigid-cushion model is not trusted (otherwise "
            "such strokes are only flagged)"},
      F{"--alternatives", &PlannerArgs::alternatives, "N",
        "Distinct solutions (other cushion routes, draw or follow, left or right) reported "
        "besides the best, >= 0"},
  }, group);
}

}  // namespace cueplan::cli
