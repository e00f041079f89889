#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt) {
  // TODO exercise 1.4 (explicit Euler step): write this part; see handouts/01_rope.md, Exercise 1.4 (physics in section 2.d, Integrators).
  throw springlab::NotImplemented("1.4", "explicit Euler step", "handouts/01_rope.md, Exercise 1.4 (physics in section 2.d, Integrators)");
}

}  // namespace springlab::rope
