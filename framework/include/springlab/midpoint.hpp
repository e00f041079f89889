#pragma once
// The explicit midpoint method (RK2): a half step with the rates at the start, then a whole
// step with the rates at that midpoint. Second order, two force evaluations per step. On an
// undamped oscillator it has no stable dt: the energy grows by (1 + y^4/4) per step, y = w dt,
// slowly enough to look fine for a while. With damping it is stable for small enough dt.
#include "springlab/integrator.hpp"
#include "springlab/state.hpp"

namespace springlab {

class Midpoint final : public Integrator {
 public:
  std::string name() const override { return "midpoint"; }
  int order() const override { return 2; }
  double stabilityConstant() const override { return 0.0; }
  void step(Simulation& sim, double dt) override;

 private:
  // Kept between steps, so a step allocates nothing once sized.
  StateRate k1_, k2_;
  State mid_, next_;
};

}  // namespace springlab
