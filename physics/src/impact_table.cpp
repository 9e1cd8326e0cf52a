// PLACEHOLDER while the surrogate is written: covers nothing, so resolve_impact
// answers table requests with the exact method.
#include "cueplan/physics/impact_table.hpp"

namespace cueplan::physics {
std::string ImpactTableOptions::validate() const { return {}; }
bool ImpactTable::resolve(const CushionParams&, const BallState&, ImpactResult*) const {
  return false;
}
}  // namespace cueplan::physics
