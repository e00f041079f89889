#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant) {
  // TODO exercise 2.2 (spring-damper force): write this part; see handouts/02_net.md, Exercise 2.2 (physics in section 2.b, Forces).
  throw springlab::NotImplemented("2.2", "spring-damper force", "handouts/02_net.md, Exercise 2.2 (physics in section 2.b, Forces)");
}

}  // namespace springlab::net
