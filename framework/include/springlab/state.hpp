#pragma once
// What changes every step: positions, velocities and the clock. Integrators read and write
// only this, so any integrator runs on any lab's system.
#include <vector>

#include "springlab/math.hpp"

namespace springlab {

struct State {
  double time = 0.0;      // s
  std::vector<Vec3> pos;  // [n] m
  std::vector<Vec3> vel;  // [n] m/s
};

// The rate of change of a state, dx/dt and dv/dt: what Runge-Kutta methods combine.
struct StateRate {
  std::vector<Vec3> dx;  // [n] m/s
  std::vector<Vec3> dv;  // [n] m/s^2
};

}  // namespace springlab
