#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 windForce(const Wind& wind, const Vec3& vel, const Vec3& normal, double area) {
  // TODO exercise 2.4 (wind): write this part; see handouts/02_net.md, Exercise 2.4 (physics in section 2.b, Forces).
  throw springlab::NotImplemented("2.4", "wind", "handouts/02_net.md, Exercise 2.4 (physics in section 2.b, Forces)");
}

}  // namespace springlab::net
