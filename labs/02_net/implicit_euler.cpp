#include <springlab/net/exercises.hpp>

namespace springlab::net {

void assembleImplicitEuler(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                           double dt, BlockSystem& system) {
  // TODO exercise 2.8 (implicit Euler with the sparse system): write this part; see handouts/02_net.md, Exercise 2.8 (physics in section 2.f, Implicit Euler).
  throw springlab::NotImplemented("2.8", "implicit Euler with the sparse system", "handouts/02_net.md, Exercise 2.8 (physics in section 2.f, Implicit Euler)");
}

}  // namespace springlab::net
