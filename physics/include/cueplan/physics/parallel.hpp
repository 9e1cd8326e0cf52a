// The thread helper's former home: cueplan::parallel_for and cueplan::thread_count live in
// cueplan/parallel.hpp (they serve every layer, not only the physics); these names keep
// older callers building.
#pragma once

#include "cueplan/parallel.hpp"

namespace cueplan::physics {
using cueplan::parallel_for;
using cueplan::thread_count;
}  // namespace cueplan::physics
