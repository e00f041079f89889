#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

void addWindForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel, const std::vector<Triangle>& triangles,
                   const std::vector<Segment>& segments, const Vec3& wind, double drag, std::vector<Vec3>& f) {
  // TODO exercise 3.9 (wind on the faces): write this part; see handouts/03_softbody.md, Exercise 3.9 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.9", "wind on the faces", "handouts/03_softbody.md, Exercise 3.9 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
