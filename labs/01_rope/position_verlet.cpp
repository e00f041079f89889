#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint positionVerletFirstStep(const PhasePoint& s, const Vec3& a, double dt) {
  // TODO exercise 1.5 (position Verlet step): write this part; see handouts/01_rope.md, Exercise 1.5 (physics in section 2.d, Integrators).
  throw springlab::NotImplemented("1.5", "position Verlet step", "handouts/01_rope.md, Exercise 1.5 (physics in section 2.d, Integrators)");
}

PhasePoint positionVerletStep(const Vec3& pos, const Vec3& previousPos, const Vec3& a, double dt) {
  // TODO exercise 1.5 (position Verlet step): write this part; see handouts/01_rope.md, Exercise 1.5 (physics in section 2.d, Integrators).
  throw springlab::NotImplemented("1.5", "position Verlet step", "handouts/01_rope.md, Exercise 1.5 (physics in section 2.d, Integrators)");
}

}  // namespace springlab::rope
