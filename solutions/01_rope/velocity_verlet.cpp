#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 velocityVerletPosition(const PhasePoint& s, const Vec3& a, double dt) {
  // BEGIN EXERCISE 1.6
  return s.pos + s.vel * dt + 0.5 * a * dt * dt;
  // END EXERCISE 1.6
}

Vec3 velocityVerletVelocity(const Vec3& vel, const Vec3& a, const Vec3& nextA, double dt) {
  // BEGIN EXERCISE 1.6
  return vel + 0.5 * (a + nextA) * dt;
  // END EXERCISE 1.6
}

}  // namespace springlab::rope
