// Smoothed aggregation preconditioned CG (see springlab/solvers/smoothed_aggregation.hpp).
#include <springlab/solvers/smoothed_aggregation.hpp>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace springlab {

namespace {
constexpr double kProlongatorDamping = 2.0 / 3.0;  // omega of P = (I - omega D^-1 A) P0
constexpr double kSmootherDamping = 2.0 / 3.0;     // omega of the block-Jacobi sweeps
constexpr double kStrongCoupling = 0.05;           // |A_ij| / max_j |A_ij| of a strong neighbour

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The 3x3 block norms of A's off-diagonal blocks, per block row: (block column, |A_ij|_F).
std::vector<std::vector<std::pair<int, double>>> couplingStrengths(const Sparse& A) {
  const int blocks = static_cast<int>(A.rows() / 3);
  std::vector<std::vector<std::pair<int, double>>> couplings(static_cast<std::size_t>(blocks));
  for (int col = 0; col < A.outerSize(); ++col) {
    for (Sparse::InnerIterator it(A, col); it; ++it) {
      const int bi = static_cast<int>(it.row() / 3), bj = col / 3;
      if (bi == bj) continue;
      auto& row = couplings[static_cast<std::size_t>(bi)];
      auto found = std::find_if(row.begin(), row.end(), [bj](const auto& e) { return e.first == bj; });
      if (found == row.end()) {
        row.push_back({bj, it.value() * it.value()});
      } else {
        found->second += it.value() * it.value();
      }
    }
  }
  for (auto& row : couplings) {
    for (auto& entry : row) entry.second = std::sqrt(entry.second);
  }
  return couplings;
}
}  // namespace

void SmoothedAggregationCG::buildAggregates(const Sparse& A) {
  const int blocks = static_cast<int>(A.rows() / 3);
  const auto couplings = couplingStrengths(A);

  // Strong neighbours: couplings within kStrongCoupling of the row's strongest.
  std::vector<std::vector<int>> strong(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) {
    double strongest = 0.0;
    for (const auto& [j, s] : couplings[static_cast<std::size_t>(b)]) strongest = std::max(strongest, s);
    for (const auto& [j, s] : couplings[static_cast<std::size_t>(b)]) {
      if (s >= kStrongCoupling * strongest) strong[static_cast<std::size_t>(b)].push_back(j);
    }
  }

  // A mass none of whose strong neighbours is taken starts an aggregate with all of them;
  // masses left over join a neighbour's aggregate, or start their own.
  aggregateOf_.assign(static_cast<std::size_t>(blocks), -1);
  int count = 0;
  for (int b = 0; b < blocks; ++b) {
    if (aggregateOf_[static_cast<std::size_t>(b)] >= 0) continue;
    const auto& nb = strong[static_cast<std::size_t>(b)];
    if (std::any_of(nb.begin(), nb.end(), [&](int j) { return aggregateOf_[static_cast<std::size_t>(j)] >= 0; })) continue;
    aggregateOf_[static_cast<std::size_t>(b)] = count;
    for (int j : nb) aggregateOf_[static_cast<std::size_t>(j)] = count;
    ++count;
  }
  for (int b = 0; b < blocks; ++b) {
    if (aggregateOf_[static_cast<std::size_t>(b)] >= 0) continue;
    for (int j : strong[static_cast<std::size_t>(b)]) {
      if (aggregateOf_[static_cast<std::size_t>(j)] >= 0) {
        aggregateOf_[static_cast<std::size_t>(b)] = aggregateOf_[static_cast<std::size_t>(j)];
        break;
      }
    }
    if (aggregateOf_[static_cast<std::size_t>(b)] < 0) aggregateOf_[static_cast<std::size_t>(b)] = count++;
  }
  aggregates_ = count;
}

void SmoothedAggregationCG::buildCoarseLevel(const Sparse& A) {
  const int blocks = static_cast<int>(A.rows() / 3);
  // P0 (each aggregate moving as one, per dimension), smoothed: P = P0 - omega D^-1 (A P0).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(3 * blocks));
  for (int b = 0; b < blocks; ++b) {
    for (int d = 0; d < 3; ++d) entries.emplace_back(3 * b + d, 3 * aggregateOf_[static_cast<std::size_t>(b)] + d, 1.0);
  }
  Sparse P0(A.rows(), 3 * aggregates_);
  P0.setFromTriplets(entries.begin(), entries.end());
  const Sparse AP0 = A * P0;
  for (int col = 0; col < AP0.outerSize(); ++col) {
    // D^-1 acts within each block row: gather the column's entries by block.
    for (Sparse::InnerIterator it(AP0, col); it; ++it) {
      const int b = static_cast<int>(it.row() / 3), d = static_cast<int>(it.row() % 3);
      const Vec3 scaled = inverseDiagonal_[static_cast<std::size_t>(b)].col(d) * it.value();
      for (int e = 0; e < 3; ++e) entries.emplace_back(3 * b + e, col, -kProlongatorDamping * scaled(e));
    }
  }
  P_ = Sparse(A.rows(), 3 * aggregates_);
  P_.setFromTriplets(entries.begin(), entries.end());  // P0's entries are in `entries` too
  P_.prune(0.0);

  // The coarse matrix, factored.
  const Sparse coarse = Sparse(P_.transpose()) * (A * P_);
  coarse_.compute(coarse);
  ++coarseBuilds_;
}

void SmoothedAggregationCG::vCycle(const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  // Sweep, coarse correction of what is left, sweep again: the same on the way down and up,
  // so the preconditioner is symmetric. The first sweep starts from z = 0: z = omega D^-1 r.
  const Eigen::Index blocks = r.size() / 3;
  z.resize(r.size());
  for (Eigen::Index b = 0; b < blocks; ++b) {
    z.segment<3>(3 * b) = kSmootherDamping * (inverseDiagonal_[static_cast<std::size_t>(b)] * r.segment<3>(3 * b));
  }
  system.multiply(z, t_);
  t_ = r - t_;
  // rc = P^T t, column by column: Eigen would run a transposed product on OpenMP threads of
  // its own (its thread count, not the framework's budget, which backs off under load).
  rc_.resize(P_.cols());
  for (int c = 0; c < P_.outerSize(); ++c) {
    double sum = 0.0;
    for (Sparse::InnerIterator it(P_, c); it; ++it) sum += it.value() * t_(it.row());
    rc_(c) = sum;
  }
  xc_ = coarse_.solve(rc_);
  z.noalias() += P_ * xc_;
  system.multiply(z, t_);
  t_ = r - t_;
  for (Eigen::Index b = 0; b < blocks; ++b) {
    z.segment<3>(3 * b) += kSmootherDamping * (inverseDiagonal_[static_cast<std::size_t>(b)] * t_.segment<3>(3 * b));
  }
}

int SmoothedAggregationCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  if (system.size() == 0 || system.rhs().squaredNorm() == 0.0) return preconditionedCG(system, x, tolerance, {}, vectors_);

  // This step's diagonal blocks, for the smoothing sweeps.
  const std::vector<Mat3>& diagonal = system.diagonalBlocks();
  inverseDiagonal_.resize(diagonal.size());
  for (std::size_t b = 0; b < diagonal.size(); ++b) inverseDiagonal_[b] = diagonal[b].inverse();

  // A new layout: new aggregates. A new coarse level when asked for.
  const bool newLayout = system.layoutVersion() != layoutVersion_;
  if (newLayout || rebuild_) {
    const Sparse A(system.matrix());
    if (newLayout) buildAggregates(A);
    buildCoarseLevel(A);
    layoutVersion_ = system.layoutVersion();
  }

  const int iterations = preconditionedCG(
      system, x, tolerance, [this, &system](const Eigen::VectorXd& r, Eigen::VectorXd& z) { vCycle(system, r, z); },
      vectors_);

  // The coarse level ages with the matrix: rebuild it when CG needs clearly more iterations
  // than with a fresh one.
  if (newLayout || rebuild_) {
    iterationsAfterBuild_ = iterations;
    rebuild_ = false;
  } else {
    rebuild_ = iterations > kRebuildGrowth * iterationsAfterBuild_ + 1;
  }
  return iterations;
}

}  // namespace springlab
