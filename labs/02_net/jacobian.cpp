#include <algorithm>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

SpringJacobian springJacobian(const Vec3& x1, const Vec3& x2, double springConstant, double springLength,
                              double frictionConstant) {
  // TODO exercise 2.7 (spring force Jacobians): write this part; see handouts/02_net.md, Exercise 2.7 (physics in section 2.f, Implicit Euler).
  throw springlab::NotImplemented("2.7", "spring force Jacobians", "handouts/02_net.md, Exercise 2.7 (physics in section 2.f, Implicit Euler)");
}

}  // namespace springlab::net
