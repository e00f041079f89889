#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant) {
  // TODO exercise 1.1 (spring-damper force): write this part; see handouts/01_rope.md, Exercise 1.1 (physics in section 2.a, Spring-damper force).
  throw springlab::NotImplemented("1.1", "spring-damper force", "handouts/01_rope.md, Exercise 1.1 (physics in section 2.a, Spring-damper force)");
}

}  // namespace springlab::rope
