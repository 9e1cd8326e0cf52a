// Inputs the problem-loader fuzzer (fuzz/problem_loader_fuzzer.cpp) found breaking the
// loader's contract, kept as tests: each must come back, promptly, as one line naming
// the source, the line and the field.
#include <gtest/gtest.h>

#include <string>

#include "cueplan/problems/problem.hpp"

namespace {

using cueplan::problems::LoadResult;
using cueplan::problems::parse_problem;

void expect_one_line_error(const LoadResult& result, const std::string& prefix) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error.find('\n'), std::string::npos) << result.error;
  EXPECT_EQ(result.error.find('\r'), std::string::npos) << result.error;
  EXPECT_EQ(result.error.rfind(prefix, 0), 0u) << "expected to start with " << prefix << ":\n"
                                               << result.error;
}

// yaml-cpp 0.7's LoadAll never returns on this text (a stray flow comma); the loader
// must not use it.
TEST(ProblemLoaderFuzzRegression, StrayCommaEndsInsteadOfLoopingForever) {
  const LoadResult result = parse_problem("\n,\n    ", "<fuzz>");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error.find('\n'), std::string::npos) << result.error;
}

TEST(ProblemLoaderFuzzRegression, FuzzedCommentsAndCommaEndInsteadOfLoopingForever) {
  const std::string text(
      "# T0003 m from target after 1 cushiona\n,nm: paper fation of figuParki"
      "?^\x03\x00``\x00\x00: a re 10 of Mn, ball that iJacs not\n# rokslo",
      122);
  const LoadResult result = parse_problem(text, "<fuzz>");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error.find('\n'), std::string::npos) << result.error;
}

// A control character after a backslash: yaml-cpp puts it, raw, into its message.
TEST(ProblemLoaderFuzzRegression, YamlErrorWithControlCharacterStaysOneLine) {
  expect_one_line_error(parse_problem("name: \"\\\x01\"\n", "<fuzz>"), "<fuzz>:1: yaml: ");
}

// A key that is not a plain word is named by its mapping, with the key quoted and its
// control characters escaped.
TEST(ProblemLoaderFuzzRegression, OddKeyIsNamedByItsMappingOnOneLine) {
  const LoadResult top = parse_problem(
      "cue_ball: [1, 0.5]\ntarget: [2, 0.5]\n\"width:, e.g.\\nspeed 0.9\": 1\n", "<fuzz>");
  expect_one_line_error(top, "<fuzz>:3: (document): has the key \"width:, e.g.\\nspeed 0.9\"");
  const LoadResult nested =
      parse_problem("table: {\"len gth\": 2}\ncue_ball: [1, 0.5]\ntarget: [2, 0.5]\n", "<fuzz>");
  expect_one_line_error(nested, "<fuzz>:1: table: has the key \"len gth\"");
}

// A plain word that is not a field keeps its own path and the suggestion.
TEST(ProblemLoaderFuzzRegression, MisspeltKeyStillNamesItself) {
  const LoadResult result =
      parse_problem("table: {lenght: 2}\ncue_ball: [1, 0.5]\ntarget: [2, 0.5]\n", "<fuzz>");
  expect_one_line_error(result, "<fuzz>:1: table.lenght: unknown key");
  EXPECT_NE(result.error.find("did you mean length?"), std::string::npos) << result.error;
}

// A quoted value holding a newline is shown escaped.
TEST(ProblemLoaderFuzzRegression, QuotedValueWithNewlineIsShownEscaped) {
  const LoadResult result = parse_problem(
      "table: {pockets: \"some\\nwhere\"}\ncue_ball: [1, 0.5]\ntarget: [2, 0.5]\n", "<fuzz>");
  expect_one_line_error(result, "<fuzz>:1: table.pockets: must be none, standard, snooker, pool, carom");
  EXPECT_NE(result.error.find("\"some\\nwhere\""), std::string::npos) << result.error;
}

}  // namespace
