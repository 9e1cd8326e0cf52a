#include "batch_csv.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <iostream>
#include <mutex>
#include <ostream>
#include <thread>

#include "cueplan/parallel.hpp"
#include "csv.hpp"
#include "cueplan/api/exit_codes.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

namespace {

constexpr size_t kReadBytes = size_t{1} << 16;

bool blank(std::string_view line) {
  return line.find_first_not_of(" \t\r") == std::string_view::npos;
}

}  // namespace

BatchReader::BatchReader(const std::string& path, std::string_view header) {
  if (path == "-") {
    name_ = "standard input";
    fd_ = STDIN_FILENO;
  } else {
    name_ = path;
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) {
      error_ = "--batch: cannot open " + path;
      return;
    }
    own_fd_ = true;
  }
  // The header: the first non-blank line.
  std::string text;
  size_t start = 0;
  for (;;) {
    const size_t newline = text.find('\n', start);
    if (newline == std::string::npos) {
      if (!end_) {
        fill(text);
        continue;
      }
      if (start == text.size()) break;  // the file ended
    }
    const size_t stop = newline == std::string::npos ? text.size() : newline;
    std::string line = text.substr(start, stop - start);
    start = newline == std::string::npos ? text.size() : newline + 1;
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (blank(line)) continue;
    std::string got;
    for (const std::string& field : split_csv_line(line)) {
      if (!got.empty()) got += ',';
      got += trimmed(field);
    }
    if (got != header)
      error_ = "--batch: " + name_ + " must start with the header '" + std::string(header) +
               "', got '" + line + "'";
    pending_ = text.substr(start);
    return;
  }
  if (error_.empty())
    error_ = "--batch: " + name_ + " is empty; it needs the header '" + std::string(header) + "'";
}

BatchReader::~BatchReader() {
  if (own_fd_) ::close(fd_);
}

bool BatchReader::fill(std::string& text) {
  if (end_) return false;
  const size_t had = text.size();
  text.resize(had + kReadBytes);
  for (;;) {
    const ssize_t n = ::read(fd_, text.data() + had, kReadBytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      text.resize(had);
      end_ = true;
      if (n < 0) error_ = "--batch: error while reading " + name_ + ": " + std::strerror(errno);
      return false;
    }
    text.resize(had + static_cast<size_t>(n));
    return true;
  }
}

bool BatchReader::read_chunk(size_t max_rows, BatchChunk* chunk) {
  chunk->text.clear();
  chunk->lines.clear();
  if (!error_.empty() && chunk->lines.empty() && pending_.empty()) return false;
  std::string& text = chunk->text;
  text.swap(pending_);
  size_t start = 0;  // the first byte not yet cut into a line
  for (;;) {
    // Whole lines of what has been read.
    while (chunk->lines.size() < max_rows) {
      const size_t newline = text.find('\n', start);
      if (newline == std::string::npos) break;
      ++line_number_;
      size_t size = newline - start;
      if (size > 0 && text[start + size - 1] == '\r') --size;
      if (!blank(std::string_view(text).substr(start, size)))
        chunk->lines.push_back({line_number_, start, size});
      start = newline + 1;
    }
    if (chunk->lines.size() >= max_rows) break;
    if (end_) {
      // A last line without its newline.
      if (start < text.size()) {
        ++line_number_;
        size_t size = text.size() - start;
        if (text.back() == '\r') --size;
        if (!blank(std::string_view(text).substr(start, size)))
          chunk->lines.push_back({line_number_, start, size});
        start = text.size();
      }
      break;
    }
    // Hand over what has come rather than wait for more.
    if (!chunk->lines.empty()) {
      pollfd ready{fd_, POLLIN, 0};
      if (::poll(&ready, 1, 0) == 0) break;
    }
    fill(text);
  }
  pending_.assign(text, start, std::string::npos);
  text.resize(start);
  return !chunk->lines.empty();
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU seconds this thread has run (user and system): unlike the wall clock, it does not
// count the time a loaded machine keeps the thread waiting for a core.
double thread_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A chunk's output rows and how many of each status they had.
struct ChunkResult {
  std::string text;
  std::map<std::string, size_t> by_status;
  size_t rows = 0;
};

void append_row(const BatchRow& row, size_t input_columns, const BatchOutcome& outcome,
                std::string& out) {
  // As csv_line of the input cells, results and status, then the quoted message and the
  // cells after it.
  bool first = true;
  const auto cell = [&](std::string_view text) {
    if (!first) out += ',';
    first = false;
    if (text.find_first_of(",\"\r\n") == std::string_view::npos)
      out += text;
    else
      out += csv_quoted(text);
  };
  for (size_t c = 0; c < input_columns; ++c)
    cell(c < row.fields.size() ? trimmed(row.fields[c]) : std::string());
  for (const std::string& result : outcome.results) cell(result);
  cell(outcome.status);
  out += ',';
  out += csv_quoted(outcome.message);
  for (const std::string& after : outcome.after_message) {
    out += ',';
    out += csv_field(after);
  }
  out += '\n';
}

// A worker's rows and outcomes, kept from chunk to chunk so that their memory is reused:
// a chunk's worth allocated and freed each time makes the allocator hand memory back to
// the system and fault it in again, which cost a second thread most of its gain.
struct ChunkScratch {
  std::vector<BatchRow> rows;
  std::vector<BatchOutcome> outcomes;
};

// Parses, computes and formats one chunk (on the calling thread), into result->text
// (whose memory is reused).
void process_chunk(const BatchChunk& chunk, const BatchJob& job, ChunkScratch& scratch,
                   ChunkResult* result) {
  std::vector<BatchRow>& rows = scratch.rows;
  rows.resize(chunk.lines.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const BatchChunk::Line& line = chunk.lines[i];
    rows[i].line = line.number;
    rows[i].fields = split_csv_line(std::string_view(chunk.text).substr(line.begin, line.size));
  }
  std::vector<BatchOutcome>& outcomes = scratch.outcomes;
  outcomes.resize(rows.size());
  for (BatchOutcome& outcome : outcomes) {
    outcome.status.clear();
    outcome.message.clear();
    outcome.results.clear();
    outcome.after_message.clear();
  }
  job.compute(rows, outcomes);
  result->text.clear();
  result->text.reserve(chunk.text.size() * 4);
  result->by_status.clear();
  result->rows = rows.size();
  for (size_t i = 0; i < rows.size(); ++i) {
    ++result->by_status[outcomes[i].status];
    append_row(rows[i], job.input_columns, outcomes[i], result->text);
  }
}

// Writes chunks in input order and keeps the counts; one writer at a time.
class OrderedWriter {
 public:
  OrderedWriter(const BatchJob& job, std::ostream& out, const BatchOutput& how,
                BatchSummary* summary)
      : job_(job), out_(out), how_(how), summary_(summary) {}

  // False when the output broke off.
  bool write(ChunkResult& chunk) {
    const double start = thread_cpu_seconds();
    out_.write(chunk.text.data(), static_cast<std::streamsize>(chunk.text.size()));
    if (how_.flush_each_chunk) out_.flush();
    for (const auto& [status, count] : chunk.by_status) {
      summary_->by_status[status] += count;
      if (job_.failed(status)) summary_->failed += count;
    }
    summary_->rows += chunk.rows;
    write_seconds_ += thread_cpu_seconds() - start;
    if (!out_) return false;
    // Rewritten at most a few times a second, so a terminal keeps up.
    if (how_.progress && Clock::now() - shown_ > std::chrono::milliseconds(250)) {
      shown_ = Clock::now();
      *how_.progress << '\r' << job_.command << ": " << summary_->rows << " rows done"
                     << std::flush;
    }
    return true;
  }

  double write_seconds() const { return write_seconds_; }
  bool shown() const { return shown_ != Clock::time_point{}; }

 private:
  const BatchJob& job_;
  std::ostream& out_;
  const BatchOutput& how_;
  BatchSummary* summary_;
  Clock::time_point shown_{};
  double write_seconds_ = 0.0;
};

// One chunk on its way through: read, then worked on, then finished, then written.
struct Slot {
  BatchChunk input;
  ChunkResult output;
  bool taken = false;
  bool finished = false;
};

}  // namespace

BatchSummary run_batch(BatchReader& reader, const BatchJob& job, std::ostream& out,
                       const BatchOutput& how) {
  const Clock::time_point started = Clock::now();
  BatchSummary summary;
  BatchTimes times;
  OrderedWriter writer(job, out, how, &summary);
  out << job.header << '\n';
  if (how.flush_each_chunk) out.flush();
  const size_t rows_per_chunk = std::max<size_t>(job.block_rows, 1);
  const unsigned threads = thread_count(job.threads);
  bool broke_off = false;

  if (threads <= 1) {
    // Everything on this thread, in turn.
    BatchChunk chunk;
    ChunkResult result;
    ChunkScratch scratch;
    for (;;) {
      double start = thread_cpu_seconds();
      const bool more = reader.read_chunk(rows_per_chunk, &chunk);
      times.read += thread_cpu_seconds() - start;
      if (!more) break;
      start = thread_cpu_seconds();
      process_chunk(chunk, job, scratch, &result);
      times.work += thread_cpu_seconds() - start;
      if (!writer.write(result)) {
        broke_off = true;
        break;
      }
    }
  } else {
    // The main thread reads; the workers take chunks in order, and the one that finishes
    // the oldest unwritten chunk writes it and every finished chunk after it.
    const size_t most_held = 2 * static_cast<size_t>(threads) + 2;
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<Slot> slots;  // references stay valid across push_back and pop_front
    size_t first = 0;        // the index of slots.front() among the chunks read
    size_t next = 0;         // the next chunk to work on
    bool read_all = false;
    bool writing = false;
    std::vector<double> work_seconds(threads, 0.0);
    // Chunks' buffers that have been read and written, kept for the next chunks (their
    // memory reused rather than freed and allocated again).
    std::vector<BatchChunk> spare_inputs;
    std::vector<ChunkResult> spare_outputs;

    const auto work = [&](unsigned t) {
      ChunkScratch scratch;
      std::unique_lock lock(mutex);
      for (;;) {
        changed.wait(lock, [&] { return next < first + slots.size() || read_all || broke_off; });
        if (broke_off || next >= first + slots.size()) return;  // nothing left to start
        Slot& slot = slots[next++ - first];
        if (!spare_outputs.empty()) {
          slot.output = std::move(spare_outputs.back());
          spare_outputs.pop_back();
        }
        lock.unlock();
        const double start = thread_cpu_seconds();
        process_chunk(slot.input, job, scratch, &slot.output);
        work_seconds[t] += thread_cpu_seconds() - start;
        lock.lock();
        spare_inputs.push_back(std::move(slot.input));
        slot.finished = true;
        if (writing) continue;  // the writer will find it
        writing = true;
        while (!broke_off && !slots.empty() && slots.front().finished) {
          ChunkResult done = std::move(slots.front().output);
          slots.pop_front();
          ++first;
          changed.notify_all();  // room for the reader
          lock.unlock();
          const bool ok = writer.write(done);
          lock.lock();
          spare_outputs.push_back(std::move(done));
          if (!ok) broke_off = true;
        }
        writing = false;
        changed.notify_all();
      }
    };
    std::vector<std::jthread> pool;
    pool.reserve(threads);
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work, t);

    BatchChunk chunk;
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return slots.size() < most_held || broke_off; });
      if (broke_off) break;
      if (!spare_inputs.empty()) {
        chunk = std::move(spare_inputs.back());
        spare_inputs.pop_back();
      }
      lock.unlock();
      const double start = thread_cpu_seconds();
      const bool more = reader.read_chunk(rows_per_chunk, &chunk);
      times.read += thread_cpu_seconds() - start;
      lock.lock();
      if (!more) break;
      slots.emplace_back().input = std::move(chunk);
      chunk = {};  // a spare one's buffers are taken above when there is one
      changed.notify_all();
    }
    read_all = true;
    changed.notify_all();
    changed.wait(lock, [&] { return (slots.empty() && !writing) || broke_off; });
    changed.notify_all();
    lock.unlock();
    pool.clear();  // joins
    for (double s : work_seconds) times.work += s;
  }

  if (!broke_off) out.flush();
  if (broke_off || !out) {
    summary.error = "cannot write the output";
  } else if (!reader.error().empty()) {
    summary.error = reader.error();
  }
  if (how.progress && writer.shown()) *how.progress << "\r\033[K" << std::flush;
  times.write = writer.write_seconds();
  times.wall = seconds_since(started);
  if (how.times) *how.times = times;
  return summary;
}

bool stdout_is_interactive() {
  struct stat st {};
  if (::fstat(STDOUT_FILENO, &st) != 0) return false;
  return S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) || S_ISCHR(st.st_mode) ||
         isatty(STDOUT_FILENO) == 1;
}

std::string summary_line(const char* command, const BatchSummary& summary, const char* unit) {
  std::string line =
      fmt::format("{}: {} {}{}", command, summary.rows, unit, summary.rows == 1 ? "" : "s");
  const char* separator = ": ";
  for (const auto& [status, count] : summary.by_status) {
    line += fmt::format("{}{} {}", separator, count, status);
    separator = ", ";
  }
  line += summary.failed == 0 ? "; none failed" : fmt::format("; {} failed", summary.failed);
  return line;
}

int run_batch_command(BatchReader& reader, const BatchJob& job, std::ostream& out,
                      std::ostream& err) {
  // Progress only where a person watches it: the process's own stderr, on a terminal.
  const bool terminal = err.rdbuf() == std::cerr.rdbuf() && isatty(STDERR_FILENO) == 1;
  BatchOutput how;
  how.progress = terminal ? &err : nullptr;
  how.flush_each_chunk = out.rdbuf() == std::cout.rdbuf() && stdout_is_interactive();
  BatchTimes times;
  const char* want_times = std::getenv("CUEPLAN_BATCH_TIMES");
  if (want_times != nullptr) how.times = &times;
  const BatchSummary summary = run_batch(reader, job, out, how);
  if (!summary.error.empty()) err << job.command << ": " << summary.error << '\n';
  if (how.times)
    err << fmt::format(
        "{}: times: {:.3f} s wall; CPU: {:.3f} s reading (main thread), {:.3f} s writing "
        "(in order), {:.3f} s parsing, computing and formatting (all workers)\n",
        job.command, times.wall, times.read, times.write, times.work);
  err << summary_line(job.command, summary) << '\n';
  return summary.error.empty() && summary.failed == 0 ? kExitOk : kExitFailed;
}

}  // namespace cueplan::batch
