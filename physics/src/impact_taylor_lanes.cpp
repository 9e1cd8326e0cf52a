// Independent impacts side by side in SIMD lanes (resolve_impacts with the exact method).
//
// Each lane holds one impact's integrator. In every round each lane plans its next
// step; the lanes whose step is of the commonest kind (both contacts slipping, in
// tau) get their series from one call of the vector kernel, the others take their
// step alone with the general kernel, exactly as resolve_impact would. A lane whose
// impact has ended takes the next one of the batch. The vector kernel is the scalar
// kernel's template (impact_taylor_series.hpp) on a GCC vector type, built for the
// instruction set found at run time: SSE2 (2 lanes, every x86-64 CPU), AVX2 (4) or
// AVX-512 (8). No fused multiply-adds anywhere (-ffp-contract=off), so a lane's
// results are bit for bit the scalar path's.
#include <algorithm>
#include <optional>

// Vectors of doubles pass between the kernels' inlined helpers only.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "impact_taylor.hpp"

namespace cueplan::physics::detail {
namespace taylor {
namespace {

typedef double Pack2 __attribute__((vector_size(16)));
typedef double Pack4 __attribute__((vector_size(32)));
typedef double Pack8 __attribute__((vector_size(64)));

// The fast kernels on several impacts at once: a lane of each SIMD vector is one impact.
template <class Pack>
using LaneKernel = void (*)(const Constants&, int, Coefficients<Pack>&);

void tau_lanes_sse2(const Constants& k, int n, Coefficients<Pack2>& s) {
  series_tau<Pack2, QuadOf<Pack2>>(k, n, s);
}
void sigma_lanes_sse2(const Constants& k, int n, Coefficients<Pack2>& s) {
  series_sigma<Pack2, QuadOf<Pack2>>(k, n, s);
}
__attribute__((target("avx2"))) void tau_lanes_avx2(const Constants& k, int n,
                                                    Coefficients<Pack4>& s) {
  series_tau<Pack4, QuadOf<Pack4>>(k, n, s);
}
__attribute__((target("avx2"))) void sigma_lanes_avx2(const Constants& k, int n,
                                                      Coefficients<Pack4>& s) {
  series_sigma<Pack4, QuadOf<Pack4>>(k, n, s);
}
__attribute__((target("avx512f"))) void tau_lanes_avx512(const Constants& k, int n,
                                                         Coefficients<Pack8>& s) {
  series_tau<Pack8, QuadOf<Pack8>>(k, n, s);
}
__attribute__((target("avx512f"))) void sigma_lanes_avx512(const Constants& k, int n,
                                                           Coefficients<Pack8>& s) {
  series_sigma<Pack8, QuadOf<Pack8>>(k, n, s);
}

template <int L, class Pack, LaneKernel<Pack> Tau, LaneKernel<Pack> Sigma>
void run_lanes(const Constants& constants, const Settings& settings, BatchImpacts& impacts) {
  std::optional<Integrator> lane[L];
  ScaledOutcome outcome[L];
  size_t id[L] = {};
  auto load = [&](int i) {
    ScaledImpact impact;
    if (impacts.next(&impact, &id[i]))
      lane[i].emplace(impact, constants, settings, nullptr, &outcome[i]);
    else
      lane[i].reset();
  };
  for (int i = 0; i < L; ++i) load(i);

  const int n = settings.order;
  Coefficients<Pack> packed;
  Coefficients<double> single;
  Kernel kinds[L];
  for (;;) {
    bool any = false;
    for (int i = 0; i < L; ++i) {
      kinds[i] = Kernel::general;
      while (lane[i] && lane[i]->done()) {
        lane[i]->finish();
        impacts.done(id[i], outcome[i]);
        load(i);
      }
      if (!lane[i]) continue;
      any = true;
      kinds[i] = lane[i]->plan_step();
      if (kinds[i] == Kernel::general) lane[i]->take_planned_step();
    }
    if (!any) break;
    // One vector call for the lanes of each fast kernel (idle lanes repeat a busy
    // one's state: same work, nothing read back) - or, for fewer than a quarter of
    // the lanes, the one-impact kernel each: cheaper than a mostly idle vector.
    for (Kernel kind : {Kernel::tau, Kernel::sigma}) {
      int first = -1, busy = 0;
      for (int i = 0; i < L; ++i) busy += kinds[i] == kind;
      if (busy == 0) continue;
      if (4 * busy < L) {
        for (int i = 0; i < L; ++i) {
          if (kinds[i] != kind) continue;
          const double* q = lane[i]->state();
          for (int c = 0; c < kState; ++c) single.c[c][0] = q[c];
          fast_series(kind, constants, n, single);
          lane[i]->finish_fast_step(single);
        }
        continue;
      }
      for (int i = 0; i < L; ++i)
        if (kinds[i] == kind) {
          if (first < 0) first = i;
          const double* q = lane[i]->state();
          for (int c = 0; c < kState; ++c) packed.c[c][0][i] = q[c];
        }
      for (int i = 0; i < L; ++i)
        if (kinds[i] != kind)
          for (int c = 0; c < kState; ++c) packed.c[c][0][i] = packed.c[c][0][first];
      (kind == Kernel::tau ? Tau : Sigma)(constants, n, packed);
      for (int i = 0; i < L; ++i) {
        if (kinds[i] != kind) continue;
        for (int c = 0; c < kState; ++c)
          for (int j = 0; j <= n + 1; ++j) single.c[c][j] = packed.c[c][j][i];
        lane[i]->finish_fast_step(single);
      }
    }
  }
}

void run_scalar(const Constants& constants, const Settings& settings, BatchImpacts& impacts) {
  ScaledImpact impact;
  size_t id = 0;
  while (impacts.next(&impact, &id)) {
    ScaledOutcome outcome;
    Integrator it(impact, constants, settings, nullptr, &outcome);
    it.run();
    impacts.done(id, outcome);
  }
}

}  // namespace

int widest_lanes() {
  if (__builtin_cpu_supports("avx512f")) return 8;
  if (__builtin_cpu_supports("avx2")) return 4;
  return 2;
}

}  // namespace taylor

void solve_taylor_batch(const Geometry& geometry, double tolerance, int max_steps, int lanes,
                        BatchImpacts& impacts) {
  const taylor::Constants constants = taylor::Constants::from(geometry);
  const taylor::Settings settings = taylor::Settings::from(tolerance, max_steps);
  const int widest = taylor::widest_lanes();
  const int use = lanes == 0 ? widest : std::min(lanes, widest);
  switch (use) {
    case 1:
      taylor::run_scalar(constants, settings, impacts);
      break;
    case 2:
      taylor::run_lanes<2, taylor::Pack2, taylor::tau_lanes_sse2, taylor::sigma_lanes_sse2>(
          constants, settings, impacts);
      break;
    case 4:
      taylor::run_lanes<4, taylor::Pack4, taylor::tau_lanes_avx2, taylor::sigma_lanes_avx2>(
          constants, settings, impacts);
      break;
    default:
      taylor::run_lanes<8, taylor::Pack8, taylor::tau_lanes_avx512, taylor::sigma_lanes_avx512>(
          constants, settings, impacts);
      break;
  }
}

}  // namespace cueplan::physics::detail
