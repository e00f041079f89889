#include "springlab/rk4.hpp"

#include "runge_kutta_stages.hpp"

namespace springlab {

void RungeKutta4::step(Simulation& sim, double dt) {
  // Four stages: the start, the midpoint twice (each from the previous stage's rates), the end.
  detail::ratesAt(sim, sim.state, k1_);
  detail::advance(sim.state, k1_, 0.5 * dt, trial_);
  detail::ratesAt(sim, trial_, k2_);
  detail::advance(sim.state, k2_, 0.5 * dt, trial_);
  detail::ratesAt(sim, trial_, k3_);
  detail::advance(sim.state, k3_, dt, trial_);
  detail::ratesAt(sim, trial_, k4_);

  // Weighted mean of the four rates: 1/6, 2/6, 2/6, 1/6.
  State& s = sim.state;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    s.pos[i] += dt / 6.0 * (k1_.dx[i] + 2.0 * k2_.dx[i] + 2.0 * k3_.dx[i] + k4_.dx[i]);
    s.vel[i] += dt / 6.0 * (k1_.dv[i] + 2.0 * k2_.dv[i] + 2.0 * k3_.dv[i] + k4_.dv[i]);
  }
  s.time += dt;
}

}  // namespace springlab
