#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint moveConnection(const PhasePoint& connection, double dt, double groundHeight) {
  // TODO exercise 1.8 (fixed end following the connection point): write this part; see handouts/01_rope.md, section Exercise 1.8.
  throw springlab::NotImplemented("1.8", "fixed end following the connection point", "handouts/01_rope.md, section Exercise 1.8");
}

}  // namespace springlab::rope
