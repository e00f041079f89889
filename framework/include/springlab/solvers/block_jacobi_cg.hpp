#pragma once
// General solver code: block-Jacobi preconditioned conjugate gradients for a BlockSystem.
#include <vector>

#include <Eigen/Core>

#include <springlab/math.hpp>
#include <springlab/solvers/block_system.hpp>
#include <springlab/solvers/conjugate_gradients.hpp>

namespace springlab {

// ---- Conjugate gradients for a BlockSystem ------------------------------------------
// Preconditioned CG (preconditionedCG), stopping at |b - A x| <= tolerance |b|.
// The preconditioner inverts each free mass's own 3x3 block (block Jacobi): it sees a
// spring's direction, where a diagonal one sees three scalars. Its vectors are kept between
// solves, so a step allocates nothing.
class BlockJacobiCG {
 public:
  double tolerance = 1e-6;
  // Solve A x = b of `system`, starting from x (a warm start); returns the iterations made
  // (at most 2 x rows, as Eigen's).
  int solve(const BlockSystem& system, Eigen::VectorXd& x);

 private:
  void precondition(const Eigen::VectorXd& in, Eigen::VectorXd& out) const;
  std::vector<Mat3> inverseDiagonal_;  // [free masses] A_ii^-1
  ConjugateGradientVectors vectors_;
};

}  // namespace springlab
