#pragma once
// What XPBD and projective dynamics share (given): they treat a scene's springs themselves
// (as constraints, or as the projective energy) and every other force as external, taken
// explicitly at the start of the step: gravity, air friction, wind, ground, gas pressure.
#include <vector>

#include <springlab/net/exercises.hpp>
#include <springlab/simulation.hpp>

namespace springlab::net {

// f = every force at sim.state except the springs' (the scene's forces, one counted
// evaluation, minus the spring-damper force of each spring, exercise 2.2): the scene keeps
// its own force code, and no lab has to split its forces for these two methods.
inline void externalForces(Simulation& sim, std::vector<Vec3>& f) {
  sim.evaluateForces(sim.state, f);
  const State& s = sim.state;
  for (const Spring& sp : sim.springs()) {
    const Vec3 f1 = springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                      sp.springConstant, sp.springLength, sp.frictionConstant);
    f[sp.mass1] -= f1;
    f[sp.mass2] += f1;
  }
}

}  // namespace springlab::net
