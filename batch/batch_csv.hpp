// Batch files of the command line (`rebound --batch`, `simulate --batch`, `collide
// --batch`): an input CSV with a fixed header and one case per line, and the output CSV,
// one row per input row in input order. The main thread only reads the file's bytes and
// cuts them into chunks of whole lines; worker threads parse, compute and format each
// chunk, and whichever finishes the oldest chunk writes it and every finished chunk after
// it (an ordered hand-off: no lock is held while computing or writing). At most a few
// chunks per thread are held, so memory stays that of a few chunks whatever the file's
// length, and the output is the same bytes for any thread count.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::batch {

// One line of the input file, as read.
struct BatchRow {
  int line = 0;                     // 1-based line number in the file
  std::vector<std::string> fields;  // the cells as written
};

// Whole lines of the input, as read: `text` holds them; each row is a line's place in
// it (a trailing CR dropped, blank lines left out) and its line number.
struct BatchChunk {
  struct Line {
    int number = 0;
    size_t begin = 0;
    size_t size = 0;
  };
  std::string text;
  std::vector<Line> lines;
};

// A batch file being read: `-` is standard input. The header is read when the reader
// is made; rows come in chunks after it.
class BatchReader {
 public:
  // Opens `path` and reads its first non-blank line, which must be `header` (its cells
  // compared with surrounding spaces removed). error() says why the file cannot be used.
  BatchReader(const std::string& path, std::string_view header);
  ~BatchReader();
  BatchReader(const BatchReader&) = delete;
  BatchReader& operator=(const BatchReader&) = delete;

  // Empty while the file can be used: it opened, its header is right and it reads.
  const std::string& error() const { return error_; }

  // Replaces *chunk with the next lines: at most `max_rows` non-blank ones, and fewer
  // when no more can be read without waiting (a pipe or terminal that pauses), so that
  // what has come is not held back. Waits only while it has no line at all. False at the
  // end of the file (or on a read error: error()).
  bool read_chunk(size_t max_rows, BatchChunk* chunk);

 private:
  // Reads more bytes onto the end of `text`; false at the end of the file or an error.
  bool fill(std::string& text);

  std::string name_;  // the path, or "standard input"
  int fd_ = -1;
  bool own_fd_ = false;
  bool end_ = false;      // no more bytes: the end of the file, or a read error
  std::string pending_;   // bytes read past the last line handed out
  int line_number_ = 0;   // lines handed out (or skipped) so far
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

// How one batch is run: the caller's computation of a chunk and the output's shape.
struct BatchJob {
  const char* command = "";  // "cueplan rebound": leads the progress and summary lines
  std::string header;        // the output's header line, without its newline
  size_t input_columns = 0;  // input cells copied to the front of each output row
  size_t block_rows = 1024;  // most rows in one chunk (one piece of work)
  int threads = 0;           // worker threads (0: one per core; 1: all on the calling thread)
  // Fills outcomes[i] for rows[i] on the calling thread; called for several chunks at
  // once from different threads.
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

// Where the time of a batch went: the CPU seconds of reading on the main thread, of
// writing (in input order, one writer at a time) and of the workers' parsing, computing
// and formatting (summed over them), and the wall-clock seconds of the whole. CPU time
// does not count the waits for a core on a loaded machine, so the shares hold there too.
struct BatchTimes {
  double read = 0.0;
  double write = 0.0;
  double work = 0.0;  // summed over the workers
  double wall = 0.0;
};

// How the output is written.
struct BatchOutput {
  // Flush after every chunk written (a pipe or terminal: its reader sees each row as it
  // is resolved); otherwise the stream's buffer decides.
  bool flush_each_chunk = false;
  std::ostream* progress = nullptr;  // a terminal: a line counting the rows done
  BatchTimes* times = nullptr;       // when given, filled in
};

// Reads the rest of `reader` in chunks, computes them from job.threads threads and
// writes their rows to `out` in input order: the header line first, then for each row
// its first `input_columns` cells (trimmed, empty where the row is short), the outcome's
// results, its status, its message (always quoted: it is free text) and its
// after_message cells. Returns the counts; summary_line() words them.
BatchSummary run_batch(BatchReader& reader, const BatchJob& job, std::ostream& out,
                       const BatchOutput& how = {});

// Whether the standard output is a pipe, socket or terminal (someone may be reading
// it as it comes), not a file.
bool stdout_is_interactive();

// "cueplan rebound: 7 rows: 2 invalid_input, 3 ok, 2 parse_error; 4 failed" (statuses
// in alphabetical order); `unit` names what was counted.
std::string summary_line(const char* command, const BatchSummary& summary,
                         const char* unit = "row");

// Runs a batch as the commands do: progress on `err` when it is the process's stderr
// and a terminal, a flush after each chunk when `out` is the standard output and that
// is a pipe or terminal, the summary line on `err` at the end. With the environment
// variable CUEPLAN_BATCH_TIMES set (to anything), a line on `err` also says where the
// time went (BatchTimes). Returns an ExitCode: kExitOk
// when every row succeeded, kExitFailed when any failed or the input or output broke
// off (its line on `err`).
int run_batch_command(BatchReader& reader, const BatchJob& job, std::ostream& out,
                      std::ostream& err);

}  // namespace cueplan::batch
