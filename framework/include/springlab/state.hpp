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

}  // namespace springlab
