#pragma once
// The step's stability at the states a run passes through, not only where the scene settles.
// A run can blow up below the limit at rest, in a stiffer state on its way (the trampoline's
// tethers catching the net, a landing's squash), or in the state the blow-up itself made; a
// calm run (the scene again from its start, at half the dt in question) passes through the
// first and not the second. The blow-up message asks it what dt would have run; the stability
// chart asks it where its trials failed.
#include <cmath>

#include "springlab/simulation.hpp"
#include "springlab/step_stability.hpp"

namespace springlab {

// The step's limit (stepStableDt with `options`) and its spectral radius at dt, computed inside
// a run (from the blow-up check's own check()) and leaving the run as it found it
// (Simulation::saveRun: the state, the lab's data, the check's watch); NaN where they cannot be
// computed (a radius also where the step is not smooth).
double limitLeavingTheRun(Simulation& sim, const StepStabilityOptions& options);
double radiusLeavingTheRun(Simulation& sim, double dt, const StepStabilityOptions& options);

// The limit linearised at `at`, a state the run passed through (moving), leaving the run as it
// found it.
double stepLimitAt(Simulation& sim, const State& at);

// What a calm run says of dt: the scene run again from its start at half of dt, its blow-up
// check off, up to `until`, and its step at dt / margin linearised at `samples` evenly spaced
// times after `from` (a spectral radius each, a tenth or less of a limit's cost: on the 80-mass
// rope a limit takes seconds). A state whose radius is at most 1 is cleared; at the others (past 1, or not
// smooth there) the limit is computed, the largest radius first, then the states that are not
// smooth, for at most `limits` of them. A limit below the calm run's own dt, which the calm run
// just stepped through, is not the run's (the linearisation caught a contact or a
// self-collision switching: the self-colliding cloth folded at t = 0.24 s under explicit Euler,
// 0.043 ms, where the calm run at 0.23 ms goes on). Leaves the run as it found it. The trampoline
// in the wind under explicit Euler at 0.8 times its limit: 0.094 ms where that run was stopped
// (the blow-up's own state), 0.232 ms at t = 0.049 s on its calm run (the tethers' catch; 0.318
// at rest). A frozen state's limit: where a contact or the stretch limit caps what the step
// grows, runs survive states whose limit is far below their dt (the hanging cloth's catch).
struct CalmRun {
  int states = 0;      // linearised (the calm run's finite states)
  int cleared = 0;     // of them, where dt is within margin times the limit
  double limit = NAN;  // s, the smallest limit found past dt / margin; NaN: none
  double time = NAN;   // s, that state's time
};
CalmRun calmRun(Simulation& sim, double dt, double margin, double from, double until, int samples, int limits);

}  // namespace springlab
