// Smoothed aggregation preconditioned CG (see springlab/solvers/smoothed_aggregation.hpp).
#include <springlab/solvers/smoothed_aggregation.hpp>

#include <algorithm>
#include <cmath>

namespace springlab {

namespace {
constexpr double kProlongatorDamping = 2.0 / 3.0;  // omega of P = (I - omega D^-1 A) P0
constexpr double kSmootherDamping = 2.0 / 3.0;     // omega of the block-Jacobi sweeps
constexpr double kStrongCoupling = 0.05;           // |A_ij| / max_j |A_ij| of a strong neighbour
}  // namespace

void SmoothedAggregationCG::setUp(const BlockSystem& system) {
  A_ = Sparse(system.matrix());
  const int blocks = static_cast<int>(A_.rows() / 3);

  // Diagonal blocks and the strength of each block coupling (Frobenius norms).
  inverseDiagonal_.assign(static_cast<std::size_t>(blocks), Mat3::Zero());
  std::vector<std::vector<std::pair<int, double>>> couplings(static_cast<std::size_t>(blocks));
  {
    std::vector<Mat3> diagonal(static_cast<std::size_t>(blocks), Mat3::Zero());
    std::vector<std::vector<std::pair<int, Mat3>>> offDiagonal(static_cast<std::size_t>(blocks));
    for (int col = 0; col < A_.outerSize(); ++col) {
      for (Sparse::InnerIterator it(A_, col); it; ++it) {
        const int bi = static_cast<int>(it.row() / 3), bj = col / 3;
        if (bi == bj) {
          diagonal[static_cast<std::size_t>(bi)](it.row() % 3, col % 3) = it.value();
        } else {
          auto& row = offDiagonal[static_cast<std::size_t>(bi)];
          if (row.empty() || row.back().first != bj) {
            auto found = std::find_if(row.begin(), row.end(), [bj](const auto& e) { return e.first == bj; });
            if (found == row.end()) {
              row.push_back({bj, Mat3::Zero()});
            } else {
              found->second(it.row() % 3, col % 3) += it.value();
              continue;
            }
          }
          row.back().second(it.row() % 3, col % 3) += it.value();
        }
      }
    }
    for (int b = 0; b < blocks; ++b) {
      inverseDiagonal_[static_cast<std::size_t>(b)] = diagonal[static_cast<std::size_t>(b)].inverse();
      for (const auto& [j, block] : offDiagonal[static_cast<std::size_t>(b)]) {
        couplings[static_cast<std::size_t>(b)].push_back({j, block.norm()});
      }
    }
  }

  // Aggregates: a mass none of whose strong neighbours is taken starts one with all of them;
  // masses left over join a neighbour's aggregate, or start their own.
  aggregateOf_.assign(static_cast<std::size_t>(blocks), -1);
  std::vector<std::vector<int>> strong(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) {
    double strongest = 0.0;
    for (const auto& [j, s] : couplings[static_cast<std::size_t>(b)]) strongest = std::max(strongest, s);
    for (const auto& [j, s] : couplings[static_cast<std::size_t>(b)]) {
      if (s >= kStrongCoupling * strongest) strong[static_cast<std::size_t>(b)].push_back(j);
    }
  }
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

  // P0 (each aggregate moving as one, per dimension), smoothed: P = P0 - omega D^-1 (A P0).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(3 * blocks));
  for (int b = 0; b < blocks; ++b) {
    for (int d = 0; d < 3; ++d) entries.emplace_back(3 * b + d, 3 * aggregateOf_[static_cast<std::size_t>(b)] + d, 1.0);
  }
  Sparse P0(A_.rows(), 3 * count);
  P0.setFromTriplets(entries.begin(), entries.end());
  Sparse AP0 = A_ * P0;
  entries.clear();
  for (int col = 0; col < AP0.outerSize(); ++col) {
    // D^-1 acts within each block row: gather the column's entries by block.
    for (Sparse::InnerIterator it(AP0, col); it; ++it) {
      const int b = static_cast<int>(it.row() / 3), d = static_cast<int>(it.row() % 3);
      const Vec3 scaled = inverseDiagonal_[static_cast<std::size_t>(b)].col(d) * it.value();
      for (int e = 0; e < 3; ++e) entries.emplace_back(3 * b + e, col, -kProlongatorDamping * scaled(e));
    }
  }
  for (int b = 0; b < blocks; ++b) {
    for (int d = 0; d < 3; ++d) entries.emplace_back(3 * b + d, 3 * aggregateOf_[static_cast<std::size_t>(b)] + d, 1.0);
  }
  P_ = Sparse(A_.rows(), 3 * count);
  P_.setFromTriplets(entries.begin(), entries.end());
  P_.prune(0.0);

  // The coarse matrix, factored.
  const Sparse coarse = Sparse(P_.transpose()) * (A_ * P_);
  coarse_.compute(coarse);
}

void SmoothedAggregationCG::smooth(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  // x += omega D^-1 (r - A x), block by block.
  t_.noalias() = A_ * x;
  t_ = r - t_;
  for (Eigen::Index b = 0; b < x.size() / 3; ++b) {
    x.segment<3>(3 * b) += kSmootherDamping * (inverseDiagonal_[static_cast<std::size_t>(b)] * t_.segment<3>(3 * b));
  }
}

void SmoothedAggregationCG::vCycle(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  // Sweep, coarse correction of what is left, sweep again: the same on the way down and up,
  // so the preconditioner is symmetric.
  z.setZero(r.size());
  smooth(r, z);
  t_.noalias() = A_ * z;
  t_ = r - t_;
  rc_.noalias() = P_.transpose() * t_;
  xc_ = coarse_.solve(rc_);
  z.noalias() += P_ * xc_;
  smooth(r, z);
}

int SmoothedAggregationCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  const Eigen::VectorXd& b = system.rhs();
  const Eigen::Index rows = b.size();
  if (x.size() != rows) x.setZero(rows);
  const double bNorm2 = b.squaredNorm();
  if (rows == 0 || bNorm2 == 0.0) {
    x.setZero();
    return 0;
  }
  setUp(system);

  // Preconditioned CG (Saad, Algorithm 9.1) from the warm start x, as BlockJacobiCG.
  q_.noalias() = A_ * x;
  r_ = b - q_;
  const double stop2 = tolerance * tolerance * bNorm2;
  const int maxIterations = static_cast<int>(2 * rows);
  vCycle(r_, z_);
  p_ = z_;
  double rz = r_.dot(z_);
  int iterations = 0;
  while (r_.squaredNorm() > stop2 && iterations < maxIterations) {
    q_.noalias() = A_ * p_;
    const double alpha = rz / p_.dot(q_);
    x += alpha * p_;
    r_ -= alpha * q_;
    vCycle(r_, z_);
    const double rzNext = r_.dot(z_);
    p_ = z_ + (rzNext / rz) * p_;
    rz = rzNext;
    ++iterations;
  }
  return iterations;
}

}  // namespace springlab
