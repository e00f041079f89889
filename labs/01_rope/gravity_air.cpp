#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 gravityAndAirFriction(double m, const Vec3& vel, const Vec3& gravitation,
                           double airFrictionConstant) {
  // TODO exercise 1.2 (gravity and air friction): write this part; see handouts/01_rope.md, section Exercise 1.2.
  throw springlab::NotImplemented("1.2", "gravity and air friction", "handouts/01_rope.md, section Exercise 1.2");
}

}  // namespace springlab::rope
