// Ball-cushion impact of Mathavan, Jackson & Parkin (2010), as fixed by
// shared/PHYSICS.md: a ball with any spin meets a rigid cushion whose nose touches
// it above its equator; it slips (or sticks) at the cushion and at the cloth while
// the cushion's normal impulse P_I grows, and leaves with a new velocity and spin.
// A second model, Han (2005), resolves the same contact in closed form with one
// impulse (docs/cushion_models.md); CushionParams::model chooses between them.
//
// Everything here is a pure function of its arguments: no globals, no hidden state,
// safe to call from many threads at once.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cueplan/physics/validation.hpp"
#include "cueplan/physics/vec3.hpp"

namespace cueplan::physics {

class ImpactTable;

// The model that resolves a ball-cushion contact (docs/cushion_models.md).
enum class CushionModel {
  mathavan_2010,  // friction at the cushion and the cloth over the normal impulse (default)
  han_2005,       // one impulse at the cushion contact, closed form, no cloth friction
  stronge_compliant,  // normal and tangential springs at the cushion contact (Stronge),
                      // no cloth friction; integrated over the contact's time
};

const char* to_string(CushionModel model);
// Parses "mathavan_2010", "han_2005" or "stronge_compliant"; returns false (leaving *model alone) otherwise.
bool parse_cushion_model(const std::string& name, CushionModel* model);

// Fixed parameters of the impact. SI units; defaults are the paper's snooker values.
struct CushionParams {
  double mass = 0.1406;             // kg
  double radius = 0.02625;          // m
  double cushion_height = 0.03675;  // m, contact height above the cloth (h = 7R/5)
  double mu_cushion = 0.14;         // ball-cushion sliding friction mu_w
  double mu_table = 0.212;          // ball-cloth sliding friction mu_s
  double restitution = 0.98;        // energetic coefficient of restitution e_e, (0, 1]
  double rigid_speed_limit = 2.5;   // m/s; normal speeds above it are flagged
  // Which model resolves the impact. han_2005 uses mass, radius, cushion_height,
  // mu_cushion (Han's mu) and restitution (Han's e, Newton's restitution of the normal
  // velocity at the contact); mu_table plays no part in its impact.
  CushionModel model = CushionModel::mathavan_2010;
  // stronge_compliant only: eta^2, the normal contact stiffness over the tangential
  // (Stronge's eta^2); with a sphere's effective masses the tangential spring vibrates
  // sqrt(3.5 / eta^2) times as fast as the normal one, which Stronge's analysis takes
  // between 1 and 2. Default 1.5: Mindlin's (2 - nu) / (2 (1 - nu)) for rubber, nu = 0.5.
  // stronge_compliant uses the parameters as han_2005 does, and this.
  double eta_squared = 1.5;

  // Elevation of the contact normal: sin(theta) = (h - R) / R.
  double sin_theta() const { return (cushion_height - radius) / radius; }
  double cos_theta() const;

  // Empty when usable; otherwise the first broken rule, fields named as the members here.
  // The rules on mu_cushion and mu_table that keep Mathavan's integration well posed
  // apply to mathavan_2010; han_2005 and stronge_compliant instead need
  // (1 + restitution) cos(theta) (cos(theta) - mu_cushion sin(theta)) > 1, or a ball
  // could leave its impulse still moving into the cushion; stronge_compliant also
  // 0.875 < eta_squared < 3.5.
  Validation validate() const;
};

// Snooker defaults with the cushion height kept at 7R/5 of the given radius.
CushionParams params_for_radius(double radius);

// Ball state in the cushion frame: X along the cushion, Y from the ball into the
// cushion, Z up. velocity.z must be zero (the ball stays on the cloth).
struct BallState {
  Vec3 velocity;  // m/s, centre of the ball
  Vec3 spin;      // rad/s
};

// Section 3.1: speed V0 (m/s) at incidence alpha (deg, 0 < alpha < 180, 90 head-on),
// topspin w_T and sidespin w_S (rad/s; w_T = V0/R is natural roll, w_S > 0 right).
BallState incoming_state(double speed, double alpha_deg, double topspin, double sidespin);

// The same with the paper's dimensionless spins k_T = w_T R / V0, k_S = w_S R / V0.
BallState incoming_state_k(double speed, double alpha_deg, double topspin_k,
                           double sidespin_k, double radius);

// Translational plus rotational kinetic energy (J) of a solid ball.
double kinetic_energy(const CushionParams& params, const BallState& state);

enum class ImpactMethod {
  exact,          // Taylor-series integrator with events (default)
  extrapolation,  // Gragg-Bulirsch-Stoer extrapolation with events: a second exact method
  paper,          // the paper's fixed-step scheme in P_I (section 3.4)
  table,          // precomputed surrogate over (alpha, k_T, k_S); see impact_table.hpp
  closed_form,    // not a choice: what resolves every impact of the han_2005 model. The
                  // methods above are Mathavan's; with han_2005 they are ignored.
};

enum class ImpactStatus {
  ok,
  rigid_limit_exceeded,  // solved, but the normal speed is above rigid_speed_limit
  invalid_input,         // nothing solved; message names the field
  step_limit,            // the integrator's work bound was reached; result unusable
};

const char* to_string(ImpactMethod method);
const char* to_string(ImpactStatus status);
// Parses "exact", "extrapolation", "paper" or "table"; returns false for anything else
// (closed_form too: it follows from the model, it is not asked for).
bool parse_method(const std::string& name, ImpactMethod* method);

// True when a result's outgoing state can be used (ok or only flagged).
inline bool usable(ImpactStatus status) {
  return status == ImpactStatus::ok || status == ImpactStatus::rigid_limit_exceeded;
}

enum class Contact : unsigned char { cushion, table };
const char* to_string(Contact contact);

// A change of slip state at one contact.
struct SlipTransition {
  Contact contact = Contact::cushion;
  bool sticking = false;  // true: the slip reached zero and the contact holds
  double impulse = 0.0;   // N s, cushion normal impulse P_I at the change
};

// One point of the slip history, for plots such as the paper's figure 12.
struct TraceSample {
  double impulse = 0.0;          // N s, P_I
  double slip_cushion = 0.0;     // m/s, s at I
  double phi_cushion_deg = 0.0;  // direction of the slip at I from X
  double slip_table = 0.0;       // m/s, s' at C
  double phi_table_deg = 0.0;    // direction of the slip at C from X
  double work = 0.0;             // J, W at I along its normal
  BallState state;
};

struct ImpactOptions {
  ImpactMethod method = ImpactMethod::exact;
  int paper_steps = 5000;     // paper: N, with dP_I = (1 + e) M V0 sin(alpha) / N
  double tolerance = 1e-12;   // exact, extrapolation: local error per step, relative to
                              // the speed scale
  int max_steps = 10000;      // exact, extrapolation: work bound on steps (extrapolation:
                              // accepted plus rejected; a slide lingering near zero slip
                              // needs more than 2000, cushion_impact_test.cpp,
                              // LongSlideNearZeroSlip...)
  const ImpactTable* table = nullptr;    // table: the surrogate (required)
  // table: the exact method's tolerance for the impacts the table does not answer;
  // 0 matches it to the table's accuracy (ImpactTable::fallback_tolerance()).
  double table_fallback_tolerance = 0.0;
  std::vector<TraceSample>* trace = nullptr;  // optional slip history (exact,
                                              // extrapolation, paper; not in batches)
  // resolve_impacts with the exact method: impacts side by side in SIMD lanes, 0 for
  // the widest the CPU has (8 with AVX-512, 4 with AVX2, else 2 with SSE2), or 1, 2, 4
  // or 8 (a width the CPU lacks falls back to the widest it has). Results do not
  // depend on it: every lane computes bit for bit what resolve_impact computes.
  int batch_lanes = 0;

  // Empty when every field is in range (those of the other methods too); otherwise the
  // first broken rule, fields named as these members. (resolve_impact also needs a
  // table for method table.)
  Validation validate() const;
};

constexpr int kMaxTransitions = 16;

struct ImpactResult {
  ImpactStatus status = ImpactStatus::invalid_input;
  std::string message;  // why, when the status is not ok
  // invalid_input: the broken rule; fields named as CushionParams' members, the
  // incoming state's ({"velocity", "y"}, {"spin", "z"}) and ImpactOptions' members.
  std::optional<ValidationError> error;
  CushionModel model = CushionModel::mathavan_2010;  // the model that resolved it
  ImpactMethod method_used = ImpactMethod::exact;    // closed_form for han_2005

  BallState outgoing;              // cushion frame, same units as the input
  double rebound_speed = 0.0;      // m/s, |(vx, vy)| after the impact
  double rebound_angle_deg = 0.0;  // from +X like alpha: mirror reflection gives beta = alpha
  // han_2005: the normal impulse along the contact normal, P_zE / (1 + e) and P_zE;
  // the work terms are Mathavan's only (0).
  double impulse_compression = 0.0;  // N s, P_I when the normal approach stops (eq. 16c)
  double impulse_total = 0.0;        // N s, P_I when W = (1 - e^2) W_c (eq. 16b)
  double work_compression = 0.0;     // J, W_c
  double work_total = 0.0;           // J, W at the end of the impact

  bool cushion_slipping_at_start = true;
  bool table_slipping_at_start = true;
  std::array<SlipTransition, kMaxTransitions> transitions{};
  int transition_count = 0;

  // The work the method did: right-hand side calls (extrapolation, paper), or series
  // orders computed (exact: each costs about one right-hand side call).
  int rhs_evaluations = 0;
};

// Resolves one impact with params.model. Never throws for bad numbers: invalid input
// comes back as status invalid_input with a message naming the field. With han_2005 the
// options' method, table and trace are ignored (the impact is one closed-form impulse;
// no slip history is recorded) and method_used is closed_form.
ImpactResult resolve_impact(const CushionParams& params, const BallState& incoming,
                            const ImpactOptions& options = {});

// Resolves in.size() independent impacts with the same parameters and options:
// out[i] is bit for bit resolve_impact(params, in[i], options). With the exact method
// (alone or for the table's fallbacks) the impacts run side by side in SIMD lanes
// (options.batch_lanes), chosen at run time for the CPU. Single-threaded: to use
// several threads, give each a part of the batch. When out.size() differs from
// in.size(), every element of out gets invalid_input with a message naming `out`.
// options.trace must be null (a batch records no slip histories).
void resolve_impacts(const CushionParams& params, std::span<const BallState> in,
                     std::span<ImpactResult> out, const ImpactOptions& options = {});

}  // namespace cueplan::physics
