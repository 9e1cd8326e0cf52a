// The ways of resolving an impact, behind resolve_impact (private header).
#pragma once

#include "cueplan/physics/cushion_impact.hpp"
#include "impact_model.hpp"

namespace cueplan::physics::detail {

// An impact posed in scaled units (see impact_model.hpp).
struct ScaledImpact {
  Geometry geometry;
  double restitution = 1.0;
  Scaled incoming;      // u_y > 0
  double speed_scale;   // m/s, V
};

// What a method finds, in scaled units; resolve_impact turns it into an ImpactResult.
struct ScaledOutcome {
  ImpactStatus status = ImpactStatus::ok;
  const char* failure = nullptr;  // set with step_limit
  Scaled outgoing;
  double impulse_compression = 0.0;
  double impulse_total = 0.0;
  double work_compression = 0.0;
  double work_total = 0.0;
  bool cushion_slipping_at_start = true;
  bool table_slipping_at_start = true;
  std::array<SlipTransition, kMaxTransitions> transitions{};  // impulses scaled
  int transition_count = 0;
  int rhs_evaluations = 0;

  void add_transition(Contact contact, bool sticking, double impulse) {
    if (transition_count < kMaxTransitions)
      transitions[transition_count++] = {contact, sticking, impulse};
  }
};

// Trace samples are recorded in scaled units and converted by the caller.
ScaledOutcome solve_paper(const ScaledImpact& impact, int steps,
                          std::vector<TraceSample>* trace);
// The extrapolation method (impact_extrapolation.cpp).
ScaledOutcome solve_exact(const ScaledImpact& impact, double tolerance, int max_steps,
                          std::vector<TraceSample>* trace);
// The Taylor method, `exact` (impact_taylor.cpp).
ScaledOutcome solve_taylor(const ScaledImpact& impact, double tolerance, int max_steps,
                           std::vector<TraceSample>* trace);
// Where solve_taylor_batch takes its impacts from, one at a time as lanes free up, and
// where it gives their outcomes back (in the order they end), so that no batch-sized
// buffers are needed.
class BatchImpacts {
 public:
  // The next impact (of the batch's geometry) into *impact, false when none is left;
  // *id names it for done().
  virtual bool next(ScaledImpact* impact, size_t* id) = 0;
  virtual void done(size_t id, const ScaledOutcome& outcome) = 0;

 protected:
  ~BatchImpacts() = default;
};

// The Taylor method on many impacts of one geometry in SIMD lanes
// (impact_taylor_lanes.cpp): each outcome is bit for bit solve_taylor's without a
// trace. lanes: 0 for the widest the CPU has, else 1, 2, 4 or 8 (at most the widest).
void solve_taylor_batch(const Geometry& geometry, double tolerance, int max_steps, int lanes,
                        BatchImpacts& impacts);

// What every impact of a resolve_impact call shares, the parameters and the options,
// checked: the error it gives every impact with them, or none.
Validation check_impact_inputs(const CushionParams& params, const ImpactOptions& options);
// resolve_impact with parameters and options that check_impact_inputs passed, for a
// caller whose impacts all share them (a shot's): the same result, checked once.
ImpactResult resolve_checked_impact(const CushionParams& params, const BallState& incoming,
                                    const ImpactOptions& options);

// The han_2005 model (impact_han.cpp) for checked parameters and a checked incoming state
// (velocity.y > 0): one closed-form impulse, flagged above the rigid-speed limit.
ImpactResult resolve_han_2005(const CushionParams& params, const BallState& incoming);

// The stronge_compliant model (impact_stronge.cpp), likewise: the contact's springs
// integrated in kStrongeSteps steps of its time.
inline constexpr int kStrongeSteps = 160;
ImpactResult resolve_stronge_compliant(const CushionParams& params, const BallState& incoming);

// Fills a trace sample (scaled) from a state and the work so far.
TraceSample scaled_sample(const Geometry& g, const Scaled& q, double impulse, double work);

}  // namespace cueplan::physics::detail
