#pragma once
// The one integrator interface. An integrator advances a Simulation's State by one step,
// asking the simulation for forces through Simulation::evaluateForces (which counts them).
// Integrators are strategies: any of them runs on any lab's system.
#include <string>

namespace springlab {

class Simulation;

class Integrator {
 public:
  virtual ~Integrator() = default;

  // Name used in scene files, on the command line and in the viewer ("symplectic_euler").
  virtual std::string name() const = 0;

  // Convergence order on a smooth problem (1 for the Euler methods, 2 for Verlet, ...).
  virtual int order() const = 0;

  // c in the undamped stability limit dt < c / w_max (2 for symplectic Euler and Verlet);
  // 0 for a method that is unstable at every dt without damping (explicit Euler).
  virtual double stabilityConstant() const = 0;

  // Forget any history (Verlet's previous positions) after the state was changed by hand.
  virtual void reset() {}

  // Advance sim.state by dt: positions, velocities and time.
  virtual void step(Simulation& sim, double dt) = 0;
};

}  // namespace springlab
