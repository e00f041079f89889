#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double enclosedVolume(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles) {
  // TODO exercise 3.3 (the enclosed volume): write this part; see handouts/03_softbody.md, Exercise 3.3 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.3", "the enclosed volume", "handouts/03_softbody.md, Exercise 3.3 (physics in section 2, The physics)");
}

double enclosedArea(const std::vector<Vec3>& pos, const std::vector<Segment>& segments) {
  // TODO exercise 3.3 (the enclosed volume): write this part; see handouts/03_softbody.md, Exercise 3.3 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.3", "the enclosed volume", "handouts/03_softbody.md, Exercise 3.3 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
