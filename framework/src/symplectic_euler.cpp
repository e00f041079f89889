#include "springlab/symplectic_euler.hpp"

#include "springlab/simulation.hpp"

namespace springlab {

void SymplecticEuler::step(Simulation& sim, double dt) {
  // Forces at the current state (one evaluation per step).
  sim.evaluateForces(sim.state, sim.force);

  // Kick, then drift with the new velocity: v += F/m dt; x += v dt. A mass the scene moves
  // (pinned, or held by the user) has 1/m = 0: its velocity stays.
  State& s = sim.state;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    s.vel[i] += sim.force[i] * (sim.inverseMass(i) * dt);
    s.pos[i] += s.vel[i] * dt;
  }
  s.time += dt;
}

}  // namespace springlab
