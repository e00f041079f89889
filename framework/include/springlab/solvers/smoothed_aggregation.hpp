#pragma once
// General solver code: conjugate gradients preconditioned with a two-level smoothed
// aggregation V-cycle, for a BlockSystem. Block Jacobi's iteration count grows like r on a
// cloth of light masses on stiff springs (about 300 at r = 64 on the fabric): it only smooths
// the error locally. The coarse level removes the smooth error a grid of aggregates sees.
//   aggregates: each free mass with its strongly coupled neighbours (a grid's 3 x 3 blocks);
//   P0: one column per aggregate and dimension (the aggregate moving as one);
//   P = (I - omega D^-1 A) P0, one damped Jacobi step (D: the 3x3 diagonal blocks);
//   A_c = P^T A P, factored (sparse Cholesky, small);
//   V-cycle: a damped block-Jacobi sweep, the coarse correction, a second sweep (symmetric,
//   so CG may use it).
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <springlab/math.hpp>
#include <springlab/solvers/block_system.hpp>

namespace springlab {

class SmoothedAggregationCG {
 public:
  double tolerance = 1e-6;  // stop at |b - A x| <= tolerance |b|
  // Solve A x = b of `system` from the warm start x; returns the CG iterations made.
  int solve(const BlockSystem& system, Eigen::VectorXd& x);
  int aggregates() const { return aggregates_; }

 private:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  void setUp(const BlockSystem& system);
  void smooth(const Eigen::VectorXd& r, Eigen::VectorXd& x);  // x += omega D^-1 (r - A x)
  void vCycle(const Eigen::VectorXd& r, Eigen::VectorXd& z);

  Sparse A_, P_;
  Eigen::SimplicialLDLT<Sparse> coarse_;
  std::vector<Mat3> inverseDiagonal_;    // [free masses] A_ii^-1
  std::vector<int> aggregateOf_;         // [free masses]
  int aggregates_ = 0;
  Eigen::VectorXd r_, z_, p_, q_, t_, rc_, xc_;  // CG and V-cycle vectors
};

}  // namespace springlab
