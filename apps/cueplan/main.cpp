// cueplan: the command line over the cueplan libraries. Each subcommand lives in its
// own file and is registered in cli_main.cpp, which parses, reports parse errors in
// one line and dispatches.
#include <cstdlib>
#include <iostream>
#include <string_view>

#include "cli_main.hpp"
#include "cueplan/planner/route.hpp"

namespace {

// CUEPLAN_SIMD caps the instruction set of the exact impact's kernels (for tools such
// as valgrind that do not decode every AVX instruction). The library takes sse2, avx2
// and avx512 and ignores anything else; say so rather than leave a typo unnoticed.
void warn_about_simd_cap(std::ostream& err) {
  const char* cap = std::getenv("CUEPLAN_SIMD");
  if (cap == nullptr) return;
  const std::string_view value(cap);
  if (value == "sse2" || value == "avx2" || value == "avx512") return;
  err << "cueplan: warning: CUEPLAN_SIMD='" << value
      << "' is not one of sse2, avx2, avx512; ignored (the exact impact uses the widest "
         "instruction set the CPU has)\n";
}

}  // namespace

int main(int argc, char** argv) {
  warn_about_simd_cap(std::cerr);
  // The commands print their own reports; OMPL (route, solve --global ompl_kpiece1)
  // keeps to errors.
  cueplan::planner::quiet_ompl_messages();
  return cueplan::cli::run_cli(argc, argv, std::cout, std::cerr);
}
