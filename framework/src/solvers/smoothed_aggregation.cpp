// Smoothed aggregation preconditioned CG (see springlab/solvers/smoothed_aggregation.hpp).
#include <springlab/solvers/smoothed_aggregation.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include <Eigen/Dense>

namespace springlab {

namespace {
constexpr double kProlongatorDamping = 2.0 / 3.0;  // omega of P = (I - omega D^-1 A) P0
constexpr double kSmootherDamping = 2.0 / 3.0;     // omega of the block-Jacobi sweeps
constexpr double kStrongCoupling = 0.05;           // |A_ij| / max_j |A_ij| of a strong neighbour

std::size_t at(int i) { return static_cast<std::size_t>(i); }

// Each block row's neighbours (block column, A_ij summed over the pairs that join them),
// sorted by column.
std::vector<std::vector<std::pair<int, Mat3>>> neighbours(const BlockSystem& system) {
  std::vector<std::vector<std::pair<int, Mat3>>> rows(system.diagonalBlocks().size());
  const auto& pairRows = system.pairRows();
  const auto& coupling = system.couplingBlocks();
  auto add = [&](int bi, int bj, const Mat3& c) {
    auto& row = rows[at(bi)];
    auto found = std::find_if(row.begin(), row.end(), [bj](const auto& e) { return e.first == bj; });
    if (found == row.end()) {
      row.push_back({bj, c});
    } else {
      found->second += c;
    }
  };
  for (std::size_t k = 0; k < pairRows.size(); ++k) {
    const auto [ri, rj] = pairRows[k];
    if (ri < 0) continue;
    add(ri / 3, rj / 3, coupling[k]);
    add(rj / 3, ri / 3, coupling[k]);
  }
  for (auto& row : rows) std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return rows;
}

// The slot of column `col` in row b of `rows` (the column is there by construction).
template <class Rows>
int slotOf(const Rows& rows, int b, int col) {
  const auto first = rows.col.begin() + rows.start[at(b)], last = rows.col.begin() + rows.start[at(b) + 1];
  const auto found = std::lower_bound(first, last, col);
  if (found == last || *found != col) throw std::logic_error("SmoothedAggregationCG: a block outside its pattern");
  return static_cast<int>(found - rows.col.begin());
}
}  // namespace

void SmoothedAggregationCG::buildLayout(const BlockSystem& system) {
  const int blocks = static_cast<int>(system.diagonalBlocks().size());
  const auto rows = neighbours(system);

  // Strong neighbours: couplings within kStrongCoupling of the row's strongest.
  std::vector<std::vector<int>> strong(at(blocks));
  for (int b = 0; b < blocks; ++b) {
    double strongest = 0.0;
    for (const auto& [j, c] : rows[at(b)]) strongest = std::max(strongest, c.norm());
    for (const auto& [j, c] : rows[at(b)]) {
      if (c.norm() >= kStrongCoupling * strongest) strong[at(b)].push_back(j);
    }
  }

  // A mass none of whose strong neighbours is taken starts an aggregate with all of them;
  // masses left over join a neighbour's aggregate, or start their own.
  aggregateOf_.assign(at(blocks), -1);
  int count = 0;
  for (int b = 0; b < blocks; ++b) {
    if (aggregateOf_[at(b)] >= 0) continue;
    const auto& nb = strong[at(b)];
    if (std::any_of(nb.begin(), nb.end(), [&](int j) { return aggregateOf_[at(j)] >= 0; })) continue;
    aggregateOf_[at(b)] = count;
    for (int j : nb) aggregateOf_[at(j)] = count;
    ++count;
  }
  for (int b = 0; b < blocks; ++b) {
    if (aggregateOf_[at(b)] >= 0) continue;
    for (int j : strong[at(b)]) {
      if (aggregateOf_[at(j)] >= 0) {
        aggregateOf_[at(b)] = aggregateOf_[at(j)];
        break;
      }
    }
    if (aggregateOf_[at(b)] < 0) aggregateOf_[at(b)] = count++;
  }
  aggregates_ = count;

  // P's pattern: row b reaches its own aggregate and its neighbours' (D^-1 A P0).
  // A P's: row b reaches what P's rows of b and of its neighbours reach.
  auto buildRows = [&](BlockRows& out, auto&& columnsOf) {
    out.start.assign(1, 0);
    out.col.clear();
    std::vector<int> cols;
    for (int b = 0; b < blocks; ++b) {
      cols.clear();
      columnsOf(b, cols);
      std::sort(cols.begin(), cols.end());
      cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
      out.col.insert(out.col.end(), cols.begin(), cols.end());
      out.start.push_back(static_cast<int>(out.col.size()));
    }
    out.value.assign(out.col.size(), Mat3::Zero());
  };
  buildRows(P_, [&](int b, std::vector<int>& cols) {
    cols.push_back(aggregateOf_[at(b)]);
    for (const auto& nb : rows[at(b)]) cols.push_back(aggregateOf_[at(nb.first)]);
  });
  auto pRow = [&](int b, std::vector<int>& cols) {
    cols.insert(cols.end(), P_.col.begin() + P_.start[at(b)], P_.col.begin() + P_.start[at(b) + 1]);
  };
  buildRows(AP_, [&](int b, std::vector<int>& cols) {
    pRow(b, cols);
    for (const auto& nb : rows[at(b)]) pRow(nb.first, cols);
  });

  // Where each product lands in A P: D_b P_b, then per pair C P_j into row i, C P_i into row j.
  apOfDiagonal_.resize(P_.col.size());
  for (int b = 0; b < blocks; ++b) {
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) apOfDiagonal_[at(s)] = slotOf(AP_, b, P_.col[at(s)]);
  }
  const auto& pairRows = system.pairRows();
  apOfPairStart_.assign(1, 0);
  apOfPair_.clear();
  for (const auto& [ri, rj] : pairRows) {
    if (ri >= 0) {
      const int i = ri / 3, j = rj / 3;
      for (int s = P_.start[at(j)]; s < P_.start[at(j) + 1]; ++s) apOfPair_.push_back(slotOf(AP_, i, P_.col[at(s)]));
      for (int s = P_.start[at(i)]; s < P_.start[at(i) + 1]; ++s) apOfPair_.push_back(slotOf(AP_, j, P_.col[at(s)]));
    }
    apOfPairStart_.push_back(static_cast<int>(apOfPair_.size()));
  }

  // A_c's blocks: (a, c) for every P_ba and (A P)_bc of a row b.
  std::map<std::pair<int, int>, int> coarseBlock;
  coarseOf_.clear();
  for (int b = 0; b < blocks; ++b) {
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) {
      for (int t = AP_.start[at(b)]; t < AP_.start[at(b) + 1]; ++t) {
        const auto inserted = coarseBlock.emplace(std::make_pair(P_.col[at(s)], AP_.col[at(t)]), static_cast<int>(coarseBlock.size()));
        coarseOf_.push_back(inserted.first->second);
      }
    }
  }
  coarseBlocks_.assign(coarseBlock.size(), Mat3::Zero());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * coarseBlock.size());
  for (const auto& [ac, id] : coarseBlock) {
    for (int d = 0; d < 3; ++d) {
      for (int e = 0; e < 3; ++e) entries.emplace_back(3 * ac.first + d, 3 * ac.second + e, 1.0);
    }
  }
  coarseMatrix_ = Sparse(3 * aggregates_, 3 * aggregates_);
  coarseMatrix_.setFromTriplets(entries.begin(), entries.end());
  coarseMatrix_.makeCompressed();
  coarseEntry_.resize(3 * coarseBlock.size());
  for (const auto& [ac, id] : coarseBlock) {
    for (int e = 0; e < 3; ++e) {
      coarseEntry_[3 * at(id) + at(e)] =
          static_cast<int>(&coarseMatrix_.coeffRef(3 * ac.first, 3 * ac.second + e) - coarseMatrix_.valuePtr());
    }
  }
  coarse_.analyzePattern(coarseMatrix_);
  ++layoutBuilds_;
}

void SmoothedAggregationCG::buildProlongator(const BlockSystem& system) {
  // P_b = P0_b - omega D_b^-1 (A P0)_b: (1 - omega) I in b's own aggregate from A_bb, and
  // -omega D_b^-1 A_bj in the aggregate of each neighbour j.
  const int blocks = static_cast<int>(system.diagonalBlocks().size());
  std::fill(P_.value.begin(), P_.value.end(), Mat3::Zero());
  for (int b = 0; b < blocks; ++b) P_.value[at(slotOf(P_, b, aggregateOf_[at(b)]))] += (1.0 - kProlongatorDamping) * Mat3::Identity();
  const auto& pairRows = system.pairRows();
  const auto& coupling = system.couplingBlocks();
  for (std::size_t k = 0; k < pairRows.size(); ++k) {
    const auto [ri, rj] = pairRows[k];
    if (ri < 0) continue;
    const int i = ri / 3, j = rj / 3;
    P_.value[at(slotOf(P_, i, aggregateOf_[at(j)]))] -= kProlongatorDamping * inverseDiagonal_[at(i)] * coupling[k];
    P_.value[at(slotOf(P_, j, aggregateOf_[at(i)]))] -= kProlongatorDamping * inverseDiagonal_[at(j)] * coupling[k];
  }
  ++prolongatorBuilds_;
}

void SmoothedAggregationCG::buildCoarseMatrix(const BlockSystem& system) {
  // A P, block by block through the layout's indices.
  const int blocks = static_cast<int>(system.diagonalBlocks().size());
  const auto& diagonal = system.diagonalBlocks();
  std::fill(AP_.value.begin(), AP_.value.end(), Mat3::Zero());
  for (int b = 0; b < blocks; ++b) {
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) AP_.value[at(apOfDiagonal_[at(s)])].noalias() += diagonal[at(b)] * P_.value[at(s)];
  }
  const auto& pairRows = system.pairRows();
  const auto& coupling = system.couplingBlocks();
  for (std::size_t k = 0; k < pairRows.size(); ++k) {
    const auto [ri, rj] = pairRows[k];
    if (ri < 0) continue;
    const int i = ri / 3, j = rj / 3;
    const Mat3& c = coupling[k];
    const int* slot = apOfPair_.data() + apOfPairStart_[k];
    for (int s = P_.start[at(j)]; s < P_.start[at(j) + 1]; ++s) AP_.value[at(*slot++)].noalias() += c * P_.value[at(s)];
    for (int s = P_.start[at(i)]; s < P_.start[at(i) + 1]; ++s) AP_.value[at(*slot++)].noalias() += c * P_.value[at(s)];
  }

  // A_c = P^T (A P), then into the factorised matrix's values.
  std::fill(coarseBlocks_.begin(), coarseBlocks_.end(), Mat3::Zero());
  const int* target = coarseOf_.data();
  for (int b = 0; b < blocks; ++b) {
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) {
      const Mat3 pT = P_.value[at(s)].transpose();
      for (int t = AP_.start[at(b)]; t < AP_.start[at(b) + 1]; ++t) coarseBlocks_[at(*target++)].noalias() += pT * AP_.value[at(t)];
    }
  }
  double* values = coarseMatrix_.valuePtr();
  for (std::size_t id = 0; id < coarseBlocks_.size(); ++id) {
    for (int e = 0; e < 3; ++e) {
      double* column = values + coarseEntry_[3 * id + at(e)];
      for (int d = 0; d < 3; ++d) column[d] = coarseBlocks_[id](d, e);
    }
  }
  coarse_.factorize(coarseMatrix_);
  if (coarse_.info() != Eigen::Success) throw std::runtime_error("SmoothedAggregationCG: the coarse matrix P^T A P is not positive definite");
}

void SmoothedAggregationCG::vCycle(const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  // Sweep, coarse correction of what is left, sweep again: the same on the way down and up,
  // so the preconditioner is symmetric. The first sweep starts from z = 0: z = omega D^-1 r.
  const int blocks = static_cast<int>(r.size() / 3);
  z.resize(r.size());
  for (int b = 0; b < blocks; ++b) z.segment<3>(3 * b) = kSmootherDamping * (inverseDiagonal_[at(b)] * r.segment<3>(3 * b));
  system.multiply(z, t_);
  t_ = r - t_;
  // rc = P^T t and z += P xc, block by block.
  rc_.setZero(3 * aggregates_);
  for (int b = 0; b < blocks; ++b) {
    const Vec3 tb = t_.segment<3>(3 * b);
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) rc_.segment<3>(3 * P_.col[at(s)]).noalias() += P_.value[at(s)].transpose() * tb;
  }
  xc_ = coarse_.solve(rc_);
  for (int b = 0; b < blocks; ++b) {
    Vec3 sum = Vec3::Zero();
    for (int s = P_.start[at(b)]; s < P_.start[at(b) + 1]; ++s) sum.noalias() += P_.value[at(s)] * xc_.segment<3>(3 * P_.col[at(s)]);
    z.segment<3>(3 * b) += sum;
  }
  system.multiply(z, t_);
  t_ = r - t_;
  for (int b = 0; b < blocks; ++b) z.segment<3>(3 * b) += kSmootherDamping * (inverseDiagonal_[at(b)] * t_.segment<3>(3 * b));
}

int SmoothedAggregationCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  if (system.size() == 0 || system.rhs().squaredNorm() == 0.0) return preconditionedCG(system, x, tolerance, {}, vectors_);

  // This step's diagonal blocks, for the smoothing sweeps and P.
  const std::vector<Mat3>& diagonal = system.diagonalBlocks();
  inverseDiagonal_.resize(diagonal.size());
  for (std::size_t b = 0; b < diagonal.size(); ++b) inverseDiagonal_[b] = diagonal[b].inverse();

  // A new layout: new aggregates and indices. New P values when asked for. A_c every step.
  const bool newLayout = system.layoutVersion() != layoutVersion_;
  if (newLayout) {
    buildLayout(system);
    layoutVersion_ = system.layoutVersion();
  }
  const bool built = newLayout || rebuild_;
  if (built) buildProlongator(system);
  buildCoarseMatrix(system);

  const int iterations = preconditionedCG(
      system, x, tolerance, [this, &system](const Eigen::VectorXd& r, Eigen::VectorXd& z) { vCycle(system, r, z); },
      vectors_);

  // P ages with the matrix (A_c does not: it is rebuilt from each step's A): rebuild it when
  // CG needs clearly more iterations than with a fresh one.
  if (built) {
    iterationsAfterBuild_ = iterations;
    rebuild_ = false;
  } else {
    rebuild_ = iterations > kRebuildGrowth * iterationsAfterBuild_ + 1;
  }
  return iterations;
}

}  // namespace springlab
