// Conjugate gradients with a block-Jacobi preconditioner on a BlockSystem (given).
#include <Eigen/Dense>

#include <springlab/solvers/block_jacobi_cg.hpp>

namespace springlab {

void BlockJacobiCG::precondition(const Eigen::VectorXd& in, Eigen::VectorXd& out) const {
  const int blocks = static_cast<int>(inverseDiagonal_.size());
  const int threads = blocks > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (int b = 0; b < blocks; ++b) out.segment<3>(3 * b) = inverseDiagonal_[static_cast<std::size_t>(b)] * in.segment<3>(3 * b);
}

int BlockJacobiCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  const Eigen::VectorXd& b = system.rhs();
  const Eigen::Index rows = b.size();
  if (x.size() != rows) x.setZero(rows);
  const double bNorm2 = b.squaredNorm();
  if (rows == 0 || bNorm2 == 0.0) {
    x.setZero();
    return 0;
  }

  // The inverse of each free mass's own block (symmetric positive definite).
  inverseDiagonal_.resize(static_cast<std::size_t>(rows / 3));
  for (int i = 0; i < system.masses(); ++i) {
    const int row = system.row(i);
    if (row >= 0) inverseDiagonal_[static_cast<std::size_t>(row / 3)] = system.diagonalBlock(i).inverse();
  }

  // Textbook preconditioned CG (Saad, Algorithm 9.1) from the warm start x.
  r_.resize(rows);
  z_.resize(rows);
  p_.resize(rows);
  q_.resize(rows);
  system.multiply(x, q_);
  r_ = b - q_;
  const double stop2 = tolerance * tolerance * bNorm2;
  const int maxIterations = static_cast<int>(2 * rows);
  precondition(r_, z_);
  p_ = z_;
  double rz = r_.dot(z_);
  int iterations = 0;
  while (r_.squaredNorm() > stop2 && iterations < maxIterations) {
    system.multiply(p_, q_);
    const double alpha = rz / p_.dot(q_);
    x += alpha * p_;
    r_ -= alpha * q_;
    precondition(r_, z_);
    const double rzNext = r_.dot(z_);
    p_ = z_ + (rzNext / rz) * p_;
    rz = rzNext;
    ++iterations;
  }
  return iterations;
}

}  // namespace springlab
