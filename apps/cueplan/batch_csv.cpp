#include "batch_csv.hpp"

#include <fstream>
#include <ostream>

#include "csv.hpp"

namespace cueplan::cli {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

BatchInput read_batch_csv(const std::string& path, std::string_view header) {
  BatchInput input;
  std::ifstream in(path);
  if (!in) {
    input.error = "--batch: cannot open " + path;
    return input;
  }
  std::string line;
  int line_number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trimmed(line).empty()) continue;
    if (!header_seen) {
      std::string got;
      for (const std::string& field : split_csv_line(line)) {
        if (!got.empty()) got += ',';
        got += trimmed(field);
      }
      if (got != header) {
        input.error = "--batch: " + path + " must start with the header '" + std::string(header) +
                      "', got '" + line + "'";
        return input;
      }
      header_seen = true;
      continue;
    }
    input.rows.push_back({line_number, split_csv_line(line)});
  }
  if (in.bad())
    input.error = "--batch: error while reading " + path;
  else if (!header_seen)
    input.error = "--batch: " + path + " is empty; it needs the header '" + std::string(header) +
                  "'";
  return input;
}

void write_batch_rows(const BatchInput& input, size_t input_columns,
                      std::vector<BatchOutcome> outcomes, std::ostream& out) {
  for (size_t i = 0; i < input.rows.size(); ++i) {
    std::vector<std::string> cells;
    for (size_t c = 0; c < input_columns; ++c)
      cells.push_back(c < input.rows[i].fields.size() ? trimmed(input.rows[i].fields[c]) : "");
    for (std::string& cell : outcomes[i].results) cells.push_back(std::move(cell));
    cells.push_back(outcomes[i].status);
    std::string line = csv_line(cells);
    line.pop_back();  // its newline: the quoted message follows
    out << line << ',' << csv_quoted(outcomes[i].message);
    for (const std::string& cell : outcomes[i].after_message) out << ',' << csv_field(cell);
    out << '\n';
  }
}

}  // namespace cueplan::cli
