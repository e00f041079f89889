#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint positionVerletFirstStep(const PhasePoint& s, const Vec3& a, double dt) {
  // TODO exercise 1.5 (position Verlet step): write this part; see handouts/01_rope.md, section Exercise 1.5.
  throw springlab::NotImplemented("1.5", "position Verlet step", "handouts/01_rope.md, section Exercise 1.5");
}

PhasePoint positionVerletStep(const Vec3& pos, const Vec3& previousPos, const Vec3& a, double dt) {
  // TODO exercise 1.5 (position Verlet step): write this part; see handouts/01_rope.md, section Exercise 1.5.
  throw springlab::NotImplemented("1.5", "position Verlet step", "handouts/01_rope.md, section Exercise 1.5");
}

}  // namespace springlab::rope
