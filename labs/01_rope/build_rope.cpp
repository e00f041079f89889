#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

RopeLayout buildRope(const RopeParameters& p) {
  // TODO exercise 1.7 (building the rope): write this part; see handouts/01_rope.md, section Exercise 1.7.
  throw springlab::NotImplemented("1.7", "building the rope", "handouts/01_rope.md, section Exercise 1.7");
}

}  // namespace springlab::rope
