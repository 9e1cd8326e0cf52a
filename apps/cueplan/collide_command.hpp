// `cueplan collide`: a cue ball striking an object ball at rest (or a CSV batch of such
// shots) through physics::resolve_table_collision, reported as text, JSON or CSV.
#pragma once

#include <cmath>
#include <iosfwd>
#include <string>

#include "cueplan/physics/ball_collision.hpp"
#include "spin_flags.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct CollideArgs {
  double speed = NAN;    // m/s, --speed
  double cut_deg = NAN;  // deg, --cut
  SpinArgs spins;        // --topspin-k, --sidespin-k, --topspin, --sidespin
  std::string spin;      // "WX,WY,WZ" rad/s, --spin (replaces them)
  std::string model = "mathavan_2014";
  std::string ball_friction = "constant";
  std::string method = "exact";
  int steps = 5000;          // paper scheme N
  double tolerance = 1e-12;  // exact method
  // --mass, --radius, --mu-ball, --ball-restitution, --mu-table.
  physics::BallBallParams params;
  bool json = false;
  std::string batch_file;
  int threads = 0;  // batch threads; 0: one per core
};

class CollideCommand {
 public:
  // Registers `collide` and its flags on `parent`; the flags write into this object,
  // so it must outlive the parse and stay where it is.
  explicit CollideCommand(CLI::App& parent);
  CollideCommand(const CollideCommand&) = delete;
  CollideCommand& operator=(const CollideCommand&) = delete;

  bool selected() const;

  // Checks every flag and the batch file without doing any work or writing anything;
  // returns kExitOk, or kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;  // everything run() needs, read and checked from the flags

  bool given(const char* flag) const;
  // All the checks of validate(); empty or the one-line reason to stop. In order: the
  // model and its options, the parameters, then the shot or the batch file.
  std::string read_inputs(Inputs* inputs) const;
  std::string read_options(physics::CollisionOptions* options) const;
  std::string read_params(physics::BallBallParams* params) const;
  std::string read_shot(const physics::BallBallParams& params, Inputs* inputs) const;

  CLI::App* command_ = nullptr;
  CollideArgs args_;
};

}  // namespace cueplan::cli
