#pragma once
// A point mass: the part of the handout's Mass that does not change during a run.
// Its position, velocity and force live in State and Simulation::force (see simulation.hpp),
// so integrators can copy and combine states without touching the model.

namespace springlab {

struct Mass {
  double m = 1.0;       // kg, > 0
  bool pinned = false;  // a pinned mass is moved only by the scene (never by forces)

  double inverseMass() const { return pinned ? 0.0 : 1.0 / m; }
};

}  // namespace springlab
