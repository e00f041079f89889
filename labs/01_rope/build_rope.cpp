#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

RopeLayout buildRope(const RopeParameters& p) {
  // TODO exercise 1.7 (building the rope): write this part; see handouts/01_rope.md, Exercise 1.7 (physics in section 2.e, Building the rope and moving its fixed end).
  throw springlab::NotImplemented("1.7", "building the rope", "handouts/01_rope.md, Exercise 1.7 (physics in section 2.e, Building the rope and moving its fixed end)");
}

}  // namespace springlab::rope
