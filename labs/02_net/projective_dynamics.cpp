#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 projectSpring(const Vec3& x1, const Vec3& x2, double restLength) {
  // TODO exercise 2.12 (projective dynamics, the local step): write this part; see handouts/02_net.md, Exercise 2.12 (physics in section 7.b, Projective dynamics for springs).
  throw springlab::NotImplemented("2.12", "projective dynamics, the local step", "handouts/02_net.md, Exercise 2.12 (physics in section 7.b, Projective dynamics for springs)");
}

}  // namespace springlab::net
