#pragma once
// General solver code: conjugate gradients preconditioned with a two-level smoothed
// aggregation V-cycle, for a BlockSystem. Block Jacobi's iteration count grows like r on a
// cloth of light masses on stiff springs (about 250 at r = 64 on the fabric): it only smooths
// the error locally. The coarse level removes the smooth error a grid of aggregates sees.
//   aggregates: each free mass with its strongly coupled neighbours (a grid's 3 x 3 blocks);
//   P0: one column per aggregate and dimension (the aggregate moving as one);
//   P = (I - omega D^-1 A) P0, one damped Jacobi step (D: the 3x3 diagonal blocks);
//   A_c = P^T A P (Galerkin), factored (sparse Cholesky, small);
//   V-cycle: a damped block-Jacobi sweep, the coarse correction, a second sweep (symmetric,
//   so CG may use it).
// What is built when: once per layout of the system (the masses and springs do not change
// from step to step, only the values do) the aggregates and every index the numbers below
// need: P's and A P's 3x3 block patterns, A_c's pattern and its symbolic factorisation.
// P's values from the step that builds them, kept while they still precondition well (CG
// accepts any fixed symmetric positive definite preconditioner) and built again when a solve
// needs more than kRebuildGrowth times the iterations of the solve after the last build.
// A_c = P^T A P from every step's A, in 3x3 blocks through those indices, and its numeric
// factorisation: a falling cloth turns its springs, and a coarse matrix kept from an earlier
// step costs ten times the iterations (r = 64: 215 against 16 per step). The smoothing
// sweeps use the step's own A and diagonal blocks.
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
  int prolongatorBuilds() const { return prolongatorBuilds_; }  // how often P's values were built
  int layoutBuilds() const { return layoutBuilds_; }            // how often the indices were built

  static constexpr double kRebuildGrowth = 1.5;

 private:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  // 3x3 blocks by rows: row b's blocks are value[start[b] .. start[b + 1]), in columns col[].
  struct BlockRows {
    std::vector<int> start, col;
    std::vector<Mat3> value;
  };
  void buildLayout(const BlockSystem& system);       // aggregates and the indices
  void buildProlongator(const BlockSystem& system);  // P's values
  void buildCoarseMatrix(const BlockSystem& system); // A_c = P^T A P, factored
  void vCycle(const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z);

  BlockRows P_;                        // [free masses] x [aggregates]
  BlockRows AP_;                       // [free masses] x [aggregates], A P
  std::vector<int> apOfDiagonal_;      // [P's blocks] the block of AP_ that D_b P_b adds to
  std::vector<int> apOfPairStart_;     // [pairs + 1] into apOfPair_
  std::vector<int> apOfPair_;          // pair (i, j): AP_i += C P_j (|P_j| slots), AP_j += C P_i
  std::vector<int> coarseOf_;          // for b, P_b's blocks s, AP_b's blocks t: A_c's block of P_bs^T AP_bt
  std::vector<Mat3> coarseBlocks_;     // [A_c's blocks]
  std::vector<int> coarseEntry_;       // [A_c's blocks x 3] valuePtr index of (3a, 3c + e)
  Sparse coarseMatrix_;
  Eigen::SimplicialLDLT<Sparse> coarse_;
  std::vector<Mat3> inverseDiagonal_;  // [free masses] A_ii^-1 of this step
  std::vector<int> aggregateOf_;       // [free masses]
  int aggregates_ = 0;
  int layoutVersion_ = -1;             // of the system the layout was built for
  int prolongatorBuilds_ = 0;
  int layoutBuilds_ = 0;
  int iterationsAfterBuild_ = 0;       // of the first solve with the current P
  bool rebuild_ = true;                // build P at the next solve
  ConjugateGradientVectors vectors_;
  Eigen::VectorXd t_, rc_, xc_;        // V-cycle vectors
};

}  // namespace springlab
