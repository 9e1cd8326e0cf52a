// Tests of `cueplan solve --batch FILE.jsonl [--shard K/N]`, run as a user runs them:
// each line's answer is what `cueplan solve --json` gives for the same problem and seed,
// the seed follows the id and not the place, the shards' outputs interleave to the
// unsharded output, and a bad line gives its own error line while the rest go on. The
// exact impact method and small budgets keep it quick, and the evaluation budget (not
// the clock) ends every search, so answers are reproducible.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_solve_batch_test_";

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kBudget =
    "--method exact --max-evaluations 200 --samples 10 --alternatives 1 --max-time 120";
const std::string kQuick = std::string(kBudget) + " --seed 5";

// Twelve problems on the default snooker table, ids mixed strings and numbers.
std::vector<json> problems() {
  std::vector<json> list;
  for (int i = 0; i < 12; ++i) {
    json p = {{"cue_ball", {0.4 + 0.2 * i, 0.5 + 0.05 * i}},
              {"target", {3.0 - 0.15 * i, 1.2 - 0.04 * i}},
              {"limits", {{"cushions", i % 3}}}};
    p["id"] = i % 2 ? json("shot-" + std::to_string(i)) : json(i);
    list.push_back(p);
  }
  return list;
}

std::string lines_of_json(const std::vector<json>& list) {
  std::string text;
  for (const json& j : list) text += j.dump() + "\n";
  return text;
}

// The output's lines as JSON, without time_s (the wall clock's, never the same twice).
std::vector<json> answers(const ProcessResult& run) {
  std::vector<json> list;
  for (const std::string& line : lines_of(run.out)) {
    json j = json::parse(line);
    j.erase("time_s");
    list.push_back(j);
  }
  return list;
}

TEST(SolveBatch, EachLineIsSolveJsonOfItsProblemWithItsSeed) {
  const std::vector<json> list = problems();
  write_text(scratch() / "all.jsonl", lines_of_json(list));
  const ProcessResult run =
      cueplan("solve --batch '" + (scratch() / "all.jsonl").string() + "' " + kQuick, "batch");
  ASSERT_LE(run.exit_code, 1) << run.err;
  const std::vector<json> got = answers(run);
  ASSERT_EQ(got.size(), list.size());
  for (size_t i : {0u, 5u, 10u}) {
    EXPECT_EQ(got[i]["id"], list[i]["id"]);
    EXPECT_EQ(got[i]["line"], i + 1);
    // The same problem as a file, solved alone with the seed the batch reports.
    json problem = list[i];
    problem.erase("id");
    const fs::path file = scratch() / ("one_" + std::to_string(i) + ".yaml");
    write_text(file, problem.dump());
    const std::string seed = got[i]["options"]["seed"].dump();
    const ProcessResult one = cueplan("solve '" + file.string() + "' --json " + kBudget +
                                          " --seed " + seed + " --threads 1",
                                      "one" + std::to_string(i));
    ASSERT_LE(one.exit_code, 1) << one.err;
    json alone = json::parse(one.out);
    alone.erase("time_s");
    json batch = got[i];
    for (const char* key : {"id", "line", "problem"}) batch.erase(key);
    alone.erase("problem");  // its name and source are the file's
    EXPECT_EQ(batch, alone) << "problem " << i;
  }
}

TEST(SolveBatch, ShardsInterleaveToTheUnshardedOutput) {
  write_text(scratch() / "all.jsonl", lines_of_json(problems()) + "\n");  // a blank line too
  const std::string file = (scratch() / "all.jsonl").string();
  const std::vector<json> whole =
      answers(cueplan("solve --batch '" + file + "' --threads 2 " + kQuick, "whole"));
  ASSERT_EQ(whole.size(), 12u);
  std::vector<std::vector<json>> shards;
  std::vector<std::string> parts;
  for (int k = 0; k < 5; ++k) {
    const ProcessResult shard = cueplan("solve --batch '" + file + "' --shard " +
                                            std::to_string(k) + "/5 --threads 1 " + kQuick,
                                        "shard" + std::to_string(k));
    shards.push_back(answers(shard));
    parts.push_back((scratch() / ("part" + std::to_string(k) + ".jsonl")).string());
    write_text(parts.back(), shard.out);
  }
  std::vector<json> interleaved;
  for (size_t j = 0; j < 3; ++j)
    for (const std::vector<json>& shard : shards)
      if (j < shard.size()) interleaved.push_back(shard[j]);
  ASSERT_EQ(interleaved.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i)
    EXPECT_EQ(interleaved[i], whole[i]) << "line " << i + 1;  // deliberate: determinism
  EXPECT_EQ(shards[0].size(), 3u);  // problems 0, 5, 10
  EXPECT_EQ(shards[4].size(), 2u);  // problems 4, 9

  // `cueplan merge` puts the parts, given in any order, back into the input's order.
  const std::string shuffled =
      "'" + parts[3] + "' '" + parts[0] + "' '" + parts[4] + "' '" + parts[2] + "' '" + parts[1] + "'";
  const ProcessResult merged = cueplan("merge " + shuffled, "merge");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(merged.err, "cueplan merge: 12 lines from 5 parts\n");
  const std::vector<json> merged_answers = answers(merged);
  ASSERT_EQ(merged_answers.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i)
    EXPECT_EQ(merged_answers[i], whole[i]) << "line " << i + 1;  // deliberate: determinism
  // --out: the same lines in a file.
  const fs::path out = scratch() / "merged.jsonl";
  const ProcessResult to_file = cueplan("merge " + shuffled + " --out '" + out.string() + "'", "to_file");
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  EXPECT_EQ(to_file.out, "");
  EXPECT_EQ(read_text(out), merged.out);
}

TEST(SolveBatch, MergeRefusesWhatIsNotOneOutputPerShard) {
  const std::string a = (scratch() / "merge_a.jsonl").string();
  const std::string b = (scratch() / "merge_b.jsonl").string();
  write_text(a, "{\"id\": 0, \"line\": 1}\n{\"id\": 2, \"line\": 3}\n");
  write_text(b, "{\"id\": 1, \"line\": 2}\n\n{\"id\": 3, \"line\": 4}\n");
  const ProcessResult good = cueplan("merge '" + b + "' '" + a + "'", "good");
  ASSERT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(good.out,
            "{\"id\": 0, \"line\": 1}\n{\"id\": 1, \"line\": 2}\n{\"id\": 2, \"line\": 3}\n"
            "{\"id\": 3, \"line\": 4}\n");

  const ProcessResult twice = cueplan("merge '" + a + "' '" + b + "' '" + a + "'", "twice");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("given twice"), std::string::npos) << twice.err;

  const std::string backward = (scratch() / "merge_backward.jsonl").string();
  write_text(backward, "{\"id\": 2, \"line\": 3}\n{\"id\": 0, \"line\": 1}\n");
  const ProcessResult reversed = cueplan("merge '" + backward + "'", "reversed");
  EXPECT_EQ(reversed.exit_code, 2);
  EXPECT_NE(reversed.err.find(backward + ":2: line 1 comes after line 3"), std::string::npos)
      << reversed.err;

  const std::string bad = (scratch() / "merge_bad.jsonl").string();
  write_text(bad, "{\"id\": 0, \"line\": 1}\nrebound_speed,1.2\n");
  const ProcessResult not_json = cueplan("merge '" + bad + "'", "not_json");
  EXPECT_EQ(not_json.exit_code, 2);
  EXPECT_NE(not_json.err.find(bad + ":2: not a JSON object"), std::string::npos) << not_json.err;

  const ProcessResult missing = cueplan("merge /nonexistent/part0.jsonl", "missing");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("cannot open /nonexistent/part0.jsonl"), std::string::npos)
      << missing.err;
}

TEST(SolveBatch, SeedFollowsTheIdNotThePlace) {
  std::vector<json> list = problems();
  list.resize(4);
  write_text(scratch() / "forward.jsonl", lines_of_json(list));
  std::reverse(list.begin(), list.end());
  write_text(scratch() / "backward.jsonl", lines_of_json(list));
  std::vector<json> forward = answers(cueplan(
      "solve --batch '" + (scratch() / "forward.jsonl").string() + "' " + kQuick, "forward"));
  std::vector<json> backward = answers(cueplan(
      "solve --batch - " + kQuick + " < '" + (scratch() / "backward.jsonl").string() +
          "'",
      "backward"));
  ASSERT_EQ(forward.size(), 4u);
  ASSERT_EQ(backward.size(), 4u);
  std::reverse(backward.begin(), backward.end());
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(forward[i]["id"], backward[i]["id"]);
    EXPECT_EQ(forward[i]["options"]["seed"], backward[i]["options"]["seed"]);
    EXPECT_EQ(forward[i]["shot"], backward[i]["shot"]) << "id " << forward[i]["id"];
  }
  // Different ids, different seeds; none is the run's own.
  EXPECT_NE(forward[0]["options"]["seed"], forward[1]["options"]["seed"]);
  EXPECT_NE(forward[0]["options"]["seed"], 5);
}

TEST(SolveBatch, BadLinesGetErrorLinesAndTheRunGoesOn) {
  const std::string text =
      "{\"id\": \"a\", \"cue_ball\": [0.9, 1.2], \"target\": [2.2, 1.1]}\n"
      "not json\n"
      "{\"cue_ball\": [0.9, 1.2], \"target\": [2.2, 1.1]}\n"
      "{\"id\": 3, \"cue_ball\": [0.9, 1.2], \"target\": [2.2, 1.1], \"table\": {\"length\": -1}}\n"
      "{\"id\": [1], \"cue_ball\": [0.9, 1.2], \"target\": [2.2, 1.1]}\n"
      "[1, 2]\n"
      "{\"id\": \"f\", \"cue_ball\": [0.8, 1.0], \"target\": [2.0, 0.9]}\n";
  write_text(scratch() / "mixed.jsonl", text);
  const ProcessResult run =
      cueplan("solve --batch '" + (scratch() / "mixed.jsonl").string() + "' " + kQuick);
  EXPECT_EQ(run.exit_code, 1);
  const std::vector<json> got = answers(run);
  ASSERT_EQ(got.size(), 7u);
  const std::vector<std::string> statuses = {"", "parse_error", "invalid_input", "invalid_input",
                                             "invalid_input", "parse_error", ""};
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i]["line"], i + 1);
    if (statuses[i].empty()) {
      EXPECT_TRUE(got[i].contains("shot")) << got[i].dump();
      continue;
    }
    EXPECT_EQ(got[i]["status"], statuses[i]) << got[i].dump();
    EXPECT_EQ(got[i]["error"].get<std::string>().rfind("line " + std::to_string(i + 1) + ": ", 0),
              0u)
        << got[i].dump();
  }
  EXPECT_EQ(got[2]["field"], "id");
  EXPECT_EQ(got[3]["id"], 3);
  EXPECT_EQ(got[3]["field"], "table.length");
  EXPECT_NE(got[3]["error"].get<std::string>().find("table.length"), std::string::npos);
  EXPECT_EQ(got[4]["field"], "id");
  EXPECT_EQ(got[6]["id"], "f");
  EXPECT_NE(run.err.find("cueplan solve: 7 problems: "), std::string::npos) << run.err;
}

TEST(SolveBatch, BadShardAndMissingFileAreWholeCommandErrors) {
  for (const char* shard : {"3/3", "1", "-1/2", "a/b", "0/0"}) {
    const ProcessResult run = cueplan(std::string("solve --batch x.jsonl --shard ") + shard, "s");
    EXPECT_EQ(run.exit_code, 2) << shard;
    EXPECT_NE(run.err.find("--shard"), std::string::npos) << run.err;
  }
  const ProcessResult missing = cueplan("solve --batch /nonexistent/problems.jsonl", "missing");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("--batch"), std::string::npos) << missing.err;
  EXPECT_EQ(missing.out, "");
}

}  // namespace
}  // namespace cli_test
