#pragma once
// The one integrator interface. An integrator advances a Simulation's State by one step,
// asking the simulation for forces through Simulation::evaluateForces (which counts them).
// Integrators are strategies: any of them runs on any lab's system.
#include <stdexcept>
#include <string>
#include <vector>

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

  // Whether the method comes to rest where the forces balance (the scene's static
  // equilibrium), as every method of forces does. One that solves the springs approximately
  // each step (XPBD from zero multipliers, projective dynamics with a fixed number of
  // iterations) rests elsewhere, lower, at a place that depends on dt: the scene's spring
  // energy is then not the energy it dissipates (the blow-up check's passivity test leaves
  // it alone), and its stability limit is taken where it rests (step_stability.hpp).
  virtual bool restsAtStaticEquilibrium() const { return true; }

  // Forget any history (Verlet's previous positions) after the state was changed by hand.
  virtual void reset() {}

  // Advance sim.state by dt: positions, velocities and time.
  virtual void step(Simulation& sim, double dt) = 0;

  // Integer settings a scene may give this method (XPBD's "iterations" and "substeps"), in
  // the scene's "integrator_options": {"<method>": {"<option>": value}}. None by default.
  virtual std::vector<std::string> optionNames() const { return {}; }
  // Set one of optionNames() (value >= 1); the registry validates names and values first.
  virtual void setOption(const std::string& option, int value) {
    (void)value;
    throw std::invalid_argument(name() + " has no option \"" + option + "\"");
  }
};

}  // namespace springlab
