// The impact domain of the stress runs, drawn at random: the paper's form (V0, alpha,
// k_T, k_S) and general spin vectors, V0 from 1e-6 to 20 m/s, alpha from 1e-6 to
// 180 - 1e-6 deg, |k| up to 20, starts with zero slip at a contact, and parameters at
// their limits (mu = 0, e = 1, friction at the edge of validity, extreme cushion
// heights, other radii and masses). Shared by tests/stress/impact_stress.cpp and the
// unit tests that check the exact methods over the same domain.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::physics::test {

class Sampler {
 public:
  explicit Sampler(uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  template <size_t N>
  double pick(const std::array<double, N>& values) {
    return values[std::uniform_int_distribution<size_t>(0, N - 1)(rng_)];
  }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  // The domain's speeds, incidences and spins, landing on an edge one time in eight.
  double speed() {
    return chance(0.125) ? pick(std::array{1e-6, 20.0, 2.5, 1e-3}) : log_uniform(1e-6, 20.0);
  }
  double alpha() {
    return chance(0.125) ? pick(std::array{1e-6, 180.0 - 1e-6, 90.0, 90.0 - 1e-6, 90.0 + 1e-6, 1e-3,
                                           180.0 - 1e-3, 0.5, 179.5})
                         : uniform(1e-6, 180.0 - 1e-6);
  }
  double spin_k() {
    return chance(0.125) ? pick(std::array{-20.0, 20.0, 0.0, 1.0, -1.0, 1e-9, -1e-9})
                         : uniform(-20.0, 20.0);
  }

 private:
  std::mt19937_64 rng_;
};

// Parameters that pass validate(): friction shrunk toward zero until they do.
inline void make_valid(CushionParams* p) {
  for (int i = 0; i < 200 && p->validate(); ++i) {
    p->mu_table *= 0.7;
    p->mu_cushion *= 0.7;
  }
  if (p->validate()) p->mu_table = p->mu_cushion = 0.0;
}

inline CushionParams draw_params(Sampler& s, std::string* kind) {
  CushionParams p;
  const int k = s.index(10);
  switch (k) {
    case 0:
    case 1:
    case 2:
    case 3:
      *kind = "snooker";
      break;
    case 4:
      *kind = "frictionless";
      p.mu_cushion = p.mu_table = 0.0;
      break;
    case 5:
      *kind = s.chance(0.5) ? "mu_w=0" : "mu_s=0";
      (*kind == "mu_w=0" ? p.mu_cushion : p.mu_table) = 0.0;
      break;
    case 6:
      *kind = "e=1";
      p.restitution = 1.0;
      if (s.chance(0.5)) {
        *kind = "e=1, frictionless";
        p.mu_cushion = p.mu_table = 0.0;
      }
      break;
    case 7:
      *kind = "tiny e";
      p.restitution = s.chance(0.5) ? 1e-6 : s.log_uniform(1e-6, 0.1);
      break;
    case 8: {
      // Friction at the edge of validity: mu_w just below tan(theta), mu_s as large as
      // validate() allows with it.
      *kind = "large mu";
      const double tan_theta = p.sin_theta() / p.cos_theta();
      p.mu_cushion = tan_theta * (1.0 - s.log_uniform(1e-9, 0.1));
      p.mu_table = s.log_uniform(0.2, 10.0);
      make_valid(&p);
      break;
    }
    default: {
      // Everything random: other radii and masses, cushion heights from just above
      // the equator to just below the top, any friction and restitution.
      *kind = "random";
      p.radius = s.log_uniform(1e-3, 0.1);
      p.mass = s.log_uniform(1e-3, 10.0);
      const double h =
          s.chance(0.2) ? s.pick(std::array{1e-6, 1.0 - 1e-6, 1e-3, 0.999}) : s.uniform(0.05, 0.95);
      p.cushion_height = p.radius * (1.0 + h);
      const double tan_theta = p.sin_theta() / p.cos_theta();
      p.mu_cushion = s.uniform(0.0, 1.0) * tan_theta;
      p.mu_table = s.uniform(0.0, 1.0);
      p.restitution = s.chance(0.1) ? 1.0 : s.uniform(1e-6, 1.0);
      make_valid(&p);
      break;
    }
  }
  return p;
}

inline BallState draw_state(Sampler& s, const CushionParams& p, std::string* kind) {
  const double v0 = s.speed(), alpha = s.alpha();
  const int k = s.index(10);
  if (k < 6) {
    *kind = "paper form";
    return incoming_state_k(v0, alpha, s.spin_k(), s.spin_k(), p.radius);
  }
  BallState b = incoming_state(v0, alpha, 0.0, 0.0);
  const double unit = v0 / p.radius;  // spin of R w = V0
  const double sth = p.sin_theta(), cth = p.cos_theta();
  if (k < 9) {
    *kind = "general spin";
    b.spin = {s.spin_k() * unit, s.spin_k() * unit, s.spin_k() * unit};
  } else if (s.chance(0.5)) {
    // No slip at the cloth: x_C = v_x - w_y R = 0, y_C = v_y + w_x R = 0.
    *kind = "zero slip at cloth";
    b.spin = {-b.velocity.y / p.radius, b.velocity.x / p.radius, s.spin_k() * unit};
  } else {
    // No slip at the cushion: y_I' = -v_y sin(th) + w_x R = 0 and
    // x_I = v_x + w_y R sin(th) - w_z R cos(th) = 0.
    *kind = "zero slip at cushion";
    const double wy = s.spin_k() * unit;
    b.spin = {b.velocity.y * sth / p.radius, wy,
              (b.velocity.x + wy * p.radius * sth) / (p.radius * cth)};
  }
  return b;
}

}  // namespace cueplan::physics::test
