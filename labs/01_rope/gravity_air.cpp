#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 gravityAndAirFriction(double m, const Vec3& vel, const Vec3& gravitation,
                           double airFrictionConstant) {
  // TODO exercise 1.2 (gravity and air friction): write this part; see handouts/01_rope.md, Exercise 1.2 (physics in section 2.b, Gravity and air friction).
  throw springlab::NotImplemented("1.2", "gravity and air friction", "handouts/01_rope.md, Exercise 1.2 (physics in section 2.b, Gravity and air friction)");
}

}  // namespace springlab::rope
