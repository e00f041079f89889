#include "springlab/rk4.hpp"

#include "runge_kutta_stages.hpp"

namespace springlab {

void RungeKutta4::step(Simulation& sim, double dt) {
  // Four stages: the start, the midpoint twice (each from the previous stage's rates), the end.
  detail::Rates k1, k2, k3, k4;
  State trial;
  detail::ratesAt(sim, sim.state, k1);
  detail::advance(sim.state, k1, 0.5 * dt, trial);
  detail::ratesAt(sim, trial, k2);
  detail::advance(sim.state, k2, 0.5 * dt, trial);
  detail::ratesAt(sim, trial, k3);
  detail::advance(sim.state, k3, dt, trial);
  detail::ratesAt(sim, trial, k4);

  // Weighted mean of the four rates: 1/6, 2/6, 2/6, 1/6.
  State& s = sim.state;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    s.pos[i] += dt / 6.0 * (k1.dx[i] + 2.0 * k2.dx[i] + 2.0 * k3.dx[i] + k4.dx[i]);
    s.vel[i] += dt / 6.0 * (k1.dv[i] + 2.0 * k2.dv[i] + 2.0 * k3.dv[i] + k4.dv[i]);
  }
  s.time += dt;
}

}  // namespace springlab
