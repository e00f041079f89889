#include <algorithm>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

Vec3 penaltyContactForce(const Penetration& p, const Vec3& relativeVelocity, const ContactMaterial& c) {
  // TODO exercise 3.7 (contact by a penalty spring): write this part; see handouts/03_softbody.md, Exercise 3.7 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.7", "contact by a penalty spring", "handouts/03_softbody.md, Exercise 3.7 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
