#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 groundContactForce(const Vec3& x, const Vec3& vel, const Ground& ground) {
  // TODO exercise 1.3 (ground contact): write this part; see handouts/01_rope.md, Exercise 1.3 (physics in section 2.c, The ground).
  throw springlab::NotImplemented("1.3", "ground contact", "handouts/01_rope.md, Exercise 1.3 (physics in section 2.c, The ground)");
}

}  // namespace springlab::rope
