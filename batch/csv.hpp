// Comma-separated values as the command line reads and writes them (RFC 4180 quoting,
// numbers in the shortest form that reads back to the same double).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::batch {

// Shortest decimal text that parses back to exactly `value`; "nan", "inf", "-inf"
// for the non-finite values.
std::string format_number(double value);

// The text in double quotes, inner quotes doubled.
std::string csv_quoted(std::string_view text);

// A field quoted (as csv_quoted) when it holds a comma, quote or line break.
std::string csv_field(std::string_view text);

// Fields joined with commas and ended by a newline; each field passes through csv_field.
std::string csv_line(const std::vector<std::string>& fields);

// Splits one line (without its line break) into fields, undoing csv_field's quoting.
// Surrounding spaces of unquoted fields are kept; parse_number ignores them.
std::vector<std::string> split_csv_line(std::string_view line);

// The whole field as a number (surrounding spaces allowed, "nan" and "inf" accepted);
// nullopt when anything else is in it.
std::optional<double> parse_number(std::string_view field);

// A table of text cells with a header, for the numbers behind a plot.
class CsvTable {
 public:
  explicit CsvTable(std::vector<std::string> header) : header_(std::move(header)) {}

  // One row; must have as many cells as the header.
  void add_row(std::vector<std::string> cells);
  // One row of numbers, each through format_number.
  void add_numbers(const std::vector<double>& values);

  const std::vector<std::string>& header() const { return header_; }
  size_t row_count() const { return rows_.size(); }
  std::string to_string() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace cueplan::batch
