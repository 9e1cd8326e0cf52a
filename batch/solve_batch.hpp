// `cueplan solve --batch FILE.jsonl [--shard K/N]`: many problems, one a line, solved on
// every core and written one JSON result a line, in input order, as they finish.
//
// Input:  one problem a line, its problem file's fields as a JSON object (JSON is YAML:
//         the same loader reads it), with an `id` (a string or a whole number) that
//         names it; blank lines are skipped. `-` reads standard input.
// Output: for each problem, the `solve --json` object (solve_json) on one line, led by
//         `id` and `line` (its line in the input). A line that is not a problem gives
//         {id (or null), line, status: parse_error | invalid_input, error, field} and
//         the run goes on.
// Seeds:  problem i is planned with a seed made from --seed and its id alone (a hash of
//         the two, reported as the result's options.seed), never from its place in the
//         file, so a problem gets the same answer in any shard.
// Shards: --shard K/N takes the problems (non-blank lines) whose 0-based index i has
//         i mod N = K. Shard K's j-th output line is problem j N + K's, so the shards'
//         outputs taken one line from each in turn (0, 1, ..., N-1, 0, ...) - or
//         concatenated and sorted by `line` - are the unsharded output, line for line:
//         exactly, apart from time_s, while the evaluation budget (not the clock) ends
//         each search.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own

// What a batch asks of the planner, whoever reads it (the command line converts its
// flags into one): the planner's and the impact method's options in the flags' units,
// and the problems solved at once.
struct SolveBatchRequest {
  api::PlannerArgs planner;
  api::ImpactArgs impact;  // --method, --accuracy, --table-cache
  int threads = 0;         // problems at once (and a table build's); 0: one per core
};

struct SolveBatchArgs {
  std::string batch_file;  // --batch FILE.jsonl; "-": standard input
  std::string shard;       // --shard K/N; empty: every problem
};

// Registers --batch and --shard on `solve` (writing into *args, which must outlive the
// parse); --batch excludes `problem` (the PROBLEM positional) and `svg` (--svg).
void add_solve_batch_flags(CLI::App& command, SolveBatchArgs* args, CLI::Option* problem,
                           CLI::Option* json, CLI::Option* svg);

// This shard: problems whose 0-based index i has i mod count = index.
struct Shard {
  uint64_t index = 0;
  uint64_t count = 1;
};

// Empty and *shard set when `text` is "K/N" with whole numbers 0 <= K < N; otherwise
// one line naming --shard.
std::string parse_shard(const std::string& text, Shard* shard);

// The seed of the problem with this id (its compact JSON text) in a run seeded `seed`.
uint64_t problem_seed(uint64_t seed, const std::string& id_json);

// Checks the flags and that the batch file opens (standard input is not read); returns
// kExitOk, or kExitUsage with its one line on `err`.
int validate_solve_batch(const SolveBatchArgs& batch, const SolveBatchRequest& args, bool accuracy_given,
                         std::ostream& err);

// Solves the batch (--threads problems at once, each plan on one thread) and writes its
// lines to `out`, a summary line on `err` at the end (progress there on a terminal).
// Returns an ExitCode: 0 when every problem was solved, 1 when any was not or a line was
// bad, 2 for bad flags or a file that cannot be opened.
int run_solve_batch(const SolveBatchArgs& batch, const SolveBatchRequest& args, bool accuracy_given,
                    std::ostream& out, std::ostream& err);

}  // namespace cueplan::batch
