// The `exact` method: Taylor-mode series in the slip variables (private header).
// The method itself is described in impact_taylor.cpp; this header is what the scalar
// path (solve_taylor) and the batch of SIMD lanes (impact_taylor_lanes.cpp) share.
#pragma once

#include <vector>

#include "impact_methods.hpp"
#include "impact_taylor_series.hpp"

namespace cueplan::physics::detail::taylor {

// What a tolerance asks of the integrator.
struct Settings {
  double tolerance = 1e-12;  // local error per step, relative to the speed scale
  int order = 16;            // series order N
  int max_steps = 10000;     // steps allowed (ImpactOptions::max_steps)
  double zero_slip = 0.0;    // a slip this small is zero
  double close_slip = 0.0;   // a slip this small whose contact can stick is closed at once
  double cross_slip = 0.0;   // a slip this small heading to zero, unable to stick, has crossed

  static Settings from(double tolerance, int max_steps);
};

// The kernel a step uses: one of the two fast ones (both contacts slipping, in tau
// or in sigma; impact_taylor_series.hpp) or the general one (impact_taylor.cpp).
enum class Kernel { tau, sigma, general };

// The builds of the one-impact fast kernels: SSE2 (every x86-64 CPU), AVX2, and AVX2
// with AVX-512's 32 registers (AVX-512VL) - bit for bit the same.
enum class KernelIsa { sse2, avx2, avx512 };

// The widest build the kernels may use: the CPU's, capped by the environment variable
// CUEPLAN_SIMD (sse2, avx2 or avx512; read once per process) for tools that do not
// decode every AVX instruction, such as valgrind 3.19 (bench/callgrind_ab.sh sets it).
// Results do not depend on it: every build gives the same bits.
KernelIsa widest_isa();

// The series of a fast step of one impact (its state in s.c[.][0]) with the widest
// build allowed (widest_isa).
void fast_series(Kernel kernel, const Constants& constants, int order, Coefficients<double>& s);
// The same with a given build; false (s untouched) where the CPU lacks it.
bool fast_series_on(KernelIsa isa, Kernel kernel, const Constants& constants, int order,
                    Coefficients<double>& s);

// A step's series read in place: coefficient j of series q at at[(q * kTerms + j) * L].
// L = 1 is a Coefficients<double>; L > 1 is one lane of a Coefficients of L-wide
// vectors (the batch's vector kernels write L impacts' series side by side).
template <int L>
struct SeriesView {
  const double* at;
  double operator()(int q, int j) const { return at[(q * kTerms + j) * L]; }
  const double* series(int q) const { return at + q * kTerms * L; }
};

// One impact, step by step. A step computes the state's Taylor series in the step's
// variable, chooses its length from the series, and ends early on the first event
// (a root of one of the step's polynomials).
class Integrator {
 public:
  Integrator(const ScaledImpact& impact, const Constants& constants, const Settings& settings,
             std::vector<TraceSample>* trace, ScaledOutcome* out);

  bool done() const { return done_; }

  // Plans the next step. For Kernel::tau and Kernel::sigma the caller computes the
  // series with series_tau or series_sigma from state() and passes them to
  // finish_fast_step; for Kernel::general it calls take_planned_step.
  Kernel plan_step();
  const double* state() const { return q_; }
  void finish_fast_step(const Coefficients<double>& series);
  // The same from a lane of a packed series (L = 2, 4, 8), read where it is, in two
  // halves: the step's length h, then the step given the state at h (at_h), which the
  // batch evaluates for all its lanes at once.
  template <int L>
  double fast_step_length(SeriesView<L> series) const;
  template <int L>
  void finish_fast_step(SeriesView<L> series, double h, const double* at_h);
  void take_planned_step();

  // The whole impact; then finish().
  void run();
  // Writes the outcome (after done(), or when the step bound stopped the impact).
  void finish();

 private:
  struct ContactMode {
    bool stick = false;
    int young = 0;  // slip growing from zero: 1 like P (stick failed), 2 like P^2 (stick broke)
    Direction seed;  // direction of a young slip (its first guess, for young = 1)
  };
  struct Plan {
    bool reg[2] = {false, false};  // dP/dsigma includes |u_I|, |u_C|
    bool young = false;            // a contact starts from zero slip: a step in P
  };
  // A contact's slip size |u| and direction u / |u| (NaN where |u| = 0).
  struct Shape {
    double r = 0.0;
    double ex = 0.0, ey = 0.0;
  };
  class General;  // the kernel for every other kind of step (impact_taylor.cpp)

  Scaled centroid(const double* q) const;
  bool slipping(int contact) const { return !mode_[contact].stick; }
  double slip_size(int contact) const;
  void slip_rates(double rates[4]) const;
  Shape shape(int contact) const;
  Direction direction(int contact) const;
  Direction direction(int contact, const Shape& shape) const;
  bool stick_would_hold(int contact) const;
  double stick_margin_at(int contact, const double* q) const;
  double margin_of(int contact, const Friction& f) const;
  bool close_slip(int contact);
  void settle_modes(bool force_slip_i, bool force_slip_c);
  template <int L>
  void take_step(SeriesView<L> s, int order);
  template <int L>
  void take_step(SeriesView<L> s, int order, double h, const double* at_h);
  template <int L>
  double step_length(SeriesView<L> s, int order) const;
  template <int L>
  double step_size(SeriesView<L> s, int order) const;
  template <int L>
  void record_trace(const SeriesView<L>* s, int order, double h);
  void fail(const char* why);

  const Constants& k_;
  const Geometry& g_;
  const Settings& set_;
  const double e_;
  std::vector<TraceSample>* trace_;
  ScaledOutcome* out_;

  double q_[kState] = {};  // x_I, y_I', x_C, y_C, o_z, W of the phase, p
  ContactMode mode_[2];
  Plan plan_;
  Shape planned_[2];  // the slips' shapes in the state plan_step planned from
  bool compressing_ = true;
  bool done_ = false;
  double work_compression_ = 0.0;
  double work_target_ = 0.0;  // restitution: W of the phase when the impact ends (< 0)
  double step_impulse_ = 0.0;  // P length the next step is expected to cover
  double uy_start_ = 0.0;
  int steps_ = 0;
  int mode_changes_ = 0;
};

}  // namespace cueplan::physics::detail::taylor
