#pragma once
// The highest angular frequency of a scene at a given state, from its linearisation
//   M x'' = -K (x - x0),  K = -dF/dx  (at fixed velocities),
// as the square root of the largest eigenvalue of M^-1 K. Lanczos iteration on the symmetric
// M^-1/2 K M^-1/2 finds it; K is never assembled: K d is a central difference of
// Simulation::evaluateForces, so the estimate covers every force a lab adds (springs, ground,
// pressure, bending) without a Jacobian. Kinematic masses (pinned or grabbed) are left out:
// they do not oscillate. A 2D scene is estimated in its plane.
//
// Gershgorin's bound (springGershgorinBound, Simulation::angularFrequencyBound) needs no
// force evaluation and never underestimates, but it sees only springs the lab lists and can
// be far too high on irregular meshes; this estimate is what the stability studies and the
// blow-up message predict with. It costs 2 force evaluations per Lanczos step (at most
// `maxIterations`), and leaves Simulation::stats unchanged.
#include "springlab/simulation.hpp"

namespace springlab {

struct FrequencyEstimate {
  double maxAngularFrequency = 0.0;  // rad/s, sqrt(lambda_max(M^-1 K)); 0 when nothing can move
  int iterations = 0;                // Lanczos steps taken
  int forceEvaluations = 0;          // evaluations spent (not counted in sim.stats)
};

// The Lanczos estimate of the highest angular frequency at state `at` (the current state:
// lanczosEstimate(sim, sim.state)).
FrequencyEstimate lanczosEstimate(Simulation& sim, const State& at, int maxIterations = 60);

}  // namespace springlab
