#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double gasPressure(double nRT, double volume) {
  // TODO exercise 3.4 (the pressure force): write this part; see handouts/03_softbody.md, Exercise 3.4 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.4", "the pressure force", "handouts/03_softbody.md, Exercise 3.4 (physics in section 2, The physics)");
}

void addPressureForces(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                       const std::vector<Segment>& segments, double pressure, std::vector<Vec3>& f) {
  // TODO exercise 3.4 (the pressure force): write this part; see handouts/03_softbody.md, Exercise 3.4 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.4", "the pressure force", "handouts/03_softbody.md, Exercise 3.4 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
