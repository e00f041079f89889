#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double gasPressure(double nRT, double volume) {
  // TODO exercise 3.4 (the pressure force): write this part; see handouts/03_softbody.md, section Exercise 3.4.
  throw springlab::NotImplemented("3.4", "the pressure force", "handouts/03_softbody.md, section Exercise 3.4");
}

void addPressureForces(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                       const std::vector<Segment>& segments, double pressure, std::vector<Vec3>& f) {
  // TODO exercise 3.4 (the pressure force): write this part; see handouts/03_softbody.md, section Exercise 3.4.
  throw springlab::NotImplemented("3.4", "the pressure force", "handouts/03_softbody.md, section Exercise 3.4");
}

}  // namespace springlab::softbody
