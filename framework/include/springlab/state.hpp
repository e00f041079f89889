#pragma once
// What changes every step: positions, velocities and the clock. Integrators read and write
// only this, so any integrator runs on any lab's system.
#include <cstddef>
#include <vector>

#include "springlab/math.hpp"

namespace springlab {

struct State {
  double time = 0.0;      // s
  std::vector<Vec3> pos;  // [n] m
  std::vector<Vec3> vel;  // [n] m/s
};

// The first mass whose position or velocity is not finite, or -1: where a blow-up shows first.
inline int firstNonFiniteMass(const State& s) {
  for (std::size_t i = 0; i < s.pos.size(); ++i) {
    if (!s.pos[i].allFinite() || !s.vel[i].allFinite()) return static_cast<int>(i);
  }
  return -1;
}

// The rate of change of a state, dx/dt and dv/dt: what Runge-Kutta methods combine.
struct StateRate {
  std::vector<Vec3> dx;  // [n] m/s
  std::vector<Vec3> dv;  // [n] m/s^2
};

}  // namespace springlab
