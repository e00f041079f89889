#pragma once
// What the Runge-Kutta methods share (private to the framework): the rates of a state,
// dx/dt = v and dv/dt = F/m, and a trial state a fraction of a step along given rates.
#include <vector>

#include "springlab/simulation.hpp"

namespace springlab::detail {

// Rates at state s: one force evaluation. A kinematic mass (inverseMass 0: pinned or grabbed)
// keeps its velocity, as in every other integrator; the scene moves it after the step.
using Rates = StateRate;

inline void ratesAt(Simulation& sim, const State& s, Rates& k) {
  sim.evaluateForces(s, sim.force);
  const int n = sim.numOfMasses();
  k.dx.resize(n);
  k.dv.resize(n);
  for (int i = 0; i < n; ++i) {
    k.dx[i] = s.vel[i];
    k.dv[i] = sim.force[i] * sim.inverseMass(i);
  }
}

// base + h * k, with the clock advanced by h.
inline void advance(const State& base, const Rates& k, double h, State& out) {
  out.time = base.time + h;
  out.pos.resize(base.pos.size());
  out.vel.resize(base.vel.size());
  for (size_t i = 0; i < base.pos.size(); ++i) {
    out.pos[i] = base.pos[i] + h * k.dx[i];
    out.vel[i] = base.vel[i] + h * k.dv[i];
  }
}

}  // namespace springlab::detail
