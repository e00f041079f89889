#include <Eigen/Dense>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

void implicitEulerBlocks(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                         double dt, std::vector<Mat3>& diagonal, std::vector<Vec3>& dv) {
  // BEGIN EXERCISE 2.9
  const int n = sim.numOfMasses();
  const std::vector<Vec3>& v = sim.state.vel;

  // Right side b = dt (F + dt dF/dx v) whole; dv holds it until the blocks are known.
  diagonal.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    diagonal[i] = sim.masses[i].m * Mat3::Identity();
    dv[i] = dt * force[i];
  }
  for (const ForceJacobian::Pair& p : J.pairs) {
    const Mat3 C = -dt * p.dv - dt * dt * p.dx;
    diagonal[p.i] += C;
    diagonal[p.j] += C;
    const Vec3 r = dt * dt * (p.dx * (v[p.i] - v[p.j]));
    dv[p.i] += r;
    dv[p.j] -= r;
  }
  for (const ForceJacobian::Own& o : J.own) {
    diagonal[o.i] += -dt * o.dv - dt * dt * o.dx;
    dv[o.i] += dt * dt * (o.dx * v[o.i]);
  }

  // Solve each mass's 3x3 system (symmetric positive definite: Cholesky); masses the
  // scene moves do not change velocity.
  for (int i = 0; i < n; ++i) {
    dv[i] = sim.inverseMass(i) == 0.0 ? Vec3::Zero() : Vec3(diagonal[i].llt().solve(dv[i]));
  }
  // END EXERCISE 2.9
}

}  // namespace springlab::net
