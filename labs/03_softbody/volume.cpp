#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double enclosedVolume(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles) {
  // TODO exercise 3.3 (the enclosed volume): write this part; see handouts/03_softbody.md, section Exercise 3.3.
  throw springlab::NotImplemented("3.3", "the enclosed volume", "handouts/03_softbody.md, section Exercise 3.3");
}

double enclosedArea(const std::vector<Vec3>& pos, const std::vector<Segment>& segments) {
  // TODO exercise 3.3 (the enclosed volume): write this part; see handouts/03_softbody.md, section Exercise 3.3.
  throw springlab::NotImplemented("3.3", "the enclosed volume", "handouts/03_softbody.md, section Exercise 3.3");
}

}  // namespace springlab::softbody
