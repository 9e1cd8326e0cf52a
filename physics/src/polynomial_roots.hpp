// Real roots of low-degree polynomials on an interval (private header).
//
// The polynomial is split at the roots of its derivative (found the same way, one
// degree lower) into monotone pieces; a piece whose ends differ in sign holds exactly
// one root, found to rounding by Newton's method kept inside the bracket (bisection
// where Newton is slow). No root with a sign change is missed, however close two roots
// are; a root without a sign change (a graze) is ignored.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace cueplan::physics::detail {

constexpr int kMaxDegree = 4;

// c[0] + c[1] t + ... + c[degree] t^degree
inline double evaluate(const double* c, int degree, double t) {
  double v = c[degree];
  for (int i = degree - 1; i >= 0; --i) v = v * t + c[i];
  return v;
}

// One root of the polynomial in [a, b] given opposite signs at the ends (fa at a, fb at
// b) on a monotone piece: Newton steps from the secant's root, each kept inside the
// bracket of the signs seen so far; a step that would not move steps to the neighbouring
// double instead, so that the bracket closes. It ends at a double where the polynomial
// is zero or between two neighbouring doubles of opposite signs, as bisection would, in
// about 6 evaluations instead of about 57 (bench/bench_roots.cpp; bench/README.md,
// "Shot"). Where rounding makes the signs near the root disagree (a flat crossing), any
// of the sign changes may be returned: each is a root to rounding. Bisection takes over
// after kNewtonSteps.
inline double bracketed_root(const double* c, int degree, double a, double b, double fa,
                             double fb) {
  constexpr int kNewtonSteps = 12;
  const bool negative_at_a = fa < 0.0;
  double x = a + (b - a) * (fa / (fa - fb));
  for (int i = 0; i < 200; ++i) {
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    if (!(x > a && x < b)) break;  // a and b are neighbours
    const double fx = evaluate(c, degree, x);
    if (fx == 0.0) return x;
    if ((fx < 0.0) == negative_at_a) a = x;
    else b = x;
    if (i >= kNewtonSteps) {
      x = 0.5 * (a + b);
      continue;
    }
    double slope = degree * c[degree];
    for (int k = degree - 1; k >= 1; --k) slope = slope * x + k * c[k];
    const double next = x - fx / slope;
    x = next != x ? next : x == a ? std::nextafter(a, b) : std::nextafter(b, a);
  }
  return 0.5 * (a + b);
}

// Roots in [lo, hi] in ascending order; returns how many were written to out
// (at most `degree`).
inline int roots_in(const double* c, int degree, double lo, double hi, double* out) {
  while (degree > 0 && c[degree] == 0.0) --degree;
  if (degree == 0 || !(lo <= hi)) return 0;
  if (degree == 1) {
    const double r = -c[0] / c[1];
    if (r >= lo && r <= hi) {
      out[0] = r;
      return 1;
    }
    return 0;
  }
  // Monotone pieces between the derivative's roots.
  std::array<double, kMaxDegree> dc{};
  for (int i = 1; i <= degree; ++i) dc[i - 1] = i * c[i];
  std::array<double, kMaxDegree + 1> cuts{};
  int n_cuts = 0;
  cuts[n_cuts++] = lo;
  std::array<double, kMaxDegree> critical{};
  const int n_crit = roots_in(dc.data(), degree - 1, lo, hi, critical.data());
  for (int i = 0; i < n_crit; ++i) cuts[n_cuts++] = critical[i];
  cuts[n_cuts++] = hi;

  int n = 0;
  double f_prev = evaluate(c, degree, cuts[0]);
  if (f_prev == 0.0) out[n++] = cuts[0];
  for (int i = 1; i < n_cuts && n < degree; ++i) {
    const double f = evaluate(c, degree, cuts[i]);
    if (f == 0.0) {
      if (n == 0 || out[n - 1] != cuts[i]) out[n++] = cuts[i];
    } else if (f_prev != 0.0 && (f < 0.0) != (f_prev < 0.0)) {
      out[n++] = bracketed_root(c, degree, cuts[i - 1], cuts[i], f_prev, f);
    }
    f_prev = f;
  }
  return n;
}

// Series polynomials (the Taylor methods' steps): degree below kMaxSeriesTerms.
constexpr int kMaxSeriesTerms = 32;

// K polynomials of one degree at h, the k-th at c + k * stride with its coefficient j
// at c[k * stride + j * J] (J > 1: one lane of a packed series): out[k]. Each is four
// interleaved Horner chains in h^4 (the coefficients of each residue of the power mod
// 4), a quarter of Horner's chain of dependent multiply-adds, held as two SIMD pairs;
// the K polynomials' chains run side by side. Every value is the same IEEE operations
// as the scalar chains', lane by lane.
template <int K, int J = 1>
inline void polys_at(const double* c, int stride, int degree, double h, double* out) {
  typedef double Pair __attribute__((vector_size(16)));
  const double h2 = h * h, h4 = h2 * h2;
  const Pair h4s = {h4, h4};
  const int top = degree / 4;
  const int rest = degree - 4 * top;  // terms above 4 top
  Pair lo[K], hi[K];  // chains 0 and 1, 2 and 3
  for (int k = 0; k < K; ++k) {
    const double* t = c + k * stride + 4 * top * J;
    lo[k] = Pair{t[0], rest >= 1 ? t[J] : 0.0};
    hi[k] = Pair{rest >= 2 ? t[2 * J] : 0.0, rest >= 3 ? t[3 * J] : 0.0};
  }
  for (int i = top - 1; i >= 0; --i) {
    for (int k = 0; k < K; ++k) {
      const double* t = c + k * stride + 4 * i * J;
      Pair a, b;
      if constexpr (J == 1) {
        __builtin_memcpy(&a, t, sizeof a);
        __builtin_memcpy(&b, t + 2, sizeof b);
      } else {
        a = Pair{t[0], t[J]};
        b = Pair{t[2 * J], t[3 * J]};
      }
      lo[k] = lo[k] * h4s + a;
      hi[k] = hi[k] * h4s + b;
    }
  }
  for (int k = 0; k < K; ++k) out[k] = (lo[k][0] + h * lo[k][1]) + h2 * (hi[k][0] + h * hi[k][1]);
}

// The polynomial c[0..degree] at h (its coefficient j at c[j * J]).
template <int J = 1>
inline double poly_at(const double* c, int degree, double h) {
  double v;
  polys_at<1, J>(c, 0, degree, h, &v);
  return v;
}

// A root in (0, h] of the polynomial c with c(0) > 0 >= c(h), to 1e-15 of h (the
// state moves by less than that fraction of the step): Newton steps kept inside the
// bracket, the secant of the bracket where they leave it.
inline double root_in(const double* c, int degree, double h) {
  double slope_c[kMaxSeriesTerms];
  for (int j = 1; j <= degree; ++j) slope_c[j - 1] = j * c[j];
  double lo = 0.0, hi = h, f_lo = c[0], f_hi = poly_at(c, degree, h);
  if (!(f_hi < f_lo)) return hi;
  double x = hi * f_lo / (f_lo - f_hi);
  const double enough = 1e-15 * h;
  for (int iter = 0; iter < 60; ++iter) {
    const double f = poly_at(c, degree, x);
    if (f == 0.0) return x;
    if (f > 0.0) {
      lo = x;
      f_lo = f;
    } else {
      hi = x;
      f_hi = f;
    }
    double next = x - f / poly_at(slope_c, degree - 1, x);
    if (std::abs(next - x) <= enough) return std::clamp(next, lo, hi);
    if (!(next > lo && next < hi)) next = lo + (hi - lo) * f_lo / (f_lo - f_hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= enough) return next;
    x = next;
  }
  return hi;
}

}  // namespace cueplan::physics::detail
