// A precomputed surrogate of the cushion impact.
//
// For the paper's initial state (section 3.1) the outcome divided by V0 depends on
// (alpha, k_T, k_S) only, and mass and radius scale out: the table samples the exact
// method on a grid over alpha in [0, 90] deg (alpha > 90 by mirror symmetry) and
// |k_T|, |k_S| <= k_max, and interpolates. Its error is measured when it is built,
// cell by cell, against the exact method; a cell whose measured error is above the
// build tolerance (a stick/slip change runs through it) answers with the exact method.
//
// Interpolation is tricubic Lagrange on a grid uniform per axis. The outcome has a
// kink at k_T = 1 (the table slip starts at zero), so the k_T axis has a node there
// and no stencil crosses it. Every cell keeps the stencil (centred, or shifted one
// node along any axis) whose measured error is smallest; a cell with none within the
// tolerance falls back. Natural roll (k_T = 1, the state of a ball that rolls into
// the cushion, the commonest case) has its own finer two-dimensional grid over
// (alpha, k_S), interpolated bicubically and measured the same way.
//
// A built table is immutable: resolve() may be called from many threads at once.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::physics {

struct ImpactTableOptions {
  int alpha_nodes = 46;           // nodes over [0, 90] deg (2 deg apart)
  int topspin_nodes = 121;        // nodes over [-k_max, k_max], one of them on k_T = 1
  int sidespin_nodes = 121;       // nodes over [-k_max, k_max]
  int roll_alpha_nodes = 181;     // natural-roll plane: nodes over [0, 90] deg
  int roll_sidespin_nodes = 481;  // natural-roll plane: nodes over [-k_max, k_max]
  double k_max = 3.0;             // largest |k_T| and |k_S| covered
  // A cell interpolates when the errors measured at its test points are within
  // cell_tolerance in |rebound speed - exact| / V0, 100 deg * cell_tolerance in the
  // rebound angle, and 10 * cell_tolerance in every velocity and R*spin component
  // / V0 and in the impulses / (M V0) and work / (M V0^2).
  double cell_tolerance = 5e-7;
  int threads = 0;  // build threads; 0: all cores (does not change the table)

  // Empty when usable; otherwise the first broken rule, fields named as the members here.
  Validation validate() const;
};

// What the build measured: errors of interpolation against the exact method at test
// points inside every cell (a cell's centre and face centres; on the natural-roll
// plane its centre and edge midpoints), over the cells that interpolate (fallback
// cells are exact by construction).
struct ImpactTableError {
  double max_speed_relative = 0.0;    // |rebound speed - exact| / V0
  double max_angle_deg = 0.0;         // |rebound angle - exact|
  double max_state_relative = 0.0;    // max over velocity and R*spin components, / V0
  double max_impulse_relative = 0.0;  // impulses / (M V0) and work / (M V0^2)
  int64_t cells = 0;
  int64_t fallback_cells = 0;
  int64_t roll_cells = 0;  // cells of the natural-roll plane
  int64_t roll_fallback_cells = 0;
  int64_t test_points = 0;  // exact evaluations made to measure the cells
};

class ImpactTable {
 public:
  // Builds the table for the dimensionless parameters of `params` (theta, mu_w,
  // mu_s, e). Takes seconds; keep it between runs with save() and load() (where is the
  // caller's choice: the command line keeps a cache directory). Invalid params or
  // options give an empty table, which covers nothing.
  static ImpactTable build(const CushionParams& params, const ImpactTableOptions& options = {});

  // A file name for a cache of tables: it encodes the format version, the
  // dimensionless parameters and the options that shape the table.
  static std::string cache_file_name(const CushionParams& params,
                                     const ImpactTableOptions& options);

  // Writes a versioned binary file (through a temporary file and a rename).
  bool save(const std::string& path) const;
  // Reads a file written by save(); nullopt when it is missing, of another version,
  // truncated or corrupt.
  static std::optional<ImpactTable> load(const std::string& path);

  // True when the table was built for the same dimensionless parameters.
  bool covers(const CushionParams& params) const;
  // True when the table has the shape (nodes, k range, cell tolerance) `options` ask
  // for; the build's thread count does not shape it.
  bool built_with(const ImpactTableOptions& options) const;
  // True when the table holds nothing (failed build).
  bool empty() const { return nodes_.empty(); }

  // Fills *result and returns true when the state has the paper's form (spin about
  // the horizontal axis perpendicular to the motion, plus sidespin), lies inside the
  // table's domain (0 < alpha < 180, |k_T|, |k_S| <= k_max), `params` is covered
  // and the cell interpolates; returns false otherwise (the caller then uses the
  // exact method). Allocation-free unless the rigid speed limit is exceeded (the
  // message is set then). Slip histories are not kept: transition_count is 0, and
  // the slipping_at_start flags are the exact method's choice at the incoming slips.
  bool resolve(const CushionParams& params, const BallState& incoming, ImpactResult* result) const;

  const ImpactTableError& measured_error() const { return error_; }
  const ImpactTableOptions& options() const { return options_; }
  // Fallback cells as a fraction of all cells (of the volume), and the same on the
  // natural-roll plane.
  double fallback_fraction() const;
  double roll_fallback_fraction() const;
  // The exact method's tolerance for the impacts this table does not answer, matched
  // to the table's accuracy: cell_tolerance / 500 (1e-9 for the default table), at
  // which the exact method's worst error over the domain is 45 times or more inside
  // the table's bounds (bench/README.md), at about 60 % of its default tolerance's time.
  // Kept within the exact method's range [1e-15, 1e-2].
  double fallback_tolerance() const {
    return std::clamp(options_.cell_tolerance / 500.0, 1e-15, 1e-2);
  }

 private:
  friend class ImpactTableAccess;  // build and file code in impact_table.cpp

  // One grid axis: uniform, or two uniform pieces meeting at a kink node.
  struct Axis {
    int nodes = 0;
    int kink_node = -1;  // index of the node on the kink; -1: none
    double lo = 0.0, kink = 0.0, hi = 0.0;
    double step_low = 0.0, step_high = 0.0;  // spacing below and above the kink
    double inv_step_low = 0.0, inv_step_high = 0.0;

    static Axis uniform(int nodes, double lo, double hi);
    // Uniform pieces either side of `kink` (lo < kink < hi), each of >= 3 cells.
    static Axis with_kink(int nodes, double lo, double kink, double hi);
    double node(int i) const;
    // Cell (0 .. nodes-2) holding x, and x's position in it, 0..1.
    int cell_of(double x, double* local) const;
    // First node of the 4-node stencil of `cell` shifted by -1, 0 or +1 nodes,
    // kept inside the cell's piece so that no stencil crosses the kink.
    int stencil_start(int cell, int shift) const;
  };

  // Interpolate the stored outcome at `local` (0..1 per axis) of `cell` with the
  // stencil coded `stencil`: in the volume (alpha, k_T, k_S), and on the
  // natural-roll plane (alpha, k_S).
  void interpolate(const int cell[3], const double local[3], int stencil, double* out) const;
  void interpolate_roll(const int cell[2], const double local[2], int stencil, double* out) const;

  ImpactTableOptions options_;
  CushionParams params_;
  ImpactTableError error_;
  // Dimensionless parameters the table covers, and two exact relations of the
  // model that give the outcomes not stored (see impact_table.cpp).
  double sin_theta_ = 0.0;
  double cos_theta_ = 0.0;
  double spin_coupling_ = 0.0;   // (1 + sin th) / cos th
  double work_ratio_ = 0.0;      // 1 - e^2
  Axis axes_[3];                 // alpha (deg), k_T, k_S
  Axis roll_axes_[2];            // alpha (deg), k_S
  bool has_roll_plane_ = false;  // k_max >= 1
  // Stored outcomes per node (alpha slowest, k_S fastest), and per cell its
  // stencil code or a fallback mark; the same for the natural-roll plane.
  std::vector<double> nodes_;
  std::vector<uint8_t> cell_stencil_;
  std::vector<double> roll_nodes_;
  std::vector<uint8_t> roll_stencil_;
};

}  // namespace cueplan::physics
