#pragma once
// How hard the implicit integrators solve their linear systems: a scene's optional "solver"
// section ({"tolerance": 1e-6, "preconditioner": "auto", "block_sweeps": 1,
// "block_tolerance": 0}), kept by the
// Simulation so any integrator can read it.
#include <string>

namespace springlab {

struct SolverSettings {
  // implicit_euler: conjugate gradients stop at this residual relative to |b|.
  double tolerance = 1e-6;
  // implicit_euler: CG's preconditioner: "block_jacobi" (each mass's 3x3 block),
  // "smoothed_aggregation" (an AMG V-cycle, its hierarchy built once per layout, its coarse
  // matrices every step: about 14-22 iterations at r = 32-128 on the swinging fabric against
  // 123-540), or "auto" (the default): block Jacobi until a step needs more than 25
  // iterations per decade of the tolerance (150 at 1e-6, 75 at 1e-3), then smoothed
  // aggregation (heavy cloth and the fabric up to r = 32 stay with block Jacobi, cheaper there
  // over a whole run; the fabric from r = 64 on switches).
  std::string preconditioner = "auto";
  // implicit_euler_blocks: block-Jacobi sweeps of the implicit system per step, at most. One
  // sweep (the cloth thesis' method) solves each mass against its neighbours' old velocities.
  int blockSweeps = 1;
  // implicit_euler_blocks: stop sweeping when the residual relative to |b| is below this
  // (0: always blockSweeps sweeps).
  double blockTolerance = 0.0;
};

}  // namespace springlab
