#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint moveConnection(const PhasePoint& connection, double dt, double groundHeight) {
  // BEGIN EXERCISE 1.8
  PhasePoint next{connection.pos + connection.vel * dt, connection.vel};

  // The connection point cannot go below the ground.
  if (next.pos.y() < groundHeight) {
    next.pos.y() = groundHeight;
    next.vel.y() = 0.0;
  }
  return next;
  // END EXERCISE 1.8
}

}  // namespace springlab::rope
