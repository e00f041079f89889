#include "springlab/symplectic_euler.hpp"

#include "springlab/simulation.hpp"
#include "springlab/spring_batches.hpp"

namespace springlab {

void SymplecticEuler::step(Simulation& sim, double dt) {
  // Forces at the current state (one evaluation per step).
  sim.evaluateForces(sim.state, sim.force);

  // Kick, then drift with the new velocity: v += F/m dt; x += v dt.
  // Each mass on its own: split over threads for large systems.
  State& s = sim.state;
  const int n = sim.numOfMasses();
  const int threads = n > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (int i = 0; i < n; ++i) {
    s.vel[i] += sim.force[i] * (sim.inverseMass(i) * dt);
    s.pos[i] += s.vel[i] * dt;
  }
  s.time += dt;
}

}  // namespace springlab
