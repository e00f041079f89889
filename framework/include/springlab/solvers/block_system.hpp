#pragma once
// General solver code: the 3x3-block linear system of an implicit step. Any lab whose
// simulation provides force Jacobians can fill one (Lab 2's implicit Euler does).
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <springlab/force_jacobian.hpp>
#include <springlab/math.hpp>

namespace springlab {

class SpringBatches;  // the pairs split for threads (the framework's internal src/fast/)

// ---- The linear system of one implicit step ------------------------------------------
// A = M - dt dF/dv - dt^2 dF/dx and b over the free masses, in 3x3 blocks: one block per
// free mass on the diagonal and one per Jacobian pair (A_ij = A_ji), set up once and refilled
// each step. A mass the scene moves (pinned or grabbed, inverse mass 0) is eliminated: its
// dv is 0, it has no rows and its columns are dropped, so blocks that involve it are ignored.
// Kept as blocks, not as a scalar sparse matrix: a pair's block is written in one place and
// read in one place, which halves the memory the solver streams per product.
class BlockSystem {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  // Ready the system for masses with free[i] != 0, coupled by J's pairs, and zero it.
  // The layout is rebuilt only when the free masses or the pairs changed.
  void prepare(const std::vector<char>& free, const ForceJacobian& J);
  void setZero();

  // A_ii += block
  void addToDiagonal(int i, const Mat3& block) {
    const int r = row_[static_cast<std::size_t>(i)];
    if (r >= 0) diagonal_[static_cast<std::size_t>(r / 3)] += block;
  }
  // A_ij += block and A_ji += block, (i, j) = J.pairs[k]
  void addToPair(int k, const Mat3& block) {
    if (pairRows_[static_cast<std::size_t>(k)][0] >= 0) coupling_[static_cast<std::size_t>(k)] += block;
  }
  // b_i += r
  void addToRhs(int i, const Vec3& r) {
    const int first = row_[static_cast<std::size_t>(i)];
    if (first >= 0) b_.segment<3>(first) += r;
  }

  int row(int i) const { return row_[static_cast<std::size_t>(i)]; }  // first row of mass i, or -1
  int size() const { return static_cast<int>(b_.size()); }            // rows = 3 x free masses
  int masses() const { return static_cast<int>(row_.size()); }
  // Counts the layouts prepare() built: unchanged while only values change, so a solver can
  // keep what it derived from the layout (smoothed aggregation's aggregates).
  int layoutVersion() const { return layoutVersion_; }
  const Eigen::VectorXd& rhs() const { return b_; }
  Mat3 block(int i, int j) const;  // A's block for masses i and j (zero when there is none)
  Mat3 diagonalBlock(int i) const; // A_ii (zero when mass i is eliminated)
  Vec3 rhsOf(int i) const;         // b's part for mass i (zero when eliminated)
  // y = A x over the rows; pairs run in batches on several threads (the same sums however
  // many). y is resized to size().
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // A as a scalar sparse matrix, built on demand (to inspect or compare; the solver uses multiply).
  Matrix matrix() const;

  // The values in the layout prepare() made, to copy an assembled system (the grader's call
  // trace carries a student's assembly from one process to another). setValues throws
  // std::invalid_argument when a size is not the layout's.
  const std::vector<Mat3>& diagonalBlocks() const { return diagonal_; }
  const std::vector<Mat3>& couplingBlocks() const { return coupling_; }
  // [pairs] the first rows of pair k's two masses, {-1, -1} when the pair is ignored (a solver
  // derives its layout from them: smoothed aggregation's neighbours).
  const std::vector<std::array<int, 2>>& pairRows() const { return pairRows_; }
  void setValues(const std::vector<Mat3>& diagonal, const std::vector<Mat3>& coupling, const Eigen::VectorXd& rhs);

 private:
  Eigen::VectorXd b_;
  std::vector<int> row_;                     // [n] first row of each mass, -1 when eliminated
  std::vector<Mat3> diagonal_;               // [free masses] A_rr
  std::vector<Mat3> coupling_;               // [p] A_ij = A_ji of pair k
  std::vector<std::array<int, 2>> pairRows_; // [p] first rows of pair k's ends; -1: the pair is ignored
  std::shared_ptr<const SpringBatches> batches_;  // the pairs split for threads
  std::vector<char> patternFree_;            // what the layout was built for
  std::vector<std::array<int, 2>> patternPairs_;
  int layoutVersion_ = 0;
};

}  // namespace springlab
