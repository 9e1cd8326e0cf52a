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

#include "impact_taylor.hpp"

namespace cueplan::physics::detail {
namespace taylor {
namespace {

typedef double Pack2 __attribute__((vector_size(16)));
typedef double Pack4 __attribute__((vector_size(32)));
typedef double Pack8 __attribute__((vector_size(64)));

void kernel_sse2(const Constants& k, int n, Coefficients<Pack2>& s) { slip_slip_tau(k, n, s); }

__attribute__((target("avx2"))) void kernel_avx2(const Constants& k, int n,
                                                 Coefficients<Pack4>& s) {
  slip_slip_tau(k, n, s);
}

__attribute__((target("avx512f"))) void kernel_avx512(const Constants& k, int n,
                                                      Coefficients<Pack8>& s) {
  slip_slip_tau(k, n, s);
}

template <int L, class Pack, void (*Kernel)(const Constants&, int, Coefficients<Pack>&)>
void run_lanes(const Constants& constants, const Settings& settings, const ScaledImpact* impacts,
               size_t count, ScaledOutcome* out) {
  std::optional<Integrator> lane[L];
  size_t next = 0;
  auto load = [&](std::optional<Integrator>& it) {
    if (next < count) {
      it.emplace(impacts[next], constants, settings, nullptr, &out[next]);
      ++next;
    } else {
      it.reset();
    }
  };
  for (auto& it : lane) load(it);

  const int n = settings.order;
  Coefficients<Pack> packed;
  Coefficients<double> single;
  bool fast[L];
  for (;;) {
    bool any = false;
    int first_fast = -1;
    for (int i = 0; i < L; ++i) {
      fast[i] = false;
      while (lane[i] && lane[i]->done()) {
        lane[i]->finish();
        load(lane[i]);
      }
      if (!lane[i]) continue;
      any = true;
      if (lane[i]->plan_step()) {
        fast[i] = true;
        if (first_fast < 0) first_fast = i;
        const double* q = lane[i]->state();
        for (int c = 0; c < kState; ++c) packed.c[c][0][i] = q[c];
      } else {
        lane[i]->take_planned_step();
      }
    }
    if (!any) break;
    if (first_fast < 0) continue;
    // Idle lanes repeat a busy one's state: same work, nothing read back.
    for (int i = 0; i < L; ++i)
      if (!fast[i])
        for (int c = 0; c < kState; ++c) packed.c[c][0][i] = packed.c[c][0][first_fast];
    Kernel(constants, n, packed);
    for (int i = 0; i < L; ++i) {
      if (!fast[i]) continue;
      for (int c = 0; c < kState; ++c)
        for (int j = 0; j <= n + 1; ++j) single.c[c][j] = packed.c[c][j][i];
      lane[i]->finish_fast_step(single);
    }
  }
}

void run_scalar(const Constants& constants, const Settings& settings, const ScaledImpact* impacts,
                size_t count, ScaledOutcome* out) {
  for (size_t i = 0; i < count; ++i) {
    Integrator it(impacts[i], constants, settings, nullptr, &out[i]);
    it.run();
  }
}

}  // namespace

int widest_lanes() {
  if (__builtin_cpu_supports("avx512f")) return 8;
  if (__builtin_cpu_supports("avx2")) return 4;
  return 2;
}

}  // namespace taylor

void solve_taylor_batch(const ScaledImpact* impacts, size_t count, double tolerance,
                        int max_steps, int lanes, ScaledOutcome* out) {
  if (count == 0) return;
  // Every impact of a batch shares the geometry (one CushionParams).
  const taylor::Constants constants = taylor::Constants::from(impacts[0].geometry);
  const taylor::Settings settings = taylor::Settings::from(tolerance, max_steps);
  const int widest = taylor::widest_lanes();
  const int use = lanes == 0 ? widest : std::min(lanes, widest);
  switch (use) {
    case 1:
      taylor::run_scalar(constants, settings, impacts, count, out);
      break;
    case 2:
      taylor::run_lanes<2, taylor::Pack2, taylor::kernel_sse2>(constants, settings, impacts, count,
                                                               out);
      break;
    case 4:
      taylor::run_lanes<4, taylor::Pack4, taylor::kernel_avx2>(constants, settings, impacts, count,
                                                               out);
      break;
    default:
      taylor::run_lanes<8, taylor::Pack8, taylor::kernel_avx512>(constants, settings, impacts,
                                                                 count, out);
      break;
  }
}

}  // namespace cueplan::physics::detail
