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
// What is built when: the aggregates once per layout of the system (the masses and springs
// do not change from step to step, only the values do); P and the factored A_c from the
// values of the step that builds them, then kept while they still precondition well: CG
// accepts any fixed symmetric positive definite preconditioner, and a cloth's matrix changes
// little from one step to the next. They are built again when a solve needs more than
// kRebuildGrowth times the iterations the solve after the last build needed. The smoothing
// sweeps always use the step's own A and diagonal blocks.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <springlab/math.hpp>
#include <springlab/solvers/block_system.hpp>
#include <springlab/solvers/conjugate_gradients.hpp>

namespace springlab {

class SmoothedAggregationCG {
 public:
  double tolerance = 1e-6;  // stop at |b - A x| <= tolerance |b|
  // Solve A x = b of `system` from the warm start x; returns the CG iterations made.
  int solve(const BlockSystem& system, Eigen::VectorXd& x);
  int aggregates() const { return aggregates_; }
  int coarseBuilds() const { return coarseBuilds_; }  // how often P and A_c were built

  static constexpr double kRebuildGrowth = 1.5;

 private:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  void buildAggregates(const Sparse& A);     // from the couplings' strengths
  void buildCoarseLevel(const Sparse& A);    // P and the factored A_c
  void vCycle(const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z);

  Sparse P_;
  Eigen::SimplicialLDLT<Sparse> coarse_;
  std::vector<Mat3> inverseDiagonal_;    // [free masses] A_ii^-1 of this step
  std::vector<int> aggregateOf_;         // [free masses]
  int aggregates_ = 0;
  int layoutVersion_ = -1;               // of the system the aggregates were built for
  int coarseBuilds_ = 0;
  int iterationsAfterBuild_ = 0;         // of the first solve with the current coarse level
  bool rebuild_ = true;                  // build P and A_c at the next solve
  ConjugateGradientVectors vectors_;
  Eigen::VectorXd t_, rc_, xc_;          // V-cycle vectors
};

}  // namespace springlab
