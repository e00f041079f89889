#pragma once
// Diagnostics every system provides: energies, momentum, the largest angular frequency and
// the blow-up check that stops a run with a message naming the likely cause.
#include <stdexcept>
#include <string>
#include <vector>

#include "springlab/math.hpp"
#include "springlab/state.hpp"

namespace springlab {

class Simulation;
class Integrator;

struct Energies {
  double kinetic = 0.0;        // J, sum 1/2 m |v|^2
  double gravitational = 0.0;  // J, sum -m g . x
  double elastic = 0.0;        // J, sum 1/2 k (l - L0)^2 over springs
  double other = 0.0;          // J, potentials a lab adds (ground repulsion, pressure)
  double total() const { return kinetic + gravitational + elastic + other; }
};

// Upper bound on the highest angular frequency of the springs (rad/s), by Gershgorin's
// theorem on M^-1 K: w_max^2 <= max_i 2 sum_{springs at i} k / m_i. It is exact for a
// uniform chain, w_max = 2 sqrt(k/m), and never underestimates.
double springGershgorinBound(const Simulation& sim);

// The largest dt the integrator keeps stable for undamped springs, c / w_max (s);
// 0 when the method has no stable dt (explicit Euler). Damping, contacts and pressure move
// the limit: stepStableDt (springlab/step_stability.hpp) gives the limit of the step that runs.
double predictedStableDt(const Integrator& integrator, double maxAngularFrequency);

// Raised when a run blew up; what() says when, why it is likely, and the safe dt.
class BlowUp : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Watches a run, with three detectors: a non-finite state; kinetic plus elastic plus other
// potential energy (otherPotentialEnergy: ground, gas) grown far beyond the energy the scene
// could ever hold (its initial energy plus the work gravity can do: the runaway factor); and
// passivity: a scene that puts no energy in (no wind, pump, moving pinned mass or user drag)
// cannot gain energy, so a total energy (gravity included) above the highest it had while
// energy came in, by more than kPassivityFraction of the energy scale for kPassivitySteps
// checks in a row, is a blow-up. Past the
// stability limit a nonlinear scene often saturates instead of overflowing (springs flip, the
// state turns to noise at a bounded energy): passivity catches that. The margin covers the
// integrator's own energy oscillation (symplectic Euler's true energy swings about its
// modified energy, by a factor up to 1 / (1 - w dt / 2) of the stiffest mode's energy).
class BlowUpCheck {
 public:
  // Energy growth factor over the scene's energy scale that counts as a runaway.
  static constexpr double kRunawayFactor = 100.0;
  // Rise of a passive scene's total energy, in energy scales, that counts as a blow-up.
  static constexpr double kPassivityFraction = 0.5;
  // Checks in a row the rise must last (the energy of a stable symplectic step swings above
  // and back within a few steps, however close to its limit).
  static constexpr int kPassivitySteps = 64;

  void arm(const Simulation& sim);  // measure the energy scale of the scene as it starts
  // The user put energy in (dragged, pinned): never count that as a blow-up.
  void admitUserEnergy(const Simulation& sim);
  // Throws BlowUp naming the detector that fired and the likely cause. A non-finite state:
  // the forces are evaluated again at the last finite state the check saw; when one is
  // non-finite there, the message names the first such mass and the term that makes it
  // non-finite (the lab's forceTermNames(), each left out in turn; else springs, gravity, or
  // the lab's own forces), and does not blame dt. Otherwise it gives the exact stability
  // limit of the step that runs (stepStableDt, at the scene's initial state: the blown-up
  // state says nothing about the scene's stiffness) and compares dt with it. Computing the
  // limit resets the lab's own data (a dragged collider returns); the state and the counters
  // are put back as the blow-up left them. Remembers the state as the last finite one when
  // it passes.
  void check(Simulation& sim, double dt);

  double energyScale() const { return energyScale_; }

 private:
  // The message's "why it blew up" part for a non-finite state: the forces' story when they
  // went non-finite first, else empty (the step made the state non-finite from finite forces).
  std::string blameForces(Simulation& sim);

  double energyScale_ = 0.0;  // J
  // J, the highest total energy (gravity included) the scene reached while energy came in;
  // a passive scene may not rise above it by more than kPassivityFraction x energyScale_.
  double passiveCeiling_ = 0.0;
  int passiveExcess_ = 0;  // checks in a row above the ceiling
  // The state at the last check that passed (or at arm()): where the forces are evaluated
  // again when the state turns non-finite.
  State last_;
  long lastStep_ = 0;
};

}  // namespace springlab
