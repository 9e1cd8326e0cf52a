#include "merge_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <queue>
#include <sstream>

#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/output_file.hpp"

namespace cueplan::cli {
namespace {

constexpr const char* kCommandName = "cueplan merge";

// One part being read: its next line and that line's `line`.
struct Part {
  std::string name;
  std::ifstream in;
  int file_line = 0;  // lines of the part read so far
  std::string text;   // the current line
  long long line = 0; // its `line` field
  long long previous = 0;
};

// Reads the part's next non-blank line; false at its end. *why on a bad line.
bool advance(Part& part, std::string* why) {
  while (std::getline(part.in, part.text)) {
    ++part.file_line;
    if (!part.text.empty() && part.text.back() == '\r') part.text.pop_back();
    if (part.text.find_first_not_of(" \t") == std::string::npos) continue;
    const std::string where = fmt::format("{}:{}: ", part.name, part.file_line);
    const nlohmann::json j = nlohmann::json::parse(part.text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      *why = where + "not a JSON object (merge takes the lines `solve --batch` writes)";
      return false;
    }
    const auto at = j.find("line");
    if (at == j.end() || !at->is_number_integer() || at->get<long long>() < 1) {
      *why = where + "line must be a whole number >= 1 (the problem's line in the input)";
      return false;
    }
    part.line = at->get<long long>();
    if (part.line <= part.previous) {
      *why = where +
             fmt::format("line {} comes after line {}: a part must be one shard's output, in "
                         "the order written",
                         part.line, part.previous);
      return false;
    }
    part.previous = part.line;
    return true;
  }
  if (part.in.bad()) *why = "error while reading " + part.name;
  return false;
}

}  // namespace

std::string merge_by_line(const std::vector<std::string>& parts, std::ostream& out,
                          size_t* count) {
  *count = 0;
  std::vector<std::unique_ptr<Part>> open;
  for (const std::string& name : parts) {
    auto part = std::make_unique<Part>();
    part->name = name;
    part->in.open(name);
    if (!part->in) return "cannot open " + name;
    open.push_back(std::move(part));
  }
  // The parts by their current line, smallest first.
  const auto later = [](const Part* a, const Part* b) { return a->line > b->line; };
  std::priority_queue<Part*, std::vector<Part*>, decltype(later)> heads(later);
  std::string why;
  for (const auto& part : open) {
    if (advance(*part, &why)) heads.push(part.get());
    if (!why.empty()) return why;
  }
  long long written = 0;
  std::string written_from;
  while (!heads.empty()) {
    Part* part = heads.top();
    heads.pop();
    if (part->line == written)
      return fmt::format("{}:{}: line {} is also in {}: a shard given twice?", part->name,
                         part->file_line, part->line, written_from);
    out << part->text << '\n';
    ++*count;
    written = part->line;
    written_from = part->name;
    if (advance(*part, &why)) heads.push(part);
    if (!why.empty()) return why;
    if (!out) return "cannot write the output";
  }
  return {};
}

MergeCommand::MergeCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "merge",
      "Merge the outputs of `solve --batch --shard K/N` (one file a shard) back into the "
      "input's order, by each line's `line`.");
  CLI::App& c = *command_;
  c.add_option("parts", args_.parts,
               "The shards' output files (JSON lines), in any order; give every shard's")
      ->type_name("PART")
      ->required();
  c.add_option("--out", args_.out_file,
               "Write the merged lines to this file (whole or not at all) instead of standard "
               "output")
      ->type_name("FILE");
  c.footer(
      "Shard K of N writes the problems whose index i has i mod N = K, each line led by its "
      "`line` in the input, in input order; merge interleaves the parts by `line`, reading "
      "one line of each at a time, so its output is the unsharded run's (apart from time_s). "
      "It stops at a line without a whole-number `line`, lines of a part out of order, or a "
      "line number in two parts.\n"
      "Exit codes: 0 merged, 2 a part that cannot be read or is not a shard's output.");
}

bool MergeCommand::selected() const { return command_->parsed(); }

std::string MergeCommand::check_flags() const {
  for (const std::string& part : args_.parts)
    if (!std::ifstream(part)) return "cannot open " + part;
  if (!args_.out_file.empty())
    if (std::string why = check_output_file(args_.out_file); !why.empty()) return "--out: " + why;
  return {};
}

int MergeCommand::validate(std::ostream& err) const {
  const std::string why = check_flags();
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int MergeCommand::run(std::ostream& out, std::ostream& err) const {
  if (std::string why = check_flags(); !why.empty()) return usage_error(err, kCommandName, why);
  size_t count = 0;
  if (args_.out_file.empty()) {
    const std::string why = merge_by_line(args_.parts, out, &count);
    out.flush();
    if (!why.empty()) return usage_error(err, kCommandName, why);
  } else {
    // Held whole so that the file appears complete or not at all.
    std::ostringstream merged;
    if (std::string why = merge_by_line(args_.parts, merged, &count); !why.empty())
      return usage_error(err, kCommandName, why);
    if (std::string why = write_file_atomically(args_.out_file, merged.str()); !why.empty()) {
      err << kCommandName << ": --out: " << why << '\n';
      return kExitFailed;
    }
  }
  err << fmt::format("{}: {} lines from {} parts\n", kCommandName, count, args_.parts.size());
  return kExitOk;
}

}  // namespace cueplan::cli
