#include "springlab/midpoint.hpp"

#include "runge_kutta_stages.hpp"

namespace springlab {

void Midpoint::step(Simulation& sim, double dt) {
  // Rates at the start, a half step to the midpoint, rates there.
  detail::Rates k1, k2;
  State mid;
  detail::ratesAt(sim, sim.state, k1);
  detail::advance(sim.state, k1, 0.5 * dt, mid);
  detail::ratesAt(sim, mid, k2);

  // The whole step with the midpoint's rates.
  State next;
  detail::advance(sim.state, k2, dt, next);
  sim.state = std::move(next);
}

}  // namespace springlab
