#include "solve_batch.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <thread>
#include <vector>

#include "batch_csv.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/parallel.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/results.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

constexpr const char* kCommandName = "cueplan solve";
constexpr size_t kDeepestLine = 16;  // nesting of brackets a problem line may have

// SplitMix64's finaliser: every bit of the input moves every bit of the output.
uint64_t mixed(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The deepest nesting of brackets outside strings, read without recursion.
size_t nesting_of(const std::string& text) {
  size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
    if ((c == ']' || c == '}') && depth > 0) --depth;
  }
  return deepest;
}

// What the flags ask for, read and checked.
struct BatchSettings {
  plan::PlannerOptions options;  // one thread each; seed: the run's
  Shard shard;
  std::string table_cache;
  int threads = 0;  // problems at once; also a table build's
  bool accuracy_given = false;
};

std::string read_settings(const SolveBatchArgs& batch, const SolveBatchRequest& args, bool accuracy_given,
                          BatchSettings* s) {
  phys::SimulationOptions simulation;
  if (std::string why = read_impact_options(args.impact, &simulation); !why.empty()) return why;
  // Each plan on one thread: the batch's parallelism is its problems. The answer does not
  // depend on it (planner.hpp) while the evaluation budget ends the search.
  if (std::string why = read_planner_options(args.planner, 1, simulation, &s->options);
      !why.empty())
    return why;
  if (args.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args.threads);
  if (!batch.shard.empty())
    if (std::string why = parse_shard(batch.shard, &s->shard); !why.empty()) return why;
  s->table_cache = args.impact.table_cache;
  s->threads = args.threads;
  s->accuracy_given = accuracy_given;
  return {};
}

// The impact tables of the batch's cushions, each loaded (or built) once, when a problem
// first needs it.
class TablesByCushion {
 public:
  // The table for the scene's cushion, or null (and *why) when it cannot be had.
  const phys::ImpactTable* find(const phys::Scene& scene, const BatchSettings& s,
                                std::mutex& err_mutex, std::ostream& err, std::string* why) {
    const std::string key =
        phys::ImpactTable::cache_file_name(scene.ball_and_cushion, {});
    std::lock_guard lock(mutex_);
    const char* failed = "the impact table for this problem's cushion could not be had (see stderr)";
    if (auto it = tables_.find(key); it != tables_.end()) {
      if (!it->second) *why = failed;  // tried once, for the first problem that needed it
      return it->second.get();
    }
    auto table = std::make_unique<phys::ImpactTable>();
    phys::SimulationOptions ignored = s.options.simulation;
    // Its notes (a first build's, said before it starts) go to stderr as they come.
    std::lock_guard err_lock(err_mutex);
    const int code = prepare_impact_table(kCommandName, scene, s.table_cache, s.threads,
                                          s.accuracy_given, table.get(), &ignored, err);
    if (code != kExitOk) {
      *why = failed;
      tables_[key] = nullptr;
      return nullptr;
    }
    return (tables_[key] = std::move(table)).get();
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<phys::ImpactTable>> tables_;
};

// One output line and its status.
struct Answer {
  std::string text;
  std::string status;
};

Answer error_line(const ordered_json& id, int line, const char* status, const std::string& message,
                  const std::string& field) {
  ordered_json j = {{"id", id},
                    {"line", line},
                    {"status", status},
                    {"error", fmt::format("line {}: {}", line, message)},
                    {"field", field.empty() ? ordered_json() : ordered_json(field)}};
  return {j.dump(-1, ' ', false, ordered_json::error_handler_t::replace), status};
}

// The loader's "SOURCE:LINE: FIELD: message" as "FIELD: message".
std::string without_location(const prob::LoadResult& r, const std::string& source) {
  std::string text = r.error;
  const std::string located = source + ":" + std::to_string(r.line) + ": ";
  if (text.rfind(located, 0) == 0) text.erase(0, located.size());
  return text;
}

// Solves the problem on one line of the input.
Answer solve_line(int line, const std::string& text, const std::string& file_name,
                  const BatchSettings& s, TablesByCushion& tables, std::mutex& err_mutex,
                  std::ostream& err) {
  if (nesting_of(text) > kDeepestLine)
    return error_line(nullptr, line, "parse_error",
                      fmt::format("nests deeper than any problem ({} levels)", kDeepestLine), "");
  ordered_json value;
  try {
    value = ordered_json::parse(text);
  } catch (const ordered_json::parse_error& e) {
    std::string what = e.what();
    if (const size_t tag = what.find("] "); tag != std::string::npos) what.erase(0, tag + 2);
    return error_line(nullptr, line, "parse_error", "not JSON: " + what, "");
  }
  if (!value.is_object())
    return error_line(nullptr, line, "parse_error",
                      "must be a JSON object of the problem file's fields with an id, such as "
                      "{\"id\": 1, \"cue_ball\": [0.8, 0.5], \"target\": [2.6, 1.2]}",
                      "");
  const auto id_at = value.find("id");
  if (id_at == value.end())
    return error_line(nullptr, line, "invalid_input",
                      "id is required: a string or a whole number naming the problem", "id");
  const ordered_json id = *id_at;
  if (!id.is_string() && !id.is_number_integer())
    return error_line(nullptr, line, "invalid_input",
                      "id must be a string or a whole number, got " + id.dump(), "id");
  value.erase("id");

  const std::string source = fmt::format("{}:{}", file_name, line);
  const prob::LoadResult loaded = prob::parse_problem(value.dump(), source);
  if (!loaded.ok()) {
    const bool whole = loaded.field.empty() || loaded.field == "(document)" || loaded.field == "yaml";
    return error_line(id, line, "invalid_input", without_location(loaded, source),
                      whole ? "" : loaded.field);
  }
  const prob::Problem& problem = *loaded.problem;

  plan::PlannerOptions options = s.options;
  options.seed = problem_seed(s.options.seed, id.dump());
  if (options.simulation.impact_method == phys::ImpactMethod::table) {
    std::string why;
    const phys::ImpactTable* table = tables.find(problem.scene, s, err_mutex, err, &why);
    if (!table) return error_line(id, line, "impact_table_failed", why, "");
    use_impact_table(*table, problem.scene, s.accuracy_given, &options.simulation);
  }
  const plan::PlanResult result = plan::plan(problem, options);
  if (result.status == plan::PlanStatus::invalid_input)
    return error_line(id, line, "invalid_input", result.message, "");

  ordered_json j = {{"id", id}, {"line", line}};
  ordered_json solved = solve_json(problem, options, result, "");
  for (auto& [key, v] : solved.items()) j[key] = std::move(v);
  return {j.dump(-1, ' ', false, ordered_json::error_handler_t::replace),
          plan::to_string(result.status)};
}

// A problem read and waiting for its answer.
struct Pending {
  int line = 0;
  std::string text;
  std::optional<Answer> answer;
};

// Reads the problems of this shard, solves them from `threads` threads and writes their
// lines in input order: at most `window` problems are held at once, so memory does not
// grow with the file, and a slow problem holds back only the writing, not the solving.
BatchSummary solve_all(std::istream& in, const std::string& file_name, const BatchSettings& s,
                       std::ostream& out, std::ostream& err, bool show_progress,
                       bool flush_each_line) {
  using Clock = std::chrono::steady_clock;
  const unsigned threads = phys::thread_count(s.threads);
  const size_t window = 4 * static_cast<size_t>(threads) + 4;
  TablesByCushion tables;
  std::mutex err_mutex;

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Pending> pending;  // references stay valid across push_back and pop_front
  size_t first = 0;             // the index of pending.front() among the problems taken
  size_t next = 0;              // the next problem to start
  bool read_all = false;

  bool writing = false;          // a worker is writing finished lines

  BatchSummary summary;
  Clock::time_point shown{};
  // Writes the finished lines at the front, in order; called by one worker at a time
  // (`writing`), with the lock held, which it lets go while it writes.
  const auto write_finished = [&](std::unique_lock<std::mutex>& lock) {
    while (!pending.empty() && pending.front().answer) {
      Answer answer = std::move(*pending.front().answer);
      pending.pop_front();
      ++first;
      changed.notify_all();  // room for the reader
      lock.unlock();
      out << answer.text << '\n';
      if (flush_each_line) out.flush();  // a pipe or terminal: its reader sees it now
      ++summary.rows;
      ++summary.by_status[answer.status];
      if (answer.status != plan::to_string(plan::PlanStatus::solved)) ++summary.failed;
      if (show_progress && Clock::now() - shown > std::chrono::milliseconds(250)) {
        shown = Clock::now();
        std::lock_guard err_lock(err_mutex);
        err << '\r' << kCommandName << ": " << summary.rows << " problems done" << std::flush;
      }
      lock.lock();
    }
  };

  // Each worker solves the next problem read; the one that answers the oldest unwritten
  // problem writes it and every answered one after it (an ordered hand-off), so lines
  // come out as soon as they can, even while the reader waits for more input.
  const auto work = [&] {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return next < first + pending.size() || read_all; });
      if (next >= first + pending.size()) return;  // everything read and started
      Pending& p = pending[next++ - first];
      lock.unlock();
      Answer answer;
      try {
        answer = solve_line(p.line, p.text, file_name, s, tables, err_mutex, err);
      } catch (const std::exception& e) {  // out of memory: this problem fails, not the run
        answer = error_line(nullptr, p.line, "failed", e.what(), "");
      }
      lock.lock();
      p.answer = std::move(answer);
      if (!writing) {
        writing = true;
        write_finished(lock);
        writing = false;
      }
      changed.notify_all();
    }
  };
  std::vector<std::jthread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);

  // Reads the next problem of this shard (blank lines skipped); nothing at the end.
  std::string line;
  int line_number = 0;
  uint64_t index = 0;  // among the non-blank lines
  const auto read_problem = [&]() -> std::optional<Pending> {
    while (std::getline(in, line)) {
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (trimmed(line).empty()) continue;
      if (index++ % s.shard.count != s.shard.index) continue;
      return Pending{line_number, std::move(line), std::nullopt};
    }
    return std::nullopt;
  };

  {
    std::unique_lock lock(mutex);
    while (!read_all) {
      changed.wait(lock, [&] { return pending.size() < window; });
      lock.unlock();
      std::optional<Pending> p = read_problem();
      lock.lock();
      if (p)
        pending.push_back(std::move(*p));
      else
        read_all = true;
      changed.notify_all();
    }
    changed.wait(lock, [&] { return pending.empty() && !writing; });
  }
  if (in.bad()) summary.error = "--batch: error while reading " + file_name;
  pool.clear();  // joins
  out.flush();
  if (!out) summary.error = "cannot write the output";
  if (show_progress && shown != Clock::time_point{}) err << "\r\033[K" << std::flush;
  return summary;
}

}  // namespace

void add_solve_batch_flags(CLI::App& command, SolveBatchArgs* args, CLI::Option* problem,
                           CLI::Option* json, CLI::Option* svg) {
  const char* group = "Batch";
  CLI::Option* batch =
      command
          .add_option("--batch", args->batch_file,
                      "Solve every problem of a JSON-lines file instead of PROBLEM: one problem "
                      "a line, the problem file's fields as a JSON object with an `id` (string "
                      "or whole number); '-' reads standard input. Writes one JSON line a "
                      "problem, in input order as they finish: the --json object led by id and "
                      "line; a bad line gives {id, line, status, error, field} and the rest go "
                      "on. --threads problems at once, each plan on one thread; each problem's "
                      "seed is a hash of --seed and its id. Exit 0 when all were solved, 1 "
                      "otherwise")
          ->type_name("FILE.jsonl")
          ->group(group);
  command
      .add_option("--shard", args->shard,
                  "With --batch: solve only the problems (non-blank lines) whose 0-based index "
                  "i has i mod N = K, for job arrays. Shard K's j-th line is problem j N + K's: "
                  "the shards' lines taken one from each in turn (or sorted by `line`) are the "
                  "unsharded output, apart from time_s, while the evaluation budget ends each "
                  "search")
      ->type_name("K/N")
      ->needs(batch)
      ->group(group);
  batch->excludes(problem);
  batch->excludes(json);
  batch->excludes(svg);
}

std::string parse_shard(const std::string& text, Shard* shard) {
  const size_t slash = text.find('/');
  const auto whole = [](std::string_view s, uint64_t* value) {
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), *value);
    return !s.empty() && error == std::errc() && end == s.data() + s.size();
  };
  uint64_t k = 0, n = 0;
  if (slash == std::string::npos || !whole(std::string_view(text).substr(0, slash), &k) ||
      !whole(std::string_view(text).substr(slash + 1), &n) || n == 0 || k >= n)
    return "--shard must be K/N with whole numbers 0 <= K < N (shard K of N, from 0), got '" +
           text + "'";
  *shard = {k, n};
  return {};
}

uint64_t problem_seed(uint64_t seed, const std::string& id_json) {
  // FNV-1a over the id's text, then mixed with the run's seed.
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : id_json) h = (h ^ c) * 0x100000001b3ULL;
  return mixed(mixed(seed) ^ h);
}

int validate_solve_batch(const SolveBatchArgs& batch, const SolveBatchRequest& args, bool accuracy_given,
                         std::ostream& err) {
  BatchSettings settings;
  if (std::string why = read_settings(batch, args, accuracy_given, &settings); !why.empty())
    return usage_error(err, kCommandName, why);
  if (batch.batch_file != "-" && !std::ifstream(batch.batch_file))
    return usage_error(err, kCommandName, "--batch: cannot open " + batch.batch_file);
  return kExitOk;
}

int run_solve_batch(const SolveBatchArgs& batch, const SolveBatchRequest& args, bool accuracy_given,
                    std::ostream& out, std::ostream& err) {
  BatchSettings settings;
  if (std::string why = read_settings(batch, args, accuracy_given, &settings); !why.empty())
    return usage_error(err, kCommandName, why);
  std::ifstream file;
  std::istream* in = &std::cin;
  std::string name = "stdin";
  if (batch.batch_file != "-") {
    file.open(batch.batch_file);
    if (!file) return usage_error(err, kCommandName, "--batch: cannot open " + batch.batch_file);
    in = &file;
    name = batch.batch_file;
  }
  const bool terminal = err.rdbuf() == std::cerr.rdbuf() && isatty(STDERR_FILENO) == 1;
  const bool interactive = out.rdbuf() == std::cout.rdbuf() && stdout_is_interactive();
  const BatchSummary summary = solve_all(*in, name, settings, out, err, terminal, interactive);
  if (!summary.error.empty()) err << kCommandName << ": " << summary.error << '\n';
  err << summary_line(kCommandName, summary, "problem") << '\n';
  return summary.error.empty() && summary.failed == 0 ? kExitOk : kExitFailed;
}

}  // namespace cueplan::batch
