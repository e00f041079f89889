#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 velocityVerletPosition(const PhasePoint& s, const Vec3& a, double dt) {
  // TODO exercise 1.6 (velocity Verlet step): write this part; see handouts/01_rope.md, Exercise 1.6 (physics in section 2.d, Integrators).
  throw springlab::NotImplemented("1.6", "velocity Verlet step", "handouts/01_rope.md, Exercise 1.6 (physics in section 2.d, Integrators)");
}

Vec3 velocityVerletVelocity(const Vec3& vel, const Vec3& a, const Vec3& nextA, double dt) {
  // TODO exercise 1.6 (velocity Verlet step): write this part; see handouts/01_rope.md, Exercise 1.6 (physics in section 2.d, Integrators).
  throw springlab::NotImplemented("1.6", "velocity Verlet step", "handouts/01_rope.md, Exercise 1.6 (physics in section 2.d, Integrators)");
}

}  // namespace springlab::rope
