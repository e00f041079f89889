#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt) {
  // BEGIN EXERCISE 1.4
  // Both updates use the state at the start of the step.
  return {s.pos + s.vel * dt, s.vel + a * dt};
  // END EXERCISE 1.4
}

}  // namespace springlab::rope
