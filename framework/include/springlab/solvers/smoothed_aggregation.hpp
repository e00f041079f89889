#pragma once
// General solver code: conjugate gradients preconditioned with a smoothed aggregation
// V-cycle, for a BlockSystem. Block Jacobi's iteration count grows like r on a cloth of light
// masses on stiff springs (about 250 at r = 64 on the fabric): it only smooths the error
// locally. Each coarser level removes the smooth error a grid of aggregates sees.
//   aggregates: each block row with its strongly coupled neighbours (a grid's 3 x 3 blocks);
//   P0: one column per aggregate and dimension (the aggregate moving as one);
//   P = (I - omega D^-1 A_F) P0, one damped Jacobi step (D: the 3x3 diagonal blocks; A_F: A
//   with its weak couplings moved onto the diagonal, so P reaches strong neighbours only and
//   the coarse matrix stays as sparse as the fine one);
//   A_c = P^T A P (Galerkin), the next level's matrix, until a level has at most
//   kDirectBlocks rows: that one is factored densely;
//   V-cycle: a forward block Gauss-Seidel sweep, the coarser levels' correction of what it
//   leaves (that residual from the blocks right of the diagonal only), a backward sweep
//   (symmetric, so CG may use it).
// What is built when: once per layout of the system (the masses and springs do not change
// from step to step, only the values do) the aggregates and every index the numbers below
// need. P's values from the step that builds them, kept while they still precondition well
// (CG accepts any fixed symmetric positive definite preconditioner) and built again when a
// solve needs more than kRebuildGrowth times the iterations of the solve after the last
// build. Every level's A = P^T A P from every step's A, in 3x3 blocks through those indices:
// a falling cloth turns its springs, and coarse matrices kept from an earlier step cost ten
// times the iterations (r = 64: 215 against 16 per step). The smoothing sweeps use the
// step's own matrices.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <springlab/math.hpp>
#include <springlab/solvers/block_system.hpp>
#include <springlab/solvers/conjugate_gradients.hpp>

namespace springlab {

class SmoothedAggregationCG {
 public:
  double tolerance = 1e-6;  // stop at |b - A x| <= tolerance |b|
  // Solve A x = b of `system` from the warm start x; returns the CG iterations made.
  int solve(const BlockSystem& system, Eigen::VectorXd& x);
  int aggregates() const { return levels_.empty() ? 0 : levels_.front().aggregates; }  // of the first level
  int levels() const { return static_cast<int>(levels_.size()) + 1; }  // the system's and the coarser ones
  int prolongatorBuilds() const { return prolongatorBuilds_; }          // how often P's values were built
  int layoutBuilds() const { return layoutBuilds_; }                    // how often the indices were built

  static constexpr double kRebuildGrowth = 1.5;
  static constexpr int kDirectBlocks = 150;  // a level this small (3x3 block rows) is factored densely

  // 3x3 blocks by rows: row b's blocks are value[start[b] .. start[b + 1]), in columns col[]
  // (sorted). A level's matrix holds both triangles.
  struct BlockRows {
    std::vector<int> start{0}, col;
    std::vector<Mat3> value;
    int rows() const { return static_cast<int>(start.size()) - 1; }
  };

 private:
  // One level above the coarsest: its matrix A and what carries its residual one level down.
  struct Level {
    BlockRows A, P, AP;                 // AP = A P
    std::vector<int> diagonalSlot;      // [rows] the slot of A_bb
    std::vector<Mat3> inverseDiagonal;  // [rows] A_bb^-1 of this step
    std::vector<int> aggregateOf;       // [rows]
    std::vector<char> strong;           // [A's blocks] A_bj is a strong coupling of row b
    int aggregates = 0;
    std::vector<int> apOf;              // for b, A_bj, P_j's blocks: the block of AP_b it adds to
    std::vector<int> coarseOf;          // for b, P_b's blocks, AP_b's blocks: the next A's block
    Eigen::VectorXd t, rc, xc;          // V-cycle vectors
  };
  void buildLayout(const BlockSystem& system);  // levels, aggregates and indices
  static void aggregate(Level& level);
  static void buildProlongator(Level& level);
  void fillFirstLevel(const BlockSystem& system);  // levels_[0].A from the system
  void buildCoarseMatrices();                      // every next A = P^T A P, the last one factored
  void vCycle(std::size_t l, const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z);

  std::vector<Level> levels_;
  std::vector<std::array<int, 2>> pairSlots_;  // [system's pairs] slots of A_ij and A_ji in levels_[0].A
  BlockRows coarsest_;                         // the last level's matrix, factored densely
  Eigen::MatrixXd coarsestDense_;
  Eigen::LLT<Eigen::MatrixXd> coarsestFactor_;
  bool coarsestFactored_ = false;              // else the last level is solved by its diagonal blocks
  int layoutVersion_ = -1;                     // of the system the layout was built for
  int prolongatorBuilds_ = 0;
  int layoutBuilds_ = 0;
  int iterationsAfterBuild_ = 0;               // of the first solve with the current P
  bool rebuild_ = true;                        // build P at the next solve
  ConjugateGradientVectors vectors_;
};

}  // namespace springlab
