#include "springlab/midpoint.hpp"

#include <utility>

#include "runge_kutta_stages.hpp"

namespace springlab {

void Midpoint::step(Simulation& sim, double dt) {
  // Rates at the start, a half step to the midpoint, rates there.
  detail::ratesAt(sim, sim.state, k1_);
  detail::advance(sim.state, k1_, 0.5 * dt, mid_);
  detail::ratesAt(sim, mid_, k2_);

  // The whole step with the midpoint's rates; swapping keeps both buffers for the next step.
  detail::advance(sim.state, k2_, dt, next_);
  std::swap(sim.state, next_);
}

}  // namespace springlab
