#pragma once
// The classical fourth-order Runge-Kutta method: four force evaluations per step, at the start,
// twice at the midpoint and at the end, combined with weights 1/6, 2/6, 2/6, 1/6. Stable for an
// undamped oscillator while w dt < 2 sqrt(2) = 2.83; the energy then decays slowly.
#include "springlab/integrator.hpp"
#include "springlab/state.hpp"

namespace springlab {

class RungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "rk4"; }
  int order() const override { return 4; }
  double stabilityConstant() const override { return 2.0 * 1.4142135623730951; }
  void step(Simulation& sim, double dt) override;

 private:
  // Kept between steps, so a step allocates nothing once sized.
  StateRate k1_, k2_, k3_, k4_;  // the four stages' rates
  State trial_;
};

}  // namespace springlab
