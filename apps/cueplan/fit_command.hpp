// `cueplan fit TRACKS.jsonl`: for every recorded shot, the stroke whose simulation on the
// carom table best matches the tracked cue ball (planner/fit.hpp), reported as a table,
// JSON lines and pictures of the recorded samples over the simulated paths.
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cueplan/planner/fit.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// The shots of a tracks file (`-`: stdin) placed on `table`. Each bad line or shot gets
// one line on `err` (naming the shot and the ball) and is left out; *bad counts them.
// Empty with *bad = -1 when the file cannot be read (its line written).
std::vector<planner::ShotData> read_tracks(const std::string& path, const physics::Scene& table,
                                           const planner::TrackFrame& frame,
                                           const std::string& command, std::ostream& err,
                                           int* bad);

// The carom table, with `--physics FILE`'s physics: block applied when the path is not
// empty. Empty on success; otherwise the line to print.
std::string carom_table(const std::string& physics_file, physics::Scene* scene);

// The physics: block of a scene's constants, as problem files and --physics take it.
nlohmann::ordered_json physics_json(const physics::Scene& scene);

// The stroke search's flags, shared by `fit` and `calibrate` (planner::FitOptions).
struct StrokeSearchArgs {
  double max_elevation_deg = planner::FitOptions{}.max_elevation_deg;
  int spin_starts = planner::FitOptions{}.spin_starts;
  int global_evaluations = planner::FitOptions{}.global_evaluations;
  int local_evaluations = planner::FitOptions{}.local_evaluations;
  double huber_delta = planner::FitOptions{}.huber_delta;
  int restarts = planner::FitOptions{}.restarts;
  bool no_horizon = false;
};
// Adds --max-elevation, --spin-starts, --global-evaluations, --local-evaluations,
// --restarts, --huber-delta and --no-horizon.
void add_stroke_search_flags(CLI::App& command, StrokeSearchArgs* args);
// Empty when the values are usable; otherwise the line to print (naming the flag).
std::string check_stroke_search(const StrokeSearchArgs& args);
// The flags applied to a FitOptions.
void apply_stroke_search(const StrokeSearchArgs& args, planner::FitOptions* options);

struct FitArgs {
  std::string tracks_file;
  bool all_balls = false;
  bool json = false;
  std::string svg_dir, png_dir;
  std::string physics_file;
  int threads = 0;
  StrokeSearchArgs search;
};

class FitCommand {
 public:
  explicit FitCommand(CLI::App& parent);
  FitCommand(const FitCommand&) = delete;
  FitCommand& operator=(const FitCommand&) = delete;
  bool selected() const;
  int validate(std::ostream& err) const;
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_ = nullptr;
  FitArgs args_;
};

}  // namespace cueplan::cli
