// Tests of the command line's reusable output helpers: CSV text and picture files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv.hpp"
#include "cueplan/api/output_file.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // csv.hpp
namespace {

TEST(Csv, NumbersReadBackExactly) {
  for (double x : {0.1, 1.0 / 3.0, -2.5e-17, 6.02214076e23, 0.0})
    EXPECT_EQ(parse_number(format_number(x)).value(), x) << format_number(x);
  EXPECT_EQ(format_number(NAN), "nan");
  EXPECT_TRUE(std::isnan(parse_number("nan").value()));
}

TEST(Csv, ParseNumberTakesOnlyWholeNumbers) {
  EXPECT_EQ(parse_number(" +1.5 ").value(), 1.5);
  EXPECT_FALSE(parse_number("1.5x").has_value());
  EXPECT_FALSE(parse_number("").has_value());
  EXPECT_FALSE(parse_number("fast").has_value());
}

TEST(Csv, QuotedFieldsSurviveARoundTrip) {
  const std::vector<std::string> fields = {"plain", "with, comma", "say \"hi\"", ""};
  std::string line = csv_line(fields);
  ASSERT_EQ(line.back(), '\n');
  line.pop_back();
  EXPECT_EQ(split_csv_line(line), fields);
  EXPECT_EQ(csv_quoted("a\"b"), "\"a\"\"b\"");
}

TEST(Csv, TableRowsMustMatchTheHeader) {
  CsvTable table({"x", "y"});
  table.add_numbers({1.0, 2.5});
  EXPECT_EQ(table.to_string(), "x,y\n1,2.5\n");
  EXPECT_THROW(table.add_numbers({1.0}), std::logic_error);
}

// A picture's file must name its format; the message names the flag.
TEST(OutputFile, PictureNeedsAKnownExtension) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  EXPECT_EQ(check_picture_file("--svg", dir / "plan.svg"), "");
  EXPECT_EQ(check_picture_file("--svg", dir / "plan.PNG"), "");
  EXPECT_EQ(check_picture_file("--out", dir / "plan.pdf"), "");
  const std::string jpg = check_picture_file("--svg", dir / "plan.jpg");
  EXPECT_EQ(jpg.rfind("--svg must name a .svg, .png or .pdf file", 0), 0u) << jpg;
  EXPECT_EQ(check_picture_file("--out", dir / "missing_dir_xyz" / "p.svg").rfind("--out: ", 0), 0u);
}

}  // namespace
}  // namespace cueplan::cli
