#include "springlab/symplectic_euler.hpp"

#include "springlab/simulation.hpp"
#include "springlab/spring_batches.hpp"

namespace springlab {

namespace {

// Kick, then drift with the new velocity, masses [begin, end): v += F/m dt; x += v dt, with
// 1/m = 0 for a pinned mass. (No test for the mass the user holds: the caller leaves it out.)
void kickAndDrift(const Mass* masses, const Vec3* force, Vec3* vel, Vec3* pos, int begin, int end, double dt) {
  for (int i = begin; i < end; ++i) {
    vel[i] += force[i] * (masses[i].inverseMass() * dt);
    pos[i] += vel[i] * dt;
  }
}

}  // namespace

void SymplecticEuler::step(Simulation& sim, double dt) {
  // Forces at the current state (one evaluation per step).
  sim.evaluateForces(sim.state, sim.force);

  // Each mass on its own: split over threads for large systems. The mass the user holds
  // (inverseMass 0) is left out of the loop, which then needs no test per mass, and drifts
  // on its own.
  State& s = sim.state;
  const int n = sim.numOfMasses();
  const int held = sim.grabbed().value_or(n);
  const auto kick = [&](int begin, int end) {
    kickAndDrift(sim.masses.data(), sim.force.data(), s.vel.data(), s.pos.data(), begin, end, dt);
  };
  const int threads = n > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    const int begin = n * t / threads, end = n * (t + 1) / threads;
    if (held < begin || held >= end) {
      kick(begin, end);
    } else {
      kick(begin, held);
      kick(held + 1, end);
    }
  }
  if (held < n) s.pos[held] += s.vel[held] * dt;
  s.time += dt;
}

}  // namespace springlab
