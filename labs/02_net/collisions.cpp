#include <algorithm>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

Contact sphereContact(const Vec3& x, const Vec3& center, double radius) {
  // TODO exercise 2.5 (collisions with spheres and planes): write this part; see handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions).
  throw springlab::NotImplemented("2.5", "collisions with spheres and planes", "handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions)");
}

Contact planeContact(const Vec3& x, const Vec3& point, const Vec3& normal) {
  // TODO exercise 2.5 (collisions with spheres and planes): write this part; see handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions).
  throw springlab::NotImplemented("2.5", "collisions with spheres and planes", "handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions)");
}

Vec3 contactVelocity(const Vec3& vel, const Vec3& colliderVelocity, const Vec3& normal, double absorption,
                     double friction) {
  // TODO exercise 2.5 (collisions with spheres and planes): write this part; see handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions).
  throw springlab::NotImplemented("2.5", "collisions with spheres and planes", "handouts/02_net.md, Exercise 2.5 (physics in section 2.c, Collisions)");
}

}  // namespace springlab::net
