// A precomputed surrogate of the cushion impact.
//
// For the paper's initial state (section 3.1) the outcome divided by V0 depends on
// (alpha, k_T, k_S) only, and mass and radius scale out: the table samples the exact
// method on a grid over alpha in [0, 90] deg (alpha > 90 by mirror symmetry) and
// |k_T|, |k_S| <= k_max, and interpolates. Its error is measured when it is built,
// cell by cell, against the exact method; a cell whose measured error is above the
// build tolerance (a stick/slip change runs through it) answers with the exact method.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::physics {

struct ImpactTableOptions {
  int alpha_nodes = 91;      // nodes over [0, 90] deg
  int topspin_nodes = 61;    // nodes over [-k_max, k_max]
  int sidespin_nodes = 61;   // nodes over [-k_max, k_max]
  double k_max = 3.0;        // largest |k_T| and |k_S| covered
  double cell_tolerance = 1e-7;  // measured relative error above which a cell falls back
  int threads = 0;           // build threads; 0: all cores

  std::string validate() const;
};

// What the build measured: errors of interpolation against the exact method at test
// points inside every cell (its centre and face centres), over the cells that
// interpolate (fallback cells are exact by construction).
struct ImpactTableError {
  double max_speed_relative = 0.0;  // |rebound speed - exact| / V0
  double max_angle_deg = 0.0;       // |rebound angle - exact|
  double max_state_relative = 0.0;  // max over velocity and R*spin components, / V0
  int64_t cells = 0;
  int64_t fallback_cells = 0;
  int64_t test_points = 0;
};

class ImpactTable {
 public:
  // Builds the table for the dimensionless parameters of `params` (theta, mu_w,
  // mu_s, e). Takes seconds; use load_or_build to keep it between runs.
  static ImpactTable build(const CushionParams& params, const ImpactTableOptions& options = {});

  // Loads a cached table for these parameters and options from `cache_dir`, or
  // builds and saves one there. `note`, when given, says which happened.
  static ImpactTable load_or_build(const CushionParams& params,
                                   const ImpactTableOptions& options,
                                   const std::string& cache_dir, std::string* note = nullptr);

  bool save(const std::string& path) const;
  static std::optional<ImpactTable> load(const std::string& path);

  // True when the table was built for the same dimensionless parameters.
  bool covers(const CushionParams& params) const;

  // Fills *result and returns true when the state has the paper's form (spin about
  // the horizontal axis perpendicular to the motion, plus sidespin), lies inside the
  // table's domain and `params` is covered; returns false otherwise.
  bool resolve(const CushionParams& params, const BallState& incoming,
               ImpactResult* result) const;

  const ImpactTableError& measured_error() const { return error_; }
  const ImpactTableOptions& options() const { return options_; }

 private:
  ImpactTableOptions options_;
  CushionParams params_;
  ImpactTableError error_;
  // Implementation data, laid out by impact_table.cpp.
  std::vector<double> nodes_;
  std::vector<uint8_t> fallback_;
};

}  // namespace cueplan::physics
