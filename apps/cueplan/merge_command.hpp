// `cueplan merge PART...`: the outputs of `solve --batch --shard K/N`, one file a shard,
// merged back into the input's order. Each output line names its problem's `line` in the
// input and each shard writes its problems in input order, so the parts merge like sorted
// runs, one line of each held at a time: memory does not grow with the files.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace cueplan::cli {

struct MergeArgs {
  std::vector<std::string> parts;  // the shards' output files, in any order
  std::string out_file;            // --out; empty: standard output
};

class MergeCommand {
 public:
  // Registers `merge` and its flags on `parent`; the flags write into this object.
  explicit MergeCommand(CLI::App& parent);
  MergeCommand(const MergeCommand&) = delete;
  MergeCommand& operator=(const MergeCommand&) = delete;

  bool selected() const;
  // Checks that every part opens and that --out can be written; returns kExitOk, or
  // kExitUsage with its one line on `err`.
  int validate(std::ostream& err) const;
  // Writes the merged lines (to --out, atomically, or to `out`); returns an ExitCode:
  // 0 done, 2 a part that cannot be read, a line without a whole-number `line`, lines of
  // one part out of order, or a line number in two parts (a shard given twice).
  int run(std::ostream& out, std::ostream& err) const;

 private:
  std::string check_flags() const;

  CLI::App* command_ = nullptr;
  MergeArgs args_;
};

// Merges the parts' lines by their `line` field into `out`; empty, or one line saying
// which part and line is wrong. Blank lines are skipped. *count gets the lines written.
std::string merge_by_line(const std::vector<std::string>& parts, std::ostream& out,
                          size_t* count);

}  // namespace cueplan::cli
