// Batch files of the command line (`rebound --batch`, `simulate --batch`): an input CSV
// with a fixed header and one case per line, and the output CSV written back, one row
// per input row in input order.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::cli {

// One line of the input file, as read.
struct BatchRow {
  int line = 0;                     // 1-based line number in the file
  std::vector<std::string> fields;  // the cells as written
};

// The input rows of a batch file, or why the whole file cannot be used.
struct BatchInput {
  std::vector<BatchRow> rows;
  std::string error;  // empty when the file was read and its header is right
};

// Reads a batch file whose first non-blank line must be `header` (its cells compared
// with surrounding spaces removed); blank lines are skipped and a trailing CR dropped.
BatchInput read_batch_csv(const std::string& path, std::string_view header);

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

// Writes one output line per input row: its first `input_columns` cells (trimmed, empty
// where the row is short), the outcome's results, its status, its message, which is
// always quoted because it is free text, and its after_message cells. The header line
// is the caller's.
void write_batch_rows(const BatchInput& input, size_t input_columns,
                      std::vector<BatchOutcome> outcomes, std::ostream& out);

}  // namespace cueplan::cli
