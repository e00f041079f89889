#include <cmath>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

Penetration planePenetration(const Vec3& x, const Vec3& point, const Vec3& normal) {
  // TODO exercise 3.6 (where a point touches an obstacle): write this part; see handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.6", "where a point touches an obstacle", "handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics)");
}

Penetration spherePenetration(const Vec3& x, const Vec3& center, double radius) {
  // TODO exercise 3.6 (where a point touches an obstacle): write this part; see handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.6", "where a point touches an obstacle", "handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics)");
}

Penetration boxPenetration(const Vec3& x, const Vec3& center, const Vec3& halfExtents) {
  // TODO exercise 3.6 (where a point touches an obstacle): write this part; see handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.6", "where a point touches an obstacle", "handouts/03_softbody.md, Exercise 3.6 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
