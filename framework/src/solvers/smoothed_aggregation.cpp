// Smoothed aggregation preconditioned CG (see springlab/solvers/smoothed_aggregation.hpp).
#include <springlab/solvers/smoothed_aggregation.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace springlab {

namespace {
constexpr double kProlongatorDamping = 2.0 / 3.0;  // omega of P = (I - omega D^-1 A_F) P0
constexpr double kStrongCoupling = 0.05;           // |A_ij| / max_j |A_ij| of a strong neighbour


std::size_t at(int i) { return static_cast<std::size_t>(i); }

using BlockRows = SmoothedAggregationCG::BlockRows;

// The slot of column `col` in row b (it is there by construction).
int slotOf(const BlockRows& rows, int b, int col) {
  const auto first = rows.col.begin() + rows.start[at(b)], last = rows.col.begin() + rows.start[at(b) + 1];
  const auto found = std::lower_bound(first, last, col);
  if (found == last || *found != col) throw std::logic_error("SmoothedAggregationCG: a block outside its pattern");
  return static_cast<int>(found - rows.col.begin());
}

// Rows whose columns are columnsOf(b, cols) (sorted and made unique here), values zero.
template <class Columns>
BlockRows patternOf(int rows, Columns&& columnsOf) {
  BlockRows out;
  std::vector<int> cols;
  for (int b = 0; b < rows; ++b) {
    cols.clear();
    columnsOf(b, cols);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    out.col.insert(out.col.end(), cols.begin(), cols.end());
    out.start.push_back(static_cast<int>(out.col.size()));
  }
  out.value.assign(out.col.size(), Mat3::Zero());
  return out;
}

std::vector<int> diagonalSlots(const BlockRows& A) {
  std::vector<int> slots(at(A.rows()));
  for (int b = 0; b < A.rows(); ++b) slots[at(b)] = slotOf(A, b, b);
  return slots;
}

void invertDiagonal(const BlockRows& A, const std::vector<int>& diagonalSlot, std::vector<Mat3>& inverse) {
  inverse.resize(diagonalSlot.size());
  for (std::size_t b = 0; b < diagonalSlot.size(); ++b) inverse[b] = A.value[at(diagonalSlot[b])].inverse();
}

// next = P^T A P through the layout's indices (AP is kept in the level).
void galerkin(const BlockRows& A, const BlockRows& P, BlockRows& AP, const std::vector<int>& apOf,
              const std::vector<int>& coarseOf, BlockRows& next) {
  std::fill(AP.value.begin(), AP.value.end(), Mat3::Zero());
  const int* target = apOf.data();
  for (int b = 0; b < A.rows(); ++b) {
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
      const Mat3& a = A.value[at(e)];
      const int j = A.col[at(e)];
      for (int s = P.start[at(j)]; s < P.start[at(j) + 1]; ++s) AP.value[at(*target++)].noalias() += a * P.value[at(s)];
    }
  }
  std::fill(next.value.begin(), next.value.end(), Mat3::Zero());
  target = coarseOf.data();
  for (int b = 0; b < A.rows(); ++b) {
    for (int s = P.start[at(b)]; s < P.start[at(b) + 1]; ++s) {
      const Mat3 pT = P.value[at(s)].transpose();
      for (int t = AP.start[at(b)]; t < AP.start[at(b) + 1]; ++t) next.value[at(*target++)].noalias() += pT * AP.value[at(t)];
    }
  }
}
}  // namespace

void SmoothedAggregationCG::aggregate(Level& level) {
  const BlockRows& A = level.A;
  const int rows = A.rows();
  // Strong neighbours: couplings within kStrongCoupling of the row's strongest.
  level.strong.assign(A.col.size(), 0);
  std::vector<std::vector<int>> strong(at(rows));
  for (int b = 0; b < rows; ++b) {
    double strongest = 0.0;
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
      if (A.col[at(e)] != b) strongest = std::max(strongest, A.value[at(e)].norm());
    }
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
      if (A.col[at(e)] != b && strongest > 0.0 && A.value[at(e)].norm() >= kStrongCoupling * strongest) {
        level.strong[at(e)] = 1;
        strong[at(b)].push_back(A.col[at(e)]);
      }
    }
  }

  // A row none of whose strong neighbours is taken starts an aggregate with all of them;
  // rows left over join a neighbour's aggregate, or start their own.
  std::vector<int>& of = level.aggregateOf;
  of.assign(at(rows), -1);
  int count = 0;
  for (int b = 0; b < rows; ++b) {
    if (of[at(b)] >= 0) continue;
    const auto& nb = strong[at(b)];
    if (std::any_of(nb.begin(), nb.end(), [&](int j) { return of[at(j)] >= 0; })) continue;
    of[at(b)] = count;
    for (int j : nb) of[at(j)] = count;
    ++count;
  }
  for (int b = 0; b < rows; ++b) {
    if (of[at(b)] >= 0) continue;
    for (int j : strong[at(b)]) {
      if (of[at(j)] >= 0) {
        of[at(b)] = of[at(j)];
        break;
      }
    }
    if (of[at(b)] < 0) of[at(b)] = count++;
  }
  level.aggregates = count;
}

void SmoothedAggregationCG::buildProlongator(Level& level) {
  // P_b = P0_b - omega D_b^-1 (A_F P0)_b: a strong A_bj goes to j's aggregate, a weak one and
  // A_bb to b's own (A_F keeps the row sums of A).
  const BlockRows& A = level.A;
  BlockRows& P = level.P;
  std::fill(P.value.begin(), P.value.end(), Mat3::Zero());
  for (int b = 0; b < A.rows(); ++b) {
    const int own = slotOf(P, b, level.aggregateOf[at(b)]);
    P.value[at(own)] += Mat3::Identity();
    const Mat3 scale = kProlongatorDamping * level.inverseDiagonal[at(b)];
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
      const int j = A.col[at(e)];
      const int slot = level.strong[at(e)] ? slotOf(P, b, level.aggregateOf[at(j)]) : own;
      P.value[at(slot)].noalias() -= scale * A.value[at(e)];
    }
  }
}

void SmoothedAggregationCG::fillFirstLevel(const BlockSystem& system) {
  BlockRows& A = levels_.front().A;
  std::fill(A.value.begin(), A.value.end(), Mat3::Zero());
  const auto& diagonal = system.diagonalBlocks();
  for (std::size_t b = 0; b < diagonal.size(); ++b) A.value[at(levels_.front().diagonalSlot[b])] = diagonal[b];
  const auto& coupling = system.couplingBlocks();
  for (std::size_t k = 0; k < pairSlots_.size(); ++k) {
    if (pairSlots_[k][0] < 0) continue;
    A.value[at(pairSlots_[k][0])] += coupling[k];
    A.value[at(pairSlots_[k][1])] += coupling[k];
  }
}

void SmoothedAggregationCG::buildLayout(const BlockSystem& system) {
  // The first level's pattern: each free mass with itself and the masses the kept pairs
  // join; a pair not kept adds its block to both masses' diagonal blocks (A_F).
  const int blocks = static_cast<int>(system.diagonalBlocks().size());
  const auto& pairRows = system.pairRows();
  auto firstLevel = [&](const std::vector<char>& keep) {
    std::vector<std::vector<int>> neighbours(at(blocks));
    for (std::size_t k = 0; k < pairRows.size(); ++k) {
      const auto [ri, rj] = pairRows[k];
      if (ri < 0 || !keep[k]) continue;
      neighbours[at(ri / 3)].push_back(rj / 3);
      neighbours[at(rj / 3)].push_back(ri / 3);
    }
    levels_.clear();
    levels_.emplace_back();
    BlockRows& A = levels_.front().A;
    A = patternOf(blocks, [&](int b, std::vector<int>& cols) {
      cols = neighbours[at(b)];
      cols.push_back(b);
    });
    pairSlots_.clear();
    for (std::size_t k = 0; k < pairRows.size(); ++k) {
      const int i = pairRows[k][0] / 3, j = pairRows[k][1] / 3;
      if (pairRows[k][0] < 0) {
        pairSlots_.push_back({-1, -1});
      } else if (keep[k]) {
        pairSlots_.push_back({slotOf(A, i, j), slotOf(A, j, i)});
      } else {
        pairSlots_.push_back({slotOf(A, i, i), slotOf(A, j, j)});
      }
    }
    levels_.front().diagonalSlot = diagonalSlots(A);
    fillFirstLevel(system);
  };
  // Every pair first, to find the weak ones; then only the pairs strong for one of their ends.
  std::vector<char> keep(pairRows.size(), 1);
  firstLevel(keep);
  {
    aggregate(levels_.front());
    const BlockRows& A = levels_.front().A;
    for (std::size_t k = 0; k < pairRows.size(); ++k) {
      if (pairRows[k][0] < 0) continue;
      const int i = pairRows[k][0] / 3, j = pairRows[k][1] / 3;
      keep[k] = levels_.front().strong[at(slotOf(A, i, j))] || levels_.front().strong[at(slotOf(A, j, i))];
    }
    firstLevel(keep);
  }

  // Level by level: aggregates (from this step's values), P, A P and the next matrix.
  for (std::size_t l = 0;; ++l) {
    Level& level = levels_[l];
    const BlockRows& A = level.A;
    const int rows = A.rows();
    invertDiagonal(A, level.diagonalSlot, level.inverseDiagonal);
    aggregate(level);
    level.P = patternOf(rows, [&](int b, std::vector<int>& cols) {
      cols.push_back(level.aggregateOf[at(b)]);
      for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
        if (level.strong[at(e)]) cols.push_back(level.aggregateOf[at(A.col[at(e)])]);
      }
    });
    buildProlongator(level);
    const BlockRows& P = level.P;
    level.AP = patternOf(rows, [&](int b, std::vector<int>& cols) {
      for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
        const int j = A.col[at(e)];
        cols.insert(cols.end(), P.col.begin() + P.start[at(j)], P.col.begin() + P.start[at(j) + 1]);
      }
    });
    level.apOf.clear();
    for (int b = 0; b < rows; ++b) {
      for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) {
        const int j = A.col[at(e)];
        for (int s = P.start[at(j)]; s < P.start[at(j) + 1]; ++s) level.apOf.push_back(slotOf(level.AP, b, P.col[at(s)]));
      }
    }
    // The next matrix: (a, c) for every P_ba and (A P)_bc of a row b.
    std::vector<std::vector<int>> coarseColumns(at(level.aggregates));
    for (int b = 0; b < rows; ++b) {
      for (int s = P.start[at(b)]; s < P.start[at(b) + 1]; ++s) {
        auto& cols = coarseColumns[at(P.col[at(s)])];
        cols.insert(cols.end(), level.AP.col.begin() + level.AP.start[at(b)], level.AP.col.begin() + level.AP.start[at(b) + 1]);
      }
    }
    BlockRows next = patternOf(level.aggregates, [&](int a, std::vector<int>& cols) { cols = coarseColumns[at(a)]; });
    level.coarseOf.clear();
    for (int b = 0; b < rows; ++b) {
      for (int s = P.start[at(b)]; s < P.start[at(b) + 1]; ++s) {
        for (int t = level.AP.start[at(b)]; t < level.AP.start[at(b) + 1]; ++t) {
          level.coarseOf.push_back(slotOf(next, P.col[at(s)], level.AP.col[at(t)]));
        }
      }
    }
    galerkin(A, P, level.AP, level.apOf, level.coarseOf, next);
    // Small enough to factor, or no longer coarsening (a system without couplings): the last.
    const bool last = next.rows() <= kDirectBlocks || 2 * next.rows() > rows;
    if (last) {
      coarsest_ = std::move(next);
      break;
    }
    levels_.emplace_back();
    levels_.back().A = std::move(next);
    levels_.back().diagonalSlot = diagonalSlots(levels_.back().A);
  }
  ++layoutBuilds_;
}

void SmoothedAggregationCG::buildCoarseMatrices() {
  // Level by level: this step's D^-1, P when asked for, the next matrix; the last one factored.
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    Level& level = levels_[l];
    if (l > 0) invertDiagonal(level.A, level.diagonalSlot, level.inverseDiagonal);
    if (rebuild_ && l > 0) buildProlongator(level);
    BlockRows& next = l + 1 < levels_.size() ? levels_[l + 1].A : coarsest_;
    galerkin(level.A, level.P, level.AP, level.apOf, level.coarseOf, next);
  }
  // The last matrix in full: a dense Cholesky of at most 3 kDirectBlocks rows. A level that
  // stopped coarsening is larger, and a matrix that is not positive definite (an A that is
  // not) cannot be factored: those are solved by their diagonal blocks instead.
  coarsestFactored_ = false;
  if (coarsest_.rows() > kDirectBlocks) return;
  const int n = 3 * coarsest_.rows();
  coarsestDense_.setZero(n, n);
  for (int a = 0; a < coarsest_.rows(); ++a) {
    for (int e = coarsest_.start[at(a)]; e < coarsest_.start[at(a) + 1]; ++e) {
      coarsestDense_.block<3, 3>(3 * a, 3 * coarsest_.col[at(e)]) = coarsest_.value[at(e)];
    }
  }
  coarsestFactor_.compute(coarsestDense_);
  coarsestFactored_ = coarsestFactor_.info() == Eigen::Success;
}

void SmoothedAggregationCG::vCycle(std::size_t l, const BlockSystem& system, const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  if (l == levels_.size()) {
    if (coarsestFactored_) {
      z = coarsestFactor_.solve(r);
    } else {
      z.resize(r.size());
      for (int a = 0; a < coarsest_.rows(); ++a) {
        z.segment<3>(3 * a) = coarsest_.value[at(slotOf(coarsest_, a, a))].ldlt().solve(Vec3(r.segment<3>(3 * a)));
      }
    }
    return;
  }
  // A forward block Gauss-Seidel sweep from z = 0, the coarse correction of what is left, a
  // backward sweep (the forward one's transpose): the preconditioner is symmetric, so CG may
  // use it. Gauss-Seidel smooths more than damped block Jacobi for the same pass over the rows
  // (r = 64: 16 iterations against 21; r = 128: 24 against 35).
  Level& level = levels_[l];
  const BlockRows& P = level.P;
  const BlockRows& A = level.A;
  const int rows = static_cast<int>(r.size() / 3);
  z.resize(r.size());
  for (int b = 0; b < rows; ++b) {
    Vec3 sum = r.segment<3>(3 * b);
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1] && A.col[at(e)] < b; ++e) sum.noalias() -= A.value[at(e)] * z.segment<3>(3 * A.col[at(e)]);
    z.segment<3>(3 * b) = level.inverseDiagonal[at(b)] * sum;
  }
  // The residual t = r - A z after a forward sweep: each row b was solved against the z_j of
  // j <= b, so only the blocks right of the diagonal remain, t_b = -sum_{j > b} A_bj z_j
  // (to round-off): half a pass over the rows instead of a whole one.
  level.t.resize(r.size());
  for (int b = 0; b < rows; ++b) {
    Vec3 sum = Vec3::Zero();
    for (int e = A.start[at(b) + 1] - 1; e >= A.start[at(b)] && A.col[at(e)] > b; --e) {
      sum.noalias() -= A.value[at(e)] * z.segment<3>(3 * A.col[at(e)]);
    }
    level.t.segment<3>(3 * b) = sum;
  }
  // rc = P^T t, the next level's correction xc, z += P xc.
  level.rc.setZero(3 * level.aggregates);
  for (int b = 0; b < rows; ++b) {
    const Vec3 tb = level.t.segment<3>(3 * b);
    for (int s = P.start[at(b)]; s < P.start[at(b) + 1]; ++s) level.rc.segment<3>(3 * P.col[at(s)]).noalias() += P.value[at(s)].transpose() * tb;
  }
  vCycle(l + 1, system, level.rc, level.xc);
  for (int b = 0; b < rows; ++b) {
    Vec3 sum = Vec3::Zero();
    for (int s = P.start[at(b)]; s < P.start[at(b) + 1]; ++s) sum.noalias() += P.value[at(s)] * level.xc.segment<3>(3 * P.col[at(s)]);
    z.segment<3>(3 * b) += sum;
  }
  for (int b = rows - 1; b >= 0; --b) {
    Vec3 sum = r.segment<3>(3 * b);
    for (int e = A.start[at(b)]; e < A.start[at(b) + 1]; ++e) sum.noalias() -= A.value[at(e)] * z.segment<3>(3 * A.col[at(e)]);
    z.segment<3>(3 * b) += level.inverseDiagonal[at(b)] * sum;
  }
}

int SmoothedAggregationCG::solve(const BlockSystem& system, Eigen::VectorXd& x) {
  if (system.size() == 0 || system.rhs().squaredNorm() == 0.0) return preconditionedCG(system, x, tolerance, {}, vectors_);

  // A new layout: new levels, aggregates, indices and P. Otherwise this step's values in the
  // first level, new P when asked for, every coarser matrix from them.
  const bool newLayout = system.layoutVersion() != layoutVersion_;
  if (newLayout) {
    buildLayout(system);
    layoutVersion_ = system.layoutVersion();
    rebuild_ = false;
  } else {
    fillFirstLevel(system);
    invertDiagonal(levels_.front().A, levels_.front().diagonalSlot, levels_.front().inverseDiagonal);
    if (rebuild_) buildProlongator(levels_.front());
  }
  const bool built = newLayout || rebuild_;
  if (built) ++prolongatorBuilds_;
  buildCoarseMatrices();
  rebuild_ = false;

  const int iterations = preconditionedCG(
      system, x, tolerance, [this, &system](const Eigen::VectorXd& r, Eigen::VectorXd& z) { vCycle(0, system, r, z); },
      vectors_);

  // P ages with the matrix (the coarse matrices do not: they are rebuilt from each step's
  // A): rebuild it when CG needs clearly more iterations than with a fresh one.
  if (built) {
    iterationsAfterBuild_ = iterations;
  } else {
    rebuild_ = iterations > kRebuildGrowth * iterationsAfterBuild_ + 1;
  }
  return iterations;
}

}  // namespace springlab
