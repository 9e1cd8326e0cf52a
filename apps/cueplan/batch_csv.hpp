// Batch files of the command line (`rebound --batch`, `simulate --batch`, `collide
// --batch`): an input CSV with a fixed header and one case per line, read a block of rows
// at a time, and the output CSV written back as each block is finished, one row per
// input row in input order. Memory stays that of one block, whatever the file's length.
#pragma once

#include <cstddef>
#include <fstream>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::cli {

// One line of the input file, as read.
struct BatchRow {
  int line = 0;                     // 1-based line number in the file
  std::vector<std::string> fields;  // the cells as written
};

// A batch file being read: `-` is standard input. The header is read when the reader
// is made; rows come in blocks after it.
class BatchReader {
 public:
  // Opens `path` and reads its first non-blank line, which must be `header` (its cells
  // compared with surrounding spaces removed). error() says why the file cannot be used.
  BatchReader(const std::string& path, std::string_view header);
  BatchReader(const BatchReader&) = delete;
  BatchReader& operator=(const BatchReader&) = delete;

  // Empty while the file can be used: it opened, its header is right and it reads.
  const std::string& error() const { return error_; }

  // Replaces *rows with the next rows, at most `count` (blank lines skipped, a trailing
  // CR dropped); an empty block means the end of the file (or a read error: error()).
  void read(size_t count, std::vector<BatchRow>* rows);

 private:
  std::string name_;  // the path, or "standard input"
  std::ifstream file_;
  std::istream* in_ = nullptr;
  int line_number_ = 0;
  std::string error_;
};

// The text without surrounding spaces, tabs and CRs.
std::string trimmed(const std::string& text);

// What one row came to: its status, message, and result cells (all empty on failure).
struct BatchOutcome {
  std::string status;
  std::string message;
  std::vector<std::string> results;
  // Cells written after the message: columns added later, so the earlier ones keep their
  // places.
  std::vector<std::string> after_message = {};
};

// How one batch is run: the caller's computation of a block and the output's shape.
struct BatchJob {
  const char* command = "";  // "cueplan rebound": leads the progress and summary lines
  std::string header;        // the output's header line, without its newline
  size_t input_columns = 0;  // input cells copied to the front of each output row
  size_t block_rows = 4096;  // rows read, computed and written at a time
  // Fills outcomes[i] for rows[i]; may use threads, but must finish them all.
  std::function<void(std::span<const BatchRow> rows, std::span<BatchOutcome> outcomes)> compute;
  // Whether a row with this status failed (it sets the exit code).
  std::function<bool(const std::string& status)> failed;
};

// What a batch came to.
struct BatchSummary {
  size_t rows = 0;
  std::map<std::string, size_t> by_status;  // rows of each status
  size_t failed = 0;                        // rows whose status the job calls failed
  std::string error;                        // the input or output broke off: why
};

// Reads the rest of `reader` a block at a time, computes each block and writes its rows
// to `out` before reading the next: the header line first, then for each row its first
// `input_columns` cells (trimmed, empty where the row is short), the outcome's results,
// its status, its message (always quoted: it is free text) and its after_message
// cells. When `progress` is given (a terminal), a line there counts the rows done and is
// rewritten as they go. Returns the counts; summary_line() words them.
BatchSummary run_batch(BatchReader& reader, const BatchJob& job, std::ostream& out,
                       std::ostream* progress);

// "cueplan rebound: 7 rows: 2 invalid_input, 3 ok, 2 parse_error; 4 failed" (statuses
// in alphabetical order); `unit` names what was counted.
std::string summary_line(const char* command, const BatchSummary& summary,
                         const char* unit = "row");

// Runs a batch as the commands do: progress on `err` when it is the process's stderr
// and a terminal, the summary line on `err` at the end. Returns an ExitCode: kExitOk
// when every row succeeded, kExitFailed when any failed or the input or output broke
// off (its line on `err`).
int run_batch_command(BatchReader& reader, const BatchJob& job, std::ostream& out,
                      std::ostream& err);

}  // namespace cueplan::cli
