// The messages people see for bad input, pinned word for word: each layer names the
// field its own way (the problem file's FILE:LINE: FIELD, the command line's flag), from
// the same typed error, and rewording one layer's rule must not lose the field or the line.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_support.hpp"

const char* const cli_test::kScratchName = "cueplan_messages_cli_test";

namespace {

using cli_test::cueplan;
using cli_test::scratch;
using cli_test::write_text;

struct FileCase {
  const char* name;
  const char* yaml;
  const char* message;  // after "cueplan solve: FILE:"
};

class ProblemFileMessage : public ::testing::TestWithParam<FileCase> {};

TEST_P(ProblemFileMessage, NamesTheFileTheLineAndTheField) {
  const FileCase& c = GetParam();
  const std::string file = (scratch() / (std::string(c.name) + ".yaml")).string();
  write_text(file, c.yaml);
  const cli_test::ProcessResult run = cueplan("solve '" + file + "' --max-evaluations 50");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "cueplan solve: " + file + ":" + c.message + "\n");
  EXPECT_EQ(run.out, "");
}

const FileCase kFileCases[] = {
    {"NegativeLength", "table: {length: -1}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: table.length: must be positive, got -1"},
    {"TableTooShort", "table: {length: 0.03, width: 1}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: table.length: must leave room for a ball: more than 2 R cos(theta) = 0.04812 m "
     "(ball.radius R = 0.02625 m), got 0.03"},
    {"BallTooBig", "ball: {radius: 1.0}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: ball.radius: leaves no room for the ball on the table: 2 R cos(theta) must be below "
     "table.width = 1.778 m"},
    {"CushionFriction", "physics: {mu_cushion: 0.9}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: physics.mu_cushion: must be below tan(theta) of the cushion contact, or the cushion "
     "lifts the ball off the cloth, got 0.9"},
    {"ClothFriction", "physics: {mu_slide: 3.0}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: physics.mu_slide: is too large together with physics.mu_cushion: friction could stop "
     "the cushion from turning the ball round, got 3"},
    {"CueBallOffTable", "cue_ball: [5,1]\ntarget: [2,1]\n",
     "1: cue_ball: (5, 1) lies off the table: its centre must be within [0.02406, 3.545] x "
     "[0.02406, 1.754] m"},
    {"TargetOffTable", "cue_ball: [1,1]\ntarget: [2,-1]\n",
     "2: target: (2, -1) lies off the table: its centre must be within [0.02406, 3.545] x "
     "[0.02406, 1.754] m"},
    {"ObstaclesOverlap", "obstacles: [[1.5,0.9],[1.52,0.9]]\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: obstacles[1]: overlaps obstacles[0]"},
    {"CueBallOnObstacle", "obstacles: [[1.0,1.01]]\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "2: cue_ball: overlaps obstacles[0]"},
    {"CueBallInPocket",
     "table: {length: 0.2, width: 0.2, pocket_radius: 0.2}\ncue_ball: [0.1,0.1]\n"
     "target: [0.1,0.12]\n",
     "2: cue_ball: lies inside the bottom_left pocket"},
    {"MisspeltKey", "cue_ball: [1,1]\ntarget: [2,1]\ntolerence: 0.1\n",
     "3: tolerence: unknown key; expected one of name, table, ball, physics, cue_ball, target, "
     "tolerance, obstacles, balls, limits, max_strokes, time_budget_s, pot, first_contact, cue, "
     "next, leave (did you mean tolerance?)"},
    {"BallOffTable",
     "balls:\n  red: [1.5,0.9]\n  blue: [3.6,0.9]\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "3: balls.blue: (3.6, 0.9) lies off the table: its centre must be within [0.02406, 3.545] x "
     "[0.02406, 1.754] m"},
    {"BallsOverlap", "balls: {red: [1.5,0.9], blue: [1.52,0.9]}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: balls.red: overlaps balls.blue"},
    {"BallOnObstacle",
     "obstacles: [[1.5,0.9]]\nballs:\n  red: [1.5,0.93]\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "3: balls.red: overlaps obstacles[0]"},
    {"CueBallOnBall", "balls: {red: [1.03,1]}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "2: cue_ball: overlaps balls.red"},
    {"UnknownBallModel", "physics: {ball_model: mathavan_2015}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: physics.ball_model: must be one of mathavan_2014, frictional_inelastic, got "
     "\"mathavan_2015\" (did you mean mathavan_2014?)"},
    {"UnknownBallName",
     "balls: {red: [1.5,0.9]}\npot: {ball: ред, pocket: top_left}\ncue_ball: [1,1]\n"
     "target: [2,1]\n",
     "2: pot.ball: must be the name of a ball in balls: red, got \"ред\""},
    {"MisspeltBallName",
     "balls: {red: [1.5,0.9], yellow: [2.5,0.9]}\nfirst_contact: yelow\ncue_ball: [1,1]\n"
     "target: [2,1]\n",
     "2: first_contact: must be the name of a ball in balls or a class of balls: red, yellow, "
     "any_red, lowest, solids, stripes, any_colour, got \"yelow\" (did you mean yellow?)"},
    {"UnknownPocket",
     "balls: {red: [1.5,0.9]}\npot: {ball: red, pocket: top_midle}\ncue_ball: [1,1]\n"
     "target: [2,1]\n",
     "2: pot.pocket: must be one of bottom_left, bottom_middle, bottom_right, top_left, "
     "top_middle, top_right, got \"top_midle\" (did you mean top_middle?)"},
    {"PotWithoutBalls",
     "pot: {ball: red, pocket: top_left}\ncue_ball: [1,1]\n",
     "1: pot.ball: names an object ball, but the file has no balls: \"red\""},
    {"PotOnATableWithoutPockets",
     "table: {pockets: none}\nballs: {red: [1.5,0.9]}\npot: {ball: red, pocket: top_left}\n"
     "cue_ball: [1,1]\n",
     "3: pot.pocket: names the top_left pocket, but the table has none (table.pockets: none)"},
    {"FirstContactNamesTheCueBall",
     "balls: {red: [1.5,0.9]}\npot: {ball: red, pocket: top_left}\nfirst_contact: cue\n"
     "cue_ball: [1,1]\n",
     "3: first_contact: must be the name of a ball in balls or a class of balls: red, any_red, "
     "lowest, solids, stripes, any_colour, got \"cue\""},
    {"TargetMissingWithoutAPot", "cue_ball: [1,1]\n",
     "1: target: missing; required: where the cue ball should stop, [x, y] in m (optional with a "
     "pot or a first_contact)"},
    {"BallFrictionTooHigh", "physics: {mu_ball: 1.5}\ncue_ball: [1,1]\ntarget: [2,1]\n",
     "1: physics.mu_ball: times physics.mu_slide must be below 2/7 for mathavan_2014: a larger "
     "friction could hold a ball's slip on the cloth at zero, which the model does not describe, "
     "got 1.5"},
    {"SpeedLimits", "cue_ball: [1,1]\ntarget: [2,1]\nlimits: {speed: [3, 1]}\n",
     "3: limits.speed: min must be below max, got [3, 1]"},
    {"YamlSyntax", "cue_ball: [1,1\ntarget: [2,1]\n",
     "2: yaml: end of sequence flow not found (column 7)"},
};

INSTANTIATE_TEST_SUITE_P(Problems, ProblemFileMessage, ::testing::ValuesIn(kFileCases),
                         [](const auto& info) { return std::string(info.param.name); });

struct FlagCase {
  const char* name;
  const char* args;
  const char* message;
};

class FlagMessage : public ::testing::TestWithParam<FlagCase> {};

TEST_P(FlagMessage, NamesTheFlag) {
  const FlagCase& c = GetParam();
  std::string args = c.args;
  const std::string problem = "PROBLEM";
  if (const size_t at = args.find(problem); at != std::string::npos)
    args.replace(at, problem.size(), cli_test::problem_path("one_rail_position"));
  const cli_test::ProcessResult run = cueplan(args);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, std::string(c.message) + "\n");
}

const FlagCase kFlagCases[] = {
    {"ReboundMass", "rebound --speed 1 --angle 45 --mass -2",
     "cueplan rebound: --mass must be positive and finite (kg), got -2"},
    {"ReboundCushionHeight", "rebound --speed 1 --angle 45 --cushion-height 0.01",
     "cueplan rebound: --cushion-height must lie between radius and 2*radius (m): the cushion "
     "touches the ball above its equator, got 0.01"},
    {"ReboundTableFriction", "rebound --speed 1 --angle 45 --mu-table 5",
     "cueplan rebound: --mu-table is too large together with --mu-cushion: friction could stop "
     "the cushion from turning the ball round, got 5"},
    {"ReboundSteps", "rebound --speed 1 --angle 45 --steps 0 --method paper",
     "cueplan rebound: --steps must be at least 1, got 0"},
    {"ReboundTolerance", "rebound --speed 1 --angle 45 --tolerance 1",
     "cueplan rebound: --tolerance must lie in [1e-15, 1e-2], got 1"},
    {"SimulateAim", "simulate PROBLEM --speed 1 --aim nan",
     "cueplan simulate: --aim must be finite (deg), got nan"},
    {"SolveEvaluations", "solve PROBLEM --max-evaluations 5",
     "cueplan solve: --max-evaluations must be at least 10, got 5"},
    {"SolveNoise", "solve PROBLEM --noise -1",
     "cueplan solve: --noise must be 0 to 10 (times a club player's scatter), got -1"},
    {"RouteStrokes", "route PROBLEM --max-strokes 0",
     "cueplan route: --max-strokes must lie in [1, 100], got 0"},
    {"RouteSteering", "route PROBLEM --steer-evaluations 2",
     "cueplan route: --steer-evaluations must be at least 10, got 2"},
    {"SpinmapGrid", "spinmap PROBLEM --out x.svg --grid 1",
     "cueplan spinmap: --grid must be 3 to 1001 points across the disc, got 1"},
};

INSTANTIATE_TEST_SUITE_P(Flags, FlagMessage, ::testing::ValuesIn(kFlagCases),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
