#pragma once
// The handout's Mass::simulate: velocity first, then position with the new velocity.
// The handout calls it Euler; it is semi-implicit (symplectic) Euler, first order, stable
// for undamped springs while w dt < 2, with energy that oscillates but does not grow.
// It is the framework's worked example of an integrator: read it before writing your own.
#include "springlab/integrator.hpp"

namespace springlab {

class SymplecticEuler final : public Integrator {
 public:
  std::string name() const override { return "symplectic_euler"; }
  int order() const override { return 1; }
  double stabilityConstant() const override { return 2.0; }
  void step(Simulation& sim, double dt) override;
};

}  // namespace springlab
