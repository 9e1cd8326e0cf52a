// The command line's contract for bad input, command by command: exit code 2, exactly
// one line on stderr naming the flag (or file) at fault, nothing on stdout, and no
// output file left behind - neither the one asked for nor a temporary beside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_main.hpp"
#include "cli_test_support.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_exit_codes_test_";

namespace {

namespace fs = std::filesystem;

struct BadCommandLine {
  const char* name;   // the test's name
  std::string args;   // after `cueplan`; PROBLEM stands for a shipped problem file
  const char* names;  // what the one line must mention
};

// Where the bad command lines point their output: a directory of their own, so that a
// file written by mistake shows up there.
fs::path bad_dir() { return scratch() / "bad_arguments"; }

std::string expanded(std::string args) {
  const std::string problem = "'" + problem_path("one_rail_position") + "'";
  for (std::size_t at = args.find("PROBLEM"); at != std::string::npos;
       at = args.find("PROBLEM", at + problem.size()))
    args.replace(at, 7, problem);
  const std::string scratch_dir = "'" + bad_dir().string() + "'";
  for (std::size_t at = args.find("SCRATCH"); at != std::string::npos;
       at = args.find("SCRATCH", at + scratch_dir.size()))
    args.replace(at, 7, scratch_dir);
  return args;
}

// Files in bad_dir() other than the one the tests put there.
std::vector<std::string> output_files() {
  std::vector<std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(bad_dir())) {
    const std::string name = entry.path().filename().string();
    if (name == "not_a_directory") continue;
    files.push_back(name);
  }
  return files;
}

class BadArguments : public ::testing::TestWithParam<BadCommandLine> {};

TEST_P(BadArguments, ExitTwoWithOneLineNamingTheFlagAndWriteNothing) {
  const BadCommandLine& bad = GetParam();
  fs::create_directories(bad_dir());
  write_text(bad_dir() / "not_a_directory", "a file\n");
  const ProcessResult run = cueplan(expanded(bad.args));
  EXPECT_EQ(run.exit_code, 2) << bad.args << "\n" << run.err;
  ASSERT_EQ(lines_of(run.err).size(), 1u) << bad.args << "\n" << run.err;
  EXPECT_TRUE(run.err.ends_with("\n")) << run.err;
  EXPECT_NE(run.err.find(bad.names), std::string::npos)
      << "'" << bad.args << "' should name " << bad.names << ":\n" << run.err;
  EXPECT_EQ(run.out, "") << bad.args;
  EXPECT_EQ(output_files(), std::vector<std::string>{}) << bad.args;
}

// SCRATCH stands for bad_dir().
const BadCommandLine kBadCommandLines[] = {
    {"NoCommand", "", "cueplan"},
    {"UnknownCommand", "frobnicate --speed 1", "frobnicate"},
    {"UnknownFlag", "rebound --speed 1 --angle 45 --bogus 3", "--bogus"},
    // rebound
    {"ReboundSpeedNotANumber", "rebound --speed fast --angle 45", "--speed"},
    {"ReboundSpeedNaN", "rebound --speed nan --angle 45", "--speed"},
    {"ReboundSpeedNegative", "rebound --speed -1 --angle 45", "--speed"},
    {"ReboundSpeedInfinite", "rebound --speed inf --angle 45", "--speed"},
    {"ReboundAngleMissing", "rebound --speed 1", "--angle"},
    {"ReboundAngleOutOfRange", "rebound --speed 1 --angle 190", "--angle"},
    {"ReboundUnknownMethod", "rebound --speed 1 --angle 45 --method fast", "--method"},
    {"ReboundNoSteps", "rebound --speed 1 --angle 45 --method paper --steps 0", "--steps"},
    {"ReboundMassZero", "rebound --speed 1 --angle 45 --mass 0", "--mass"},
    {"ReboundRestitutionNaN", "rebound --speed 1 --angle 45 --restitution nan", "--restitution"},
    {"ReboundBatchMissing", "rebound --batch SCRATCH/missing.csv", "--batch"},
    {"ReboundThreadsNegative", "rebound --batch SCRATCH/missing.csv --threads -1", "--threads"},
    // collide
    {"CollideSpeedNaN", "collide --speed nan --cut 30", "--speed"},
    {"CollideCutMissing", "collide --speed 1", "--cut"},
    {"CollideUnknownModel", "collide --speed 1 --cut 30 --model fast", "--model"},
    {"CollideBatchMissing", "collide --batch SCRATCH/missing.csv", "--batch"},
    // simulate
    {"SimulateSpeedNaN", "simulate PROBLEM --speed nan --aim 0", "--speed"},
    {"SimulateSpeedNegative", "simulate PROBLEM --speed -2 --aim 0", "--speed"},
    {"SimulateAimMissing", "simulate PROBLEM --speed 1", "--aim"},
    {"SimulateNoEvents", "simulate PROBLEM --speed 1 --aim 0 --max-events 0", "--max-events"},
    {"SimulateAccuracyZero", "simulate PROBLEM --speed 1 --aim 0 --accuracy 0", "--accuracy"},
    {"SimulateProblemMissing", "simulate SCRATCH/missing.yaml --speed 1 --aim 0", "missing.yaml"},
    {"SimulateProblemIsADirectory", "simulate SCRATCH --speed 1 --aim 0", "is a directory"},
    {"SimulateSvgInMissingDirectory",
     "simulate PROBLEM --speed 1 --aim 0 --svg SCRATCH/missing/path.svg", "--svg"},
    {"SimulateSvgUnderAFile",
     "simulate PROBLEM --speed 1 --aim 0 --svg SCRATCH/not_a_directory/path.svg", "--svg"},
    {"SimulateSvgIsADirectory", "simulate PROBLEM --speed 1 --aim 0 --svg SCRATCH", "--svg"},
    {"SimulateBadSpeedWithSvg", "simulate PROBLEM --speed nan --aim 0 --svg SCRATCH/path.svg",
     "--speed"},
    {"SimulateSvgUnknownExtension", "simulate PROBLEM --speed 1 --aim 0 --svg SCRATCH/path.jpg",
     "--svg"},
    // solve
    {"SolveProblemMissing", "solve SCRATCH/missing.yaml --method exact", "missing.yaml"},
    {"SolveThreadsNegative", "solve PROBLEM --method exact --threads -1", "--threads"},
    {"SolveUnknownMethod", "solve PROBLEM --method fast", "--method"},
    {"SolveSeedNotANumber", "solve PROBLEM --seed seven", "--seed"},
    {"SolveNoEvaluations", "solve PROBLEM --method exact --max-evaluations 0",
     "--max-evaluations"},
    {"SolveSvgInMissingDirectory", "solve PROBLEM --method exact --svg SCRATCH/missing/plan.svg",
     "--svg"},
    {"SolveBadFlagWithSvg",
     "solve PROBLEM --method exact --threads -1 --svg SCRATCH/plan.svg", "--threads"},
    {"SolveSvgUnknownExtension", "solve PROBLEM --method exact --svg SCRATCH/plan.gif", "--svg"},
    // route
    {"RouteSvgUnknownExtension", "route PROBLEM --svg SCRATCH/route.txt", "--svg"},
    // spinmap
    {"SpinmapOutMissing", "spinmap PROBLEM --speed 1 --aim 0", "--out"},
    {"SpinmapOutNotAPicture", "spinmap PROBLEM --speed 1 --aim 0 --out SCRATCH/map.txt", "--out"},
    {"SpinmapOutInMissingDirectory",
     "spinmap PROBLEM --speed 1 --aim 0 --out SCRATCH/missing/map.svg", "--out"},
    {"SpinmapAimWithoutSpeed", "spinmap PROBLEM --aim 0 --out SCRATCH/map.svg", "--speed"},
    {"SpinmapSpeedNaN", "spinmap PROBLEM --speed nan --aim 0 --out SCRATCH/map.svg", "--speed"},
    {"SpinmapGridTooSmall", "spinmap PROBLEM --speed 1 --aim 0 --grid 2 --out SCRATCH/map.png",
     "--grid"},
    {"SpinmapThreadsNegative",
     "spinmap PROBLEM --speed 1 --aim 0 --threads -1 --out SCRATCH/map.svg", "--threads"},
    {"SpinmapProblemMissing",
     "spinmap SCRATCH/missing.yaml --speed 1 --aim 0 --out SCRATCH/map.svg", "missing.yaml"},
    // figures
    {"FiguresOutMissing", "figures", "--out"},
    {"FiguresStepZero", "figures --out SCRATCH/figures --alpha-step 0", "--alpha-step"},
    {"FiguresStepNaN", "figures --out SCRATCH/figures --alpha-step nan", "--alpha-step"},
    {"FiguresOutIsAFile", "figures --out SCRATCH/not_a_directory", "--out"},
    {"FiguresUnknownFormat", "figures --out SCRATCH/figures --format jpg", "--format"},
};

INSTANTIATE_TEST_SUITE_P(EveryCommand, BadArguments, ::testing::ValuesIn(kBadCommandLines),
                         [](const ::testing::TestParamInfo<BadCommandLine>& case_info) {
                           return std::string(case_info.param.name);
                         });

// A drawing that cannot be written fails the run with exit 2 and leaves neither the file
// nor its temporary behind.
TEST(OutputFiles, UnwritableSvgLeavesNoFileAndNoTemporary) {
  const fs::path dir = scratch() / "read_only";
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  const ProcessResult run = cueplan(expanded("simulate PROBLEM --speed 1.002 --aim -60.36 "
                                             "--topspin-k 0.8 --svg '" +
                                             (dir / "path.svg").string() + "'"));
  fs::permissions(dir, fs::perms::owner_all);
  if (run.exit_code == 0) GTEST_SKIP() << "the directory stayed writable (running as root)";
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(lines_of(run.err).size(), 1u) << run.err;
  EXPECT_NE(run.err.find("--svg"), std::string::npos) << run.err;
  EXPECT_TRUE(fs::is_empty(dir));
}

// A run that succeeds replaces its output whole and leaves no temporary beside it.
TEST(OutputFiles, SuccessfulRunLeavesOnlyItsFile) {
  const fs::path dir = scratch() / "drawings";
  fs::create_directories(dir);
  const fs::path svg = dir / "path.svg";
  write_text(svg, "stale\n");
  const ProcessResult run = cueplan(expanded("simulate PROBLEM --speed 1.002 --aim -60.36 "
                                             "--topspin-k 0.8 --svg '" + svg.string() + "'"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(read_text(svg).starts_with("<svg") || read_text(svg).starts_with("<?xml"));
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"path.svg"});
}

// Validate mode (what the command-line fuzzer runs) checks a good command line and
// accepts it, but computes nothing and creates neither files nor directories.
TEST(ValidateMode, AcceptsAGoodCommandLineAndWritesNothing) {
  const fs::path dir = scratch() / "validate_only";
  fs::create_directories(dir);
  const std::string problem = problem_path("one_rail_position");
  const std::string picture = (dir / "map.svg").string();
  const std::string figures = (dir / "figures").string();
  const std::vector<std::vector<std::string>> command_lines = {
      {"spinmap", problem, "--speed", "1", "--aim", "0", "--out", picture},
      {"simulate", problem, "--speed", "1", "--aim", "0", "--svg", picture},
      {"figures", "--out", figures},
  };
  for (const std::vector<std::string>& args : command_lines) {
    std::vector<const char*> argv{"cueplan"};
    for (const std::string& arg : args) argv.push_back(arg.c_str());
    std::ostringstream out, err;
    EXPECT_EQ(cueplan::cli::run_cli(static_cast<int>(argv.size()), argv.data(), out, err,
                                    cueplan::cli::CliMode::validate),
              0)
        << args.front() << ": " << err.str();
    EXPECT_EQ(out.str(), "");
    EXPECT_EQ(err.str(), "");
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// The same bad command line gives the same line in validate mode as when run.
TEST(ValidateMode, ReportsTheSameLineAsARun) {
  const std::string problem = problem_path("one_rail_position");
  std::vector<const char*> argv{"cueplan", "simulate", problem.c_str(), "--speed", "nan",
                                "--aim", "0"};
  std::ostringstream out, err;
  EXPECT_EQ(cueplan::cli::run_cli(static_cast<int>(argv.size()), argv.data(), out, err,
                                  cueplan::cli::CliMode::validate),
            2);
  const ProcessResult run = cueplan("simulate '" + problem + "' --speed nan --aim 0");
  EXPECT_EQ(err.str(), run.err);
}

}  // namespace
}  // namespace cli_test
