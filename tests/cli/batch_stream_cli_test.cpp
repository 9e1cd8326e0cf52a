// The CSV batches (`rebound --batch`, `collide --batch`, `simulate --batch`) parse,
// compute and format on worker threads and write in input order: the output is the same
// bytes for 1, 2 and 3 threads, bad rows, blank lines and CRs included; and a reader of a
// pipe gets each row as it is resolved, not when the input ends.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/cli_test_support.hpp"

namespace cli_test {
const char* const kScratchName = "cueplan_batch_stream_test_";
}

namespace {

namespace fs = std::filesystem;
using cli_test::cueplan;
using cli_test::lines_of;
using cli_test::ProcessResult;
using cli_test::scratch;
using cli_test::write_text;

// A few thousand impacts with every kind of line a file may hold: good rows (some with
// spaces, a CR or quotes), bad numbers, short rows, rows outside the model, blank lines.
std::string mixed_impacts(int rows) {
  std::string text = "speed,angle_deg,topspin_k,sidespin_k\n";
  for (int i = 0; i < rows; ++i) {
    const double speed = 0.1 + 0.0007 * (i % 2900);
    const double angle = 1.0 + (i * 37 % 1780) * 0.1;
    const double top = -1.0 + (i % 41) * 0.05, side = 1.0 - (i % 23) * 0.09;
    switch (i % 97) {
      case 13: text += "1,fast,1,0\n"; break;
      case 29: text += "1,45,1\n"; break;
      case 41: text += "-1,45,0,0\n"; break;
      case 55: text += "\n  \n"; break;
      case 71: text += "\"1.5\",\"30\",0,0\r\n"; break;
      case 83: text += " 2 , 60 , 0.5 , -0.5 \n"; break;
      default:
        text += std::to_string(speed) + "," + std::to_string(angle) + "," + std::to_string(top) +
                "," + std::to_string(side) + "\n";
    }
  }
  return text;
}

TEST(BatchStream, ReboundIsTheSameBytesOnOneTwoAndThreeThreads) {
  const fs::path input = scratch() / "impacts.csv";
  write_text(input, mixed_impacts(4000));
  const ProcessResult one = cueplan("rebound --batch '" + input.string() + "' --threads 1", "1");
  const ProcessResult two = cueplan("rebound --batch '" + input.string() + "' --threads 2", "2");
  const ProcessResult three = cueplan("rebound --batch '" + input.string() + "' --threads 3", "3");
  EXPECT_EQ(one.exit_code, 1) << one.err;  // the bad rows fail
  const std::vector<std::string> lines = lines_of(one.out);
  ASSERT_EQ(lines.size(), 4001u - 41u);  // the header; 41 entries are blank lines
  EXPECT_NE(one.err.find("cueplan rebound: 3959 rows: "), std::string::npos) << one.err;
  EXPECT_EQ(one.out, two.out);  // deliberate exact comparisons: the bytes, not the numbers
  EXPECT_EQ(one.out, three.out);
  EXPECT_EQ(one.err, two.err);
  EXPECT_EQ(one.err, three.err);
  // Rows in input order: the 14th row of the file (i = 13) is a bad number, on line 15.
  EXPECT_NE(lines.at(14).find("line 15: angle_deg is not a number"), std::string::npos)
      << lines.at(14);
}

TEST(BatchStream, ReadFromAPipeInTinyPiecesGivesTheFileOutput) {
  // The reader hands over whatever whole lines have come; a line split across reads
  // must come out whole.
  const fs::path input = scratch() / "impacts_pipe.csv";
  write_text(input, mixed_impacts(600));
  const ProcessResult file =
      cueplan("rebound --batch '" + input.string() + "' --threads 2 --method paper", "file");
  // dd with a small block size writes the pipe in 7-byte pieces.
  const std::string command = "dd if='" + input.string() + "' bs=7 status=none | '" CUEPLAN_BINARY
                              "' rebound --batch - --threads 2 --method paper 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  pclose(pipe);
  EXPECT_EQ(out, file.out);
}

// Runs `command` and returns the seconds until its output's second line (the first row)
// came, and the whole output.
double seconds_to_first_row(const std::string& command, std::string* out) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return -1.0;
  double first_row = -1.0;
  int newlines = 0;
  for (int c; (c = fgetc(pipe)) != EOF;) {
    *out += static_cast<char>(c);
    if (c == '\n' && ++newlines == 2)
      first_row = std::chrono::duration<double>(Clock::now() - start).count();
  }
  pclose(pipe);
  return first_row;
}

TEST(BatchStream, APausedPipeGetsItsFirstRowBeforeTheInputEnds) {
  // The writer sends the header and one row, pauses 4 s, then sends one more row. The
  // first row must reach the reader during the pause, for one thread and for two.
  constexpr double kPause = 4.0;
  for (const char* threads : {"1", "2"}) {
    const std::string command =
        "{ printf 'speed,angle_deg,topspin_k,sidespin_k\\n1,45,1,0\\n'; sleep 4; "
        "printf '2,30,0,0\\n'; } | '" CUEPLAN_BINARY "' rebound --batch - --threads " +
        std::string(threads) + " 2>/dev/null";
    std::string out;
    const double first = seconds_to_first_row(command, &out);
    EXPECT_EQ(lines_of(out).size(), 3u) << out;
    EXPECT_GE(first, 0.0) << "no row came";
    EXPECT_LT(first, kPause - 1.5) << threads << " threads: the first row waited for the input";
  }
}

TEST(BatchStream, SolveBatchWritesEachAnswerBeforeTheInputEnds) {
  // One problem, a pause, one more: the first answer must come during the pause.
  constexpr double kPause = 4.0;
  const std::string command =
      "{ echo '{\"id\": 1, \"cue_ball\": [0.9, 1.2], \"target\": [2.2, 1.1]}'; sleep 4; "
      "echo '{\"id\": 2, \"cue_ball\": [0.8, 1.0], \"target\": [2.0, 0.9]}'; } | '" CUEPLAN_BINARY
      "' solve --batch - --threads 2 --method exact --max-evaluations 100 --samples 4 "
      "--alternatives 0 2>/dev/null";
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  double first = -1.0;
  for (int c; (c = fgetc(pipe)) != EOF;) {
    out += static_cast<char>(c);
    if (c == '\n' && first < 0.0)
      first = std::chrono::duration<double>(Clock::now() - start).count();
  }
  pclose(pipe);
  EXPECT_EQ(lines_of(out).size(), 2u) << out;
  EXPECT_GE(first, 0.0) << "no answer came";
  EXPECT_LT(first, kPause - 1.5) << "the first answer waited for the input";
}

TEST(BatchStream, SimulateAndCollideAreTheSameBytesOnOneAndThreeThreads) {
  std::string shots = "speed,aim_deg,topspin_k,sidespin_k\n";
  std::string cuts = "speed,cut_deg,topspin_k,sidespin_k\n";
  for (int i = 0; i < 300; ++i) {
    shots += std::to_string(0.3 + 0.01 * i) + "," + std::to_string(-170 + 1.13 * i) + "," +
             std::to_string(-0.5 + 0.003 * i) + ",0\n";
    cuts += std::to_string(0.2 + 0.01 * i) + "," + std::to_string(-85 + 0.56 * i) + "," +
            std::to_string(-1 + 0.006 * i) + "," + std::to_string(0.4 - 0.002 * i) + "\n";
    if (i % 50 == 7) shots += "1,x,0,0\n";
  }
  write_text(scratch() / "shots.csv", shots);
  write_text(scratch() / "cuts.csv", cuts);
  const std::string problem = std::string(CUEPLAN_PROBLEMS_DIR) + "/one_rail_position.yaml";
  const std::string simulate =
      "simulate '" + problem + "' --batch '" + (scratch() / "shots.csv").string() + "'";
  const ProcessResult s1 = cueplan(simulate + " --threads 1", "s1");
  const ProcessResult s3 = cueplan(simulate + " --threads 3", "s3");
  EXPECT_EQ(lines_of(s1.out).size(), 307u) << s1.err;
  EXPECT_EQ(s1.out, s3.out);  // deliberate: the bytes
  const std::string collide = "collide --batch '" + (scratch() / "cuts.csv").string() + "'";
  const ProcessResult c1 = cueplan(collide + " --threads 1", "c1");
  const ProcessResult c3 = cueplan(collide + " --threads 3", "c3");
  EXPECT_EQ(lines_of(c1.out).size(), 301u) << c1.err;
  EXPECT_EQ(c1.out, c3.out);  // deliberate: the bytes
}

}  // namespace
