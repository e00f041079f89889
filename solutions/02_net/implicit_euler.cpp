#include <springlab/net/exercises.hpp>

namespace springlab::net {

void assembleImplicitEuler(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                           double dt, BlockSystem& system) {
  // BEGIN EXERCISE 2.8
  const std::vector<Vec3>& v = sim.state.vel;

  // Mass matrix and the forces: A_ii = m_i I, b_i = dt F_i.
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    system.addToDiagonal(i, sim.masses[i].m * Mat3::Identity());
    system.addToRhs(i, dt * force[i]);
  }

  // Pairs: C = -dt dv - dt^2 dx on both diagonal blocks, -C on both off-diagonal ones;
  // dF/dx v adds dt^2 dx (v_i - v_j) to b_i and the opposite to b_j.
  for (int k = 0; k < static_cast<int>(J.pairs.size()); ++k) {
    const ForceJacobian::Pair& p = J.pairs[k];
    const Mat3 C = -dt * p.dv - dt * dt * p.dx;
    system.addToDiagonal(p.i, C);
    system.addToDiagonal(p.j, C);
    system.addToPair(k, -C);
    const Vec3 r = dt * dt * (p.dx * (v[p.i] - v[p.j]));
    system.addToRhs(p.i, r);
    system.addToRhs(p.j, -r);
  }

  // Terms of one mass: on its diagonal block, and dt^2 dx v_i in b_i.
  for (const ForceJacobian::Own& o : J.own) {
    system.addToDiagonal(o.i, -dt * o.dv - dt * dt * o.dx);
    system.addToRhs(o.i, dt * dt * (o.dx * v[o.i]));
  }
  // END EXERCISE 2.8
}

}  // namespace springlab::net
