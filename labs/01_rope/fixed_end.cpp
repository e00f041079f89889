#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint moveConnection(const PhasePoint& connection, double dt, double groundHeight) {
  // TODO exercise 1.8 (fixed end following the connection point): write this part; see handouts/01_rope.md, Exercise 1.8 (physics in section 2.e, Building the rope and moving its fixed end).
  throw springlab::NotImplemented("1.8", "fixed end following the connection point", "handouts/01_rope.md, Exercise 1.8 (physics in section 2.e, Building the rope and moving its fixed end)");
}

}  // namespace springlab::rope
