// Independent impacts side by side in SIMD lanes (resolve_impacts with the exact method).
//
// Each impact in flight has its own integrator. Its fast steps (both contacts
// slipping, in tau or in sigma) get their series from vector calls of the fast
// kernels, one impact per lane, its other steps are taken alone with the general
// kernel, exactly as resolve_impact would; an impact that has ended makes room for the
// next one of the batch (run_lanes below). The vector kernel is the scalar
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

// The lanes' states at their steps' lengths h (a lane each): polys_at's four Horner
// chains in h^4 per series, lane by lane the same operations. (The vectors pass by
// reference: by value their ABI differs between builds for different instruction sets.)
template <class Pack>
[[gnu::always_inline]] inline void states_at(const Coefficients<Pack>& s, int degree,
                                             const Pack& hs, Pack out[kState]) {
  const Pack h = hs, h2 = h * h, h4 = h2 * h2;
  const int top = degree / 4;
  const int rest = degree - 4 * top;
  for (int q = 0; q < kState; ++q) {
    const Pack* t = s.c[q] + 4 * top;
    const Pack zero{};
    Pack c0 = t[0], c1 = rest >= 1 ? t[1] : zero, c2 = rest >= 2 ? t[2] : zero,
         c3 = rest >= 3 ? t[3] : zero;
    for (int i = top - 1; i >= 0; --i) {
      c0 = c0 * h4 + s.c[q][4 * i];
      c1 = c1 * h4 + s.c[q][4 * i + 1];
      c2 = c2 * h4 + s.c[q][4 * i + 2];
      c3 = c3 * h4 + s.c[q][4 * i + 3];
    }
    out[q] = (c0 + h * c1) + h2 * (c2 + h * c3);
  }
}
template <class Pack>
using LaneStates = void (*)(const Coefficients<Pack>&, int, const Pack&, Pack*);
void states_sse2(const Coefficients<Pack2>& s, int d, const Pack2& h, Pack2* out) {
  states_at(s, d, h, out);
}
__attribute__((target("avx2"))) void states_avx2(const Coefficients<Pack4>& s, int d,
                                                 const Pack4& h, Pack4* out) {
  states_at(s, d, h, out);
}
__attribute__((target("avx512f"))) void states_avx512(const Coefficients<Pack8>& s, int d,
                                                      const Pack8& h, Pack8* out) {
  states_at(s, d, h, out);
}

// Twice as many impacts in flight as lanes: each is taken up to its next fast step
// (general steps at once, an ended impact replaced by the batch's next), then the kind
// with more impacts waiting fills a vector call, up to L of them; the others wait. With
// 2L impacts in flight one kind always has L waiting until the batch runs dry, so the
// vector calls are full (a lane holding a step of the other kind no longer idles).
template <int L, class Pack, LaneKernel<Pack> Tau, LaneKernel<Pack> Sigma,
          LaneStates<Pack> States>
void run_lanes(const Constants& constants, const Settings& settings, BatchImpacts& impacts) {
  constexpr int kFlight = 2 * L;
  std::optional<Integrator> flight[kFlight];
  ScaledOutcome outcome[kFlight];
  size_t id[kFlight] = {};
  Kernel kind[kFlight];
  bool waiting[kFlight] = {};
  auto load = [&](int i) {
    ScaledImpact impact;
    if (impacts.next(&impact, &id[i]))
      flight[i].emplace(impact, constants, settings, nullptr, &outcome[i]);
    else
      flight[i].reset();
  };
  for (int i = 0; i < kFlight; ++i) load(i);

  const int n = settings.order;
  Coefficients<Pack> packed;
  Coefficients<double> single;
  for (;;) {
    int count[2] = {0, 0};  // waiting for tau, for sigma
    for (int i = 0; i < kFlight; ++i) {
      while (!waiting[i] && flight[i]) {
        if (flight[i]->done()) {
          flight[i]->finish();
          impacts.done(id[i], outcome[i]);
          load(i);
          continue;
        }
        kind[i] = flight[i]->plan_step();
        if (kind[i] == Kernel::general)
          flight[i]->take_planned_step();
        else
          waiting[i] = true;
      }
      if (waiting[i]) ++count[kind[i] == Kernel::tau ? 0 : 1];
    }
    if (count[0] + count[1] == 0) break;
    const Kernel run = count[0] >= count[1] ? Kernel::tau : Kernel::sigma;
    int lane_of[L], busy = 0;
    for (int i = 0; i < kFlight && busy < L; ++i)
      if (waiting[i] && kind[i] == run) lane_of[busy++] = i;
    // Fewer than a quarter of the lanes: the one-impact kernel each, cheaper than a
    // mostly idle vector.
    if (4 * busy < L) {
      for (int b = 0; b < busy; ++b) {
        const int i = lane_of[b];
        const double* q = flight[i]->state();
        for (int c = 0; c < kState; ++c) single.c[c][0] = q[c];
        fast_series(run, constants, n, single);
        flight[i]->finish_fast_step(single);
        waiting[i] = false;
      }
      continue;
    }
    // Idle lanes repeat a busy one's state: same work, nothing read back.
    for (int l = 0; l < L; ++l) {
      const double* q = flight[lane_of[l < busy ? l : 0]]->state();
      for (int c = 0; c < kState; ++c) packed.c[c][0][l] = q[c];
    }
    (run == Kernel::tau ? Tau : Sigma)(constants, n, packed);
    // Each lane's series read where the vector call wrote it; the states at the steps'
    // lengths in one vector pass (idle lanes: any length).
    const double* lanes = reinterpret_cast<const double*>(&packed);
    Pack h{};
    for (int b = 0; b < busy; ++b)
      h[b] = flight[lane_of[b]]->fast_step_length(SeriesView<L>{lanes + b});
    Pack at_h[kState];
    States(packed, n + 1, h, at_h);
    for (int b = 0; b < busy; ++b) {
      const int i = lane_of[b];
      double q[kState];
      for (int c = 0; c < kState; ++c) q[c] = at_h[c][b];
      flight[i]->finish_fast_step(SeriesView<L>{lanes + b}, h[b], q);
      waiting[i] = false;
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
  const KernelIsa isa = widest_isa();
  if (isa == KernelIsa::avx512 && __builtin_cpu_supports("avx512f")) return 8;
  if (isa != KernelIsa::sse2) return 4;
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
      taylor::run_lanes<2, taylor::Pack2, taylor::tau_lanes_sse2, taylor::sigma_lanes_sse2,
                          taylor::states_sse2>(
          constants, settings, impacts);
      break;
    case 4:
      taylor::run_lanes<4, taylor::Pack4, taylor::tau_lanes_avx2, taylor::sigma_lanes_avx2,
                          taylor::states_avx2>(
          constants, settings, impacts);
      break;
    default:
      taylor::run_lanes<8, taylor::Pack8, taylor::tau_lanes_avx512,
                          taylor::sigma_lanes_avx512, taylor::states_avx512>(
          constants, settings, impacts);
      break;
  }
}

}  // namespace cueplan::physics::detail
