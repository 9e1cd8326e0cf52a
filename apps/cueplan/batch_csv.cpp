#include "batch_csv.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <ostream>

#include "csv.hpp"
#include "exit_codes.hpp"

namespace cueplan::cli {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

BatchReader::BatchReader(const std::string& path, std::string_view header) {
  if (path == "-") {
    name_ = "standard input";
    in_ = &std::cin;
  } else {
    name_ = path;
    file_.open(path);
    if (!file_) {
      error_ = "--batch: cannot open " + path;
      return;
    }
    in_ = &file_;
  }
  std::string line;
  while (std::getline(*in_, line)) {
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trimmed(line).empty()) continue;
    std::string got;
    for (const std::string& field : split_csv_line(line)) {
      if (!got.empty()) got += ',';
      got += trimmed(field);
    }
    if (got != header)
      error_ = "--batch: " + name_ + " must start with the header '" + std::string(header) +
               "', got '" + line + "'";
    return;
  }
  error_ = in_->bad() ? "--batch: error while reading " + name_
                      : "--batch: " + name_ + " is empty; it needs the header '" +
                            std::string(header) + "'";
}

void BatchReader::read(size_t count, std::vector<BatchRow>* rows) {
  rows->clear();
  if (!error_.empty()) return;
  std::string line;
  while (rows->size() < count && std::getline(*in_, line)) {
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trimmed(line).empty()) continue;
    rows->push_back({line_number_, split_csv_line(line)});
  }
  if (in_->bad()) error_ = "--batch: error while reading " + name_;
}

namespace {

void write_row(const BatchRow& row, size_t input_columns, BatchOutcome& outcome,
               std::ostream& out) {
  std::vector<std::string> cells;
  cells.reserve(input_columns + outcome.results.size() + 1);
  for (size_t c = 0; c < input_columns; ++c)
    cells.push_back(c < row.fields.size() ? trimmed(row.fields[c]) : "");
  for (std::string& cell : outcome.results) cells.push_back(std::move(cell));
  cells.push_back(outcome.status);
  std::string line = csv_line(cells);
  line.pop_back();  // its newline: the quoted message follows
  out << line << ',' << csv_quoted(outcome.message);
  for (const std::string& cell : outcome.after_message) out << ',' << csv_field(cell);
  out << '\n';
}

}  // namespace

BatchSummary run_batch(BatchReader& reader, const BatchJob& job, std::ostream& out,
                       std::ostream* progress) {
  using Clock = std::chrono::steady_clock;
  BatchSummary summary;
  out << job.header << '\n';
  std::vector<BatchRow> rows;
  std::vector<BatchOutcome> outcomes;
  Clock::time_point shown{};
  for (reader.read(job.block_rows, &rows); !rows.empty(); reader.read(job.block_rows, &rows)) {
    outcomes.assign(rows.size(), {});
    job.compute(rows, outcomes);
    for (size_t i = 0; i < rows.size(); ++i) {
      ++summary.by_status[outcomes[i].status];
      if (job.failed(outcomes[i].status)) ++summary.failed;
      write_row(rows[i], job.input_columns, outcomes[i], out);
    }
    summary.rows += rows.size();
    if (!out) {
      summary.error = "cannot write the output";
      return summary;
    }
    // Rewritten at most a few times a second, so a terminal keeps up.
    if (progress && Clock::now() - shown > std::chrono::milliseconds(250)) {
      shown = Clock::now();
      *progress << '\r' << job.command << ": " << summary.rows << " rows done" << std::flush;
    }
  }
  out.flush();
  if (!reader.error().empty()) summary.error = reader.error();
  if (!out) summary.error = "cannot write the output";
  if (progress && shown != Clock::time_point{}) *progress << "\r\033[K" << std::flush;
  return summary;
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
  const BatchSummary summary = run_batch(reader, job, out, terminal ? &err : nullptr);
  if (!summary.error.empty()) err << job.command << ": " << summary.error << '\n';
  err << summary_line(job.command, summary) << '\n';
  return summary.error.empty() && summary.failed == 0 ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
