#include <Eigen/Dense>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

void implicitEulerBlocks(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                         double dt, std::vector<Mat3>& diagonal, std::vector<Vec3>& dv) {
  // TODO exercise 2.9 (implicit Euler with per-particle blocks): write this part; see handouts/02_net.md, Exercise 2.9 (physics in section 2.f, Implicit Euler).
  throw springlab::NotImplemented("2.9", "implicit Euler with per-particle blocks", "handouts/02_net.md, Exercise 2.9 (physics in section 2.f, Implicit Euler)");
}

}  // namespace springlab::net
