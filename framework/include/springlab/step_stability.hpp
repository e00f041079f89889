#pragma once
// The stability limit of the step that runs: the largest dt at which the integrator's own
// one-step map, linearised at the state the scene settles to, has spectral radius at most 1.
//
// The state: where the scene settles (dynamic relaxation from its start, see
// StepStabilityOptions::settle), since a run blows up near the state it spends its time in;
// a start far from rest only passes through. No constant per integrator: the map is the scene's real step (Simulation::operate: the
// integrator, then the lab's after-step corrections), with every force the scene has
// (spring dampers, air, wind, pressure, contacts active at that state). Its Jacobian J is
// never assembled; it acts on a perturbation as the difference of two runs, one from the
// state and one from the state moved by a small perturbation (1e-6 of the scene's lengths).
//
// Why runs and not one step per vector: an integrator may keep history between steps
// (position Verlet's previous positions, velocity Verlet's accelerations), which a single
// step from a hand-set state cannot see. After one step the history of the methods here is a
// function of the state, so each run is taken two steps: its differences d_1, d_2 from the
// unperturbed run satisfy d_2 = J d_1. With X = [d_1 ...] and Y = [d_2 ...] over several
// runs, J on X's range is Y X^+, and its eigenvalues (Rayleigh-Ritz) those of J there.
// - Small systems (at most denseBelow free coordinates): one run per coordinate, so X spans
//   everything and the eigenvalues are J's own (dense, exact up to the finite differences).
// - Larger ones: runs along the modes that fail first, the stiffest modes of M^-1 K, the
//   most damped of M^-1 C and the stiffest for their damping (largest w^2 / gamma, where
//   explicit Euler fails: a ball's wobble that only the air and the floor damp; two Lanczos
//   runs where the first finds ratios well above the stiffest mode's) at the settled state
//   (Lanczos on finite differences of the forces), each as a displacement and as a velocity. For a linear scene with proportional
//   damping (spring dampers on the springs' pairs, air) this subspace is invariant under the
//   step and the result is exact; with other damping, contacts or pressure it is the
//   Rayleigh-Ritz estimate on the modes most likely to fail. A Krylov sequence of one long
//   run (Arnoldi on snapshots) was tried first: its Ritz values of the far-from-normal step
//   map land outside the unit circle at any dt.

// The limit is then a bracket (doubling or halving from a first guess) narrowed on dt to
// the tolerance (probes aimed where the unstable radii extrapolate to 1, a secant, bisection as
// the safeguard: stepStabilityLimit in step_stability.cpp). A closed form per method and mode (undamped c / w_max, explicit Euler's kd / k,
// symplectic Euler's w^2 dt^2 + 2 gamma dt < 4, the stability polynomials of RK4 and the
// midpoint rule) is a test of this, not part of it.
//
// An implicit method (a linear solve per step) is linearised at the settled state with a
// constant load that cancels the force left there, as at a rest: away from rest its step's
// Jacobian has a term that grows with dt (step_stability.cpp, LinearisedRuns), which gave
// implicit Euler a limit of 47.6 ms on the 32 x 32 hanging cloth where it has none
// (implicit_rest_limit_test.cpp).
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "springlab/simulation.hpp"

namespace springlab {

struct StepStabilityOptions {
  int modes = 8;                 // stiffest and most damped modes each, half as many stiffest
                                 // for their damping (twice that where the first run's
                                 // largest ratio exceeds 1.5 times the stiffest mode's): 5 to 6
                                 // x modes runs per dt
  int denseBelow = 500;          // build the whole Jacobian when the free coordinates (positions
                                 // and velocities) number at most this (the 80-mass rope: 480;
                                 // its modal runs missed both Verlets' limits 20-fold, since the
                                 // first step's image of the modes is not invariant there)
  double relativePerturbation = 1e-6;  // of the scene's typical length (and length x w_max for velocities)
  double radiusSlack = 1e-6;     // a spectral radius above 1 + this is unstable (the finite
                                 // differences resolve the radius to about 1e-8)
  double tolerance = 2e-3;       // relative width of the final dt bracket
  double largestFactor = 1000.0; // stable up to this times the first guess: unbounded
  double smallestFactor = 1e-4;  // unstable down to this times the first guess: no stable dt
  bool settle = true;            // linearise at the settled state (false: at the initial state)
  // Where the step is not smooth at a fallen body's rest (a mass resting on a projected
  // collider), hold the masses its contacts hold one-sidedly, as the limit does (false: the
  // limit is NaN there, and stepSpectralRadius gives the finite differences as they come, a
  // jump included).
  bool holdRestingContacts = true;
  // Linearise at this state instead (positions, velocities and time as given; the blow-up
  // message's: where the run was when it was stopped, a squash stiffer than the rest). The
  // step is then linearised about a moving state, and no method's own rest is looked for.
  std::optional<State> at;
  long settleEvaluations = 400000;  // settling budget: force evaluations x free coordinates
  long settleSteps = 4000;       // and at most this many steps (at least 100)
  // Asked before every run of the scene; true stops the computation with
  // StepStabilityCancelled (the viewer's worker, when the scene or the method changed).
  std::function<bool()> cancelled;
};

// Thrown by the functions below when options.cancelled() said so; the simulation is left reset.
struct StepStabilityCancelled : std::runtime_error {
  StepStabilityCancelled() : std::runtime_error("the stability limit's computation was cancelled") {}
};

// The spectral radius of the scene's linearised step at dt, at its settled state: the
// linearisation the limit uses (a fallen body's resting contacts held where the step is not
// smooth there), NaN where the step is not smooth and cannot be held (stepStabilityLimit).
struct StepSpectrum {
  double radius = 0.0;  // largest |eigenvalue| found
  int steps = 0;        // steps of the scene taken to find it
  // Linearised where a fallen body came to rest on what it hit (the settling followed its fall
  // and its impact's ringing): a run from the start gets there only after its fall.
  bool restsAfterImpact = false;
};
StepSpectrum stepSpectralRadius(Simulation& sim, double dt, const StepStabilityOptions& options = {});

// How much the real step (not linearised) amplifies a small perturbation of the state the
// radius is computed at: a run of `steps` steps at dt from that state, and `directions` more,
// each moved by options.relativePerturbation in a pseudo-random direction (every coordinate,
// not only the modes the radius probes; seeds seed, seed + 1, ...), compared with the first about
// 256 times along the way. An independent check of the radius: past the limit the difference
// grows until something nonlinear caps it or the run turns non-finite; within it, it stays
// within the step's transient amplification.
struct StepGrowth {
  double growth = 0.0;  // the median over the directions of each one's largest difference of the
                        // velocities over the perturbation (velocities over length x w_max, as the
                        // perturbation): a drift along a free direction grows the positions'
                        // difference, not the velocities'
  std::vector<double> growths;  // each direction's (+inf: its run ended early)
  bool finite = true;   // the median direction's run stayed finite (and no step threw) to the end
  int steps = 0;        // steps of the scene taken (the settling's included)
};
StepGrowth stepPerturbationGrowth(Simulation& sim, double dt, long steps, const StepStabilityOptions& options = {},
                                  unsigned seed = 1, int directions = 1);

// The largest dt with spectral radius <= 1 + slack. `firstGuess` starts the bracket (the
// undamped c / w_max, or 2 / w_max); +inf when stable up to largestFactor x firstGuess, 0
// when unstable down to smallestFactor x firstGuess; NaN when the step is not smooth at the
// state (a contact switching exactly there: its finite differences change with the
// perturbation's size), where a linearised limit does not exist. Where a fallen body rests
// on what it hit, the masses its contacts hold one-sidedly are held first (left out of the
// modal directions, as the contact leaves them), and the limit is that of the rest.
struct StepStabilityLimit {
  double dt = 0.0;     // s
  int evaluations = 0; // spectral radii computed
  int steps = 0;       // steps of the scene taken
};
StepStabilityLimit stepStabilityLimit(Simulation& sim, double firstGuess, const StepStabilityOptions& options = {});

// The limit of sim's integrator on sim's scene, bracketed from 2 / w_max (w_max: the Lanczos
// estimate at the initial state). Leaves the simulation reset to its initial state.
double stepStableDt(Simulation& sim, const StepStabilityOptions& options = {});

}  // namespace springlab
