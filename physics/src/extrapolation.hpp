// Gragg-Bulirsch-Stoer extrapolation and the event landing it serves (private header),
// shared by the exact integrators of the cushion impact (impact_extrapolation.cpp) and of the
// ball-ball collision (ball_collision_extrapolation.cpp).
//
// Both models are integrated in t = -(normal approach speed), scaled. The normal impulse
// always slows the approach, so t rises monotonically through the whole impact: the end
// of compression is the fixed point t = 0, and the normal impulse p and the work W along
// the normal become state components, with dW/dt = -k t for a k > 0 that the model knows
// (k = c dp/dt at the cushion, k = dp/dt between two balls).
//
// Between events a model's right-hand side is smooth, so steps are taken by extrapolation
// of the modified midpoint rule (order up to 16), which reaches tight tolerances in very
// few steps. Events are landed on rather than stepped over:
//   - the end of compression, t = 0, a fixed target;
//   - the end of the impact, W = (1 - e^2) W_c, by Newton steps on the locally quadratic
//     W(t) (distance_to_work_end);
//   - a slip reaching zero, by Newton steps on |slip| (limit_step_by_slip). Near zero a
//     slip's direction turns on a scale of |slip|: no step turns a moving slip by more
//     than kMaxTurn, so that the extrapolation's error estimate sees the turn rather than
//     stepping over it, and a step that reversed a slip (stepped_through) is retried
//     shorter so that the zero is landed on instead.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "cueplan/physics/vec2.hpp"

namespace cueplan::physics::detail {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr int kMaxColumns = 8;    // midpoint runs of 2, 4, ..., 16 substeps
constexpr double kMaxTurn = 0.5;  // rad: the most a step may turn a moving slip

// Event thresholds for a tolerance (local error per step, in scaled units). They sit
// well above the integration noise (about tol per step) and well below what would change
// the outcome at the tolerance.
struct EventThresholds {
  double zero_slip = 0.0;   // a slip this small has reached zero
  double young_slip = 0.0;  // a slip grown from zero this large takes its own direction
  double close_slip = 0.0;  // a slip this small may be closed by the impulse that cancels it
  double landing = 0.0;     // an event this close in t has been reached
  double tiny = 0.0;        // a slip this small has no direction of its own

  static EventThresholds for_tolerance(double tol) {
    EventThresholds e;
    e.zero_slip = 100.0 * tol;
    e.young_slip = 1e5 * tol;
    // Closing a slip of size s costs O(s^2); 1e4 tol at tight tolerances, never above
    // 1e-6 nor below the zero-slip threshold.
    e.close_slip = std::max(e.zero_slip, std::min(1e4 * tol, 1e-6));
    e.landing = std::max(1e-3 * tol, 1e-15);
    e.tiny = 1e-3 * tol;
    return e;
  }
};

struct StepReport {
  int column = 0;       // the column the step was accepted at
  double next_h = 0.0;  // suggested size of the next step (or of the retry)
};

// A step as an integrator plans and takes it: f at its start, its size, the event it is
// cut to land on (`Target::none` when none), the state at its end and the extrapolation's
// report. Each integrator adds what it learns about its own slips.
template <size_t N, class Target>
struct PlannedStep {
  std::array<double, N> f0;  // f(t, y) at the step's start
  double size = 0.0;
  Target target = Target::none;
  std::array<double, N> next;  // the state at the step's end
  StepReport report;
};

// One extrapolated step of size h at a time, with the order and step-size control of
// extrapolation codes (Hairer & Wanner's ODEX): columns are computed up to one past the
// target column, a step is accepted at the first column whose error estimate (the
// largest component change between the last two columns) meets the tolerance, and the
// column that would cover the most ground per evaluation becomes the next target.
template <size_t N>
class Extrapolator {
 public:
  using State = std::array<double, N>;

  explicit Extrapolator(double tolerance) : tol_(tolerance) {}

  // A step from (t, y) with f0 = f(t, y); rhs(t, y, dy) evaluates f. True with the
  // result when the step converged; false with report->next_h the size to retry with.
  template <class Rhs>
  bool step(Rhs&& rhs, double t, const State& y, const State& f0, double h, State& result,
            StepReport* report);

 private:
  double tol_;
  int target_column_ = 4;  // column at which steps are meant to converge
};

template <size_t N>
template <class Rhs>
bool Extrapolator<N>::step(Rhs&& rhs, double t, const State& y, const State& f0, double h,
                           State& result, StepReport* report) {
  // Cumulative right-hand side calls to complete column k (substeps 2(k+1)), with f0.
  static constexpr std::array<double, kMaxColumns> kWork = {2, 5, 10, 17, 26, 37, 50, 65};
  const double length = std::abs(h);
  const int last = std::min(target_column_ + 1, kMaxColumns - 1);
  // row[j] holds T(k, j) of the current row k; it is updated in place.
  std::array<State, kMaxColumns> row;
  std::array<double, kMaxColumns> err_of{};
  auto substeps = [](int k) { return 2.0 * (k + 1); };
  // Step size that would let column k converge, from its error estimate.
  auto h_opt = [&](int k) {
    return length * 0.94 * std::pow(0.65 * tol_ / std::max(err_of[k], 1e-300), 1.0 / (2 * k + 1));
  };
  for (int k = 0; k <= last; ++k) {
    const int n = 2 * (k + 1);
    const double hs = h / n;
    // Modified midpoint rule with n substeps.
    State z0 = y, z1, fz;
    for (size_t i = 0; i < N; ++i) z1[i] = y[i] + hs * f0[i];
    for (int m = 1; m < n; ++m) {
      rhs(t + m * hs, z1, fz);
      for (size_t i = 0; i < N; ++i) {
        const double z2 = z0[i] + 2.0 * hs * fz[i];
        z0[i] = z1[i];
        z1[i] = z2;
      }
    }
    // Richardson extrapolation in h^2 (Aitken-Neville), in place.
    State above = row[0];  // T(k-1, j-1) as the sweep moves right
    row[0] = z1;
    for (int j = 1; j <= k; ++j) {
      const double ratio = static_cast<double>(n) / (2 * (k - j + 1));
      const double denom = ratio * ratio - 1.0;
      const State next_above = row[j];
      for (size_t i = 0; i < N; ++i) row[j][i] = row[j - 1][i] + (row[j - 1][i] - above[i]) / denom;
      above = next_above;
    }
    if (k >= 1) {
      double err = 0.0, size = 1.0;
      for (size_t i = 0; i < N; ++i) {
        err = std::max(err, std::abs(row[k][i] - row[k - 1][i]));
        size = std::max(size, std::abs(row[k][i]));
      }
      if (!std::isfinite(err)) {
        report->next_h = 0.25 * length;
        return false;
      }
      err_of[k] = err;
      // Rounding bounds what the estimate can show: never ask for less.
      const double tol = std::max(tol_, 4e-16 * size);
      if (err <= tol) {
        result = row[k];
        report->column = k;
        int next = k;
        if (k < target_column_) {
          // Converged sooner than planned: the step could have been longer.
          report->next_h = std::max(h_opt(k), 2.0 * length);
          return true;
        }
        if (k >= 2 && kWork[k - 1] / h_opt(k - 1) < 0.9 * kWork[k] / h_opt(k)) {
          next = k - 1;
        } else if (k == target_column_ && k + 1 < kMaxColumns - 1 &&
                   kWork[k] / h_opt(k) < 0.9 * kWork[k - 1] / h_opt(k - 1)) {
          next = k + 1;
        }
        report->next_h = next == k + 1 ? h_opt(k) * kWork[k + 1] / kWork[k] : h_opt(next);
        target_column_ = std::clamp(next, 2, kMaxColumns - 2);
        return true;
      }
      // Give up early when the error cannot plausibly fall to the tolerance by the
      // last column: one more column gains about (n_{k+1} / n_0)^2.
      if (k == target_column_ && err > tol * std::pow(substeps(k + 1) / substeps(0), 2)) {
        report->next_h = std::clamp(h_opt(k), 0.05 * length, 0.7 * length);
        if (k >= 2 && kWork[k - 1] / h_opt(k - 1) < kWork[k] / h_opt(k))
          target_column_ = std::max(2, k - 1);
        return false;
      }
    }
  }
  report->next_h = std::clamp(h_opt(last), 0.05 * length, 0.7 * length);
  return false;
}

// A slip at a contact, in that contact's tangent plane.
struct PlanarSlip {
  double x = 0.0, y = 0.0;
  double magnitude() const { return vec2::length(x, y); }
};

// What a moving slip asked of the next step.
enum class SlipLimit {
  none,   // nothing: the step stays as planned
  lands,  // the step is cut to land on the slip's predicted zero
  turns,  // the step is cut so that the slip turns by at most kMaxTurn (not an event)
};

// Cuts *step (> 0) for a slip `s` (|s| above the zero threshold) changing at
// (dsx, dsy) per unit t: a slip heading for zero gets there, by a Newton prediction, in
// |s| / rate, of which a landing step covers the fraction `approach` (1, or less where
// landing steps have failed to converge at a zero whose direction is not smooth). A slip
// passing near zero turns through up to half a turn on a scale of its size, so no step
// turns it by more than kMaxTurn - except a young slip (grown from zero, with a direction
// not its own), which turns slowly.
inline SlipLimit limit_step_by_slip(PlanarSlip s, double dsx, double dsy, double approach,
                                    bool young, double* step) {
  SlipLimit limit = SlipLimit::none;
  const double mag = s.magnitude();
  const double rate = (s.x * dsx + s.y * dsy) / mag;
  if (rate < 0.0) {
    const double when = approach * mag / -rate;
    if (when < *step) {
      *step = when;
      limit = SlipLimit::lands;
    }
  }
  const double sideways = std::abs(s.x * dsy - s.y * dsx) / mag;
  if (!young && *step > 0.0 && sideways * *step > kMaxTurn * mag) {
    *step = kMaxTurn * mag / sideways;
    limit = SlipLimit::turns;
  }
  return limit;
}

// Whether a step took a slip from `before` through zero to `after` (ending within the
// zero threshold is a landing, whatever the rounding sign).
inline bool stepped_through(PlanarSlip before, PlanarSlip after, double zero_slip) {
  return after.magnitude() > zero_slip && before.x * after.x + before.y * after.y < 0.0;
}

// Distance in t from t to the end of the impact, where `work_left` = W - W_end has been
// released, from W(t + s) = W - k t s - k s^2 / 2 (dW/dt = -k t, k locally constant).
inline double distance_to_work_end(double t, double work_left, double k) {
  const double disc = t * t + 2.0 * work_left / k;
  return disc > 0.0 ? -t + std::sqrt(disc) : -t;
}

// The end of the impact has been reached: within `landing` in t, or with the work left
// below W's own rounding (near W = W_end one ulp of W can span more than `landing` in t).
inline bool work_end_reached(double distance, double landing, double work, double work_left,
                             double work_end) {
  return std::abs(distance) <= landing ||
         std::abs(work_left) <= 4.0 * kEpsilon * std::max(std::abs(work), std::abs(work_end));
}

enum class EndStep {
  none,        // the end lies beyond the planned step
  lands,       // the step is cut to land on the end
  walks_back,  // the end lies more than a step behind: the step is reversed
};

// Aims the planned *step at the end of the impact `distance` away in t. A landing step
// can overshoot the end; then the next one steps back, a step at a time.
inline EndStep aim_at_work_end(double distance, double* step) {
  if (distance > *step) return EndStep::none;
  if (distance >= -*step) {
    *step = distance;
    return EndStep::lands;
  }
  *step = -*step;
  return EndStep::walks_back;
}

// The next adaptive step size after an accepted step of `step` (not 0): as the
// extrapolation suggested, but never ten times the step taken, and after a step cut
// short by an event no shorter than the size h that was planned.
inline double next_step_size(double h, double suggested, double step, bool cut_by_event) {
  const double capped = std::min(suggested, 10.0 * std::abs(step));
  return cut_by_event ? std::max(h, capped) : capped;
}

}  // namespace cueplan::physics::detail
