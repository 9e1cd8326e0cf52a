// `cueplan rebound`: one ball-cushion impact (or a CSV batch of them) through
// physics::resolve_impact, reported as text, JSON or CSV.
#pragma once

#include <cmath>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/physics/cushion_impact.hpp"
#include "spin_flags.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct ReboundArgs {
  double speed = NAN;       // m/s, --speed
  double angle_deg = NAN;   // deg, --angle
  SpinArgs spin;            // --topspin-k, --sidespin-k, --topspin, --sidespin
  std::string method = physics::to_string(physics::ImpactOptions{}.method);
  int steps = physics::ImpactOptions{}.paper_steps;      // paper scheme N
  double tolerance = physics::ImpactOptions{}.tolerance;  // exact method
  // --mass, --radius, --mu-cushion, --mu-table, --restitution, --cushion-height;
  // the cushion height becomes 7R/5 of the radius unless given.
  physics::CushionParams params;
  std::string cushion_model = physics::to_string(physics::CushionParams{}.model);  // --cushion-model
  bool json = false;
  std::string batch_file;
  int threads = 0;          // batch threads; 0: one per core
  std::string table_cache;  // empty: default_table_cache_dir() (table_cache.hpp)
};

// One incoming ball as resolved from the flags.
struct Incidence {
  double speed = 0.0;      // m/s, V0
  double angle_deg = 0.0;  // deg, alpha
  double topspin = 0.0;    // rad/s, w_T
  double sidespin = 0.0;   // rad/s, w_S
};

class ReboundCommand {
 public:
  // Registers `rebound` and its flags on `parent`; the flags write into this object,
  // so it must outlive the parse and stay where it is.
  explicit ReboundCommand(CLI::App& parent);
  ReboundCommand(const ReboundCommand&) = delete;
  ReboundCommand& operator=(const ReboundCommand&) = delete;

  bool selected() const;

  // Checks every flag and the batch file without doing any work or writing anything;
  // returns kExitOk, or kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;  // everything run() needs, read and checked from the flags

  bool given(const char* flag) const;
  // All the checks of validate(); empty or the one-line reason to stop.
  std::string read_inputs(Inputs* inputs) const;

  // Stages of run(), in order; each returns empty or the one-line reason to stop.
  std::string read_options(physics::ImpactOptions* options) const;
  std::string read_params(physics::CushionParams* params) const;
  std::string read_incidence(const physics::CushionParams& params, Incidence* in) const;

  CLI::App* command_ = nullptr;
  ReboundArgs args_;
};

// What `cueplan rebound --json` prints for one impact.
nlohmann::ordered_json rebound_json(const physics::CushionParams& params, const Incidence& in,
                                    const physics::ImpactOptions& options,
                                    const physics::ImpactResult& r);

}  // namespace cueplan::cli
