#include <algorithm>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

PhasePoint projectContact(const PhasePoint& point, const Penetration& p, const Vec3& obstacleVelocity,
                          const ContactMaterial& c) {
  // TODO exercise 3.8 (contact by projection): write this part; see handouts/03_softbody.md, Exercise 3.8 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.8", "contact by projection", "handouts/03_softbody.md, Exercise 3.8 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
