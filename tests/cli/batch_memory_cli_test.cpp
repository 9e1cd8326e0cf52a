// A batch streams: `cueplan rebound --batch -` fed a million impacts on standard input
// keeps its resident memory under a fixed bound, far below what holding the rows would
// take (about 0.9 kB a row before batches streamed: 87 MB for 100k rows). The peak is
// the kernel's count for the finished child processes (getrusage RUSAGE_CHILDREN), so
// this test program runs nothing else.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/cli_test_support.hpp"

namespace cli_test {
const char* const kScratchName = "cueplan_batch_memory_test_";
}

namespace {

using cli_test::lines_of;

constexpr long kRows = 1000000;
constexpr long kBoundKiB = 50 * 1024;  // 50 MB, the binary and its libraries included

TEST(BatchMemory, MillionReboundsStayUnderFiftyMegabytes) {
  // The rows come from awk through a pipe, never as a file; the fast fixed-step method
  // keeps the run short (the memory does not depend on the method).
  const std::string rows =
      "awk 'BEGIN { print \"speed,angle_deg,topspin_k,sidespin_k\"; for (i = 0; i < " +
      std::to_string(kRows) +
      "; i++) printf \"%.6g,%.6g,%.3g,%.3g\\n\", 0.2 + (i % 997) * 0.002, 5 + (i % 170), "
      "((i % 21) - 10) / 10, ((i % 11) - 5) / 10 }'";
  const std::filesystem::path dir = cli_test::scratch();
  const std::string command =
      rows + " | { '" CUEPLAN_BINARY "' rebound --batch - --method paper --steps 10 --threads 2 2>'" +
      (dir / "err").string() + "'; echo $? >'" + (dir / "code").string() + "'; } | wc -l >'" +
      (dir / "lines").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(cli_test::read_text(dir / "code"), "0\n");
  EXPECT_EQ(cli_test::read_text(dir / "err"),
            "cueplan rebound: 1000000 rows: 1000000 ok; none failed\n");
  EXPECT_EQ(lines_of(cli_test::read_text(dir / "lines")).at(0),
            std::to_string(kRows + 1));  // the header and every row

  rusage children{};
  ASSERT_EQ(getrusage(RUSAGE_CHILDREN, &children), 0);
  const long peak_kib = children.ru_maxrss;  // KiB on Linux
  RecordProperty("peak_resident_kib", std::to_string(peak_kib));
  EXPECT_GT(peak_kib, 1024) << "the peak of the children was not measured";
  EXPECT_LT(peak_kib, kBoundKiB) << "the batch held " << peak_kib / 1024 << " MB";
}

}  // namespace
