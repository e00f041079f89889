// Conjugate gradients with a block-Jacobi preconditioner on a BlockSystem (given).
#include <Eigen/Dense>

#include <springlab/solvers/block_jacobi_cg.hpp>

#include "fast/spring_batches.hpp"
#include "fast/thread_budget.hpp"

namespace springlab {

void BlockJacobiCG::precondition(const Eigen::VectorXd& in, Eigen::VectorXd& out) const {
  out.resize(in.size());
  const int blocks = static_cast<int>(inverseDiagonal_.size());
  const int threads = blocks > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (int b = 0; b < blocks; ++b) out.segment<3>(3 * b) = inverseDiagonal_[static_cast<std::size_t>(b)] * in.segment<3>(3 * b);
}

int BlockJacobiCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  // The inverse of each free mass's own block (symmetric positive definite).
  inverseDiagonal_.resize(system.diagonalBlocks().size());
  for (std::size_t b = 0; b < inverseDiagonal_.size(); ++b) inverseDiagonal_[b] = system.diagonalBlocks()[b].inverse();
  return preconditionedCG(
      system, x, tolerance, [this](const Eigen::VectorXd& r, Eigen::VectorXd& z) { precondition(r, z); }, vectors_);
}

}  // namespace springlab
