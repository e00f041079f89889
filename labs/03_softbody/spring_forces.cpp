#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

void addSpringForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                     std::vector<Vec3>& f) {
  // TODO exercise 3.1 (spring forces): write this part; see handouts/03_softbody.md, Exercise 3.1 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.1", "spring forces", "handouts/03_softbody.md, Exercise 3.1 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
