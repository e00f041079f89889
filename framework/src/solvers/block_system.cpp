// The linear system of an implicit step in 3x3 blocks (given). The layout is built once from
// the free masses and the Jacobian's pairs; later steps only refill values.
#include <stdexcept>
#include <string>

#include <springlab/solvers/block_system.hpp>

#include "fast/spring_batches.hpp"
#include "fast/thread_budget.hpp"

namespace springlab {

void BlockSystem::prepare(const std::vector<char>& free, const ForceJacobian& J) {
  // Same masses and couplings as last time: keep the layout, zero the values.
  bool same = free == patternFree_ && J.pairs.size() == patternPairs_.size();
  for (std::size_t k = 0; same && k < J.pairs.size(); ++k) {
    same = J.pairs[k].i == patternPairs_[k][0] && J.pairs[k].j == patternPairs_[k][1];
  }
  if (same && !row_.empty()) {
    setZero();
    return;
  }
  patternFree_ = free;
  ++layoutVersion_;
  patternPairs_.resize(J.pairs.size());
  for (std::size_t k = 0; k < J.pairs.size(); ++k) patternPairs_[k] = {J.pairs[k].i, J.pairs[k].j};

  // Number the free masses: mass i owns rows row_[i] .. row_[i] + 2.
  const std::size_t n = free.size();
  row_.assign(n, -1);
  int blocks = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (free[i]) row_[i] = 3 * blocks++;
  }

  // A pair couples two different free masses, or nothing.
  pairRows_.resize(patternPairs_.size());
  for (std::size_t k = 0; k < patternPairs_.size(); ++k) {
    const auto [i, j] = patternPairs_[k];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n) {
      throw std::out_of_range("BlockSystem: a Jacobian pair names a mass that does not exist");
    }
    const int ri = row_[static_cast<std::size_t>(i)], rj = row_[static_cast<std::size_t>(j)];
    pairRows_[k] = ri < 0 || rj < 0 || ri == rj ? std::array<int, 2>{-1, -1} : std::array<int, 2>{ri, rj};
  }
  batches_ = std::make_shared<const SpringBatches>(patternPairs_);
  diagonal_.resize(static_cast<std::size_t>(blocks));
  coupling_.resize(patternPairs_.size());
  b_.resize(3 * blocks);
  setZero();
}

void BlockSystem::setZero() {
  std::fill(diagonal_.begin(), diagonal_.end(), Mat3::Zero());
  std::fill(coupling_.begin(), coupling_.end(), Mat3::Zero());
  b_.setZero();
}

void BlockSystem::setValues(const std::vector<Mat3>& diagonal, const std::vector<Mat3>& coupling,
                            const Eigen::VectorXd& rhs) {
  if (diagonal.size() != diagonal_.size() || coupling.size() != coupling_.size() || rhs.size() != b_.size())
    throw std::invalid_argument("BlockSystem::setValues: " + std::to_string(diagonal.size()) + " diagonal blocks, " +
                                std::to_string(coupling.size()) + " pair blocks and " + std::to_string(rhs.size()) +
                                " right-side rows for a layout of " + std::to_string(diagonal_.size()) + ", " +
                                std::to_string(coupling_.size()) + " and " + std::to_string(b_.size()));
  diagonal_ = diagonal;
  coupling_ = coupling;
  b_ = rhs;
}

void BlockSystem::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // The diagonal blocks, each row on its own; then the pairs, each adding to both its rows.
  y.resize(b_.size());
  const int blocks = static_cast<int>(diagonal_.size());
  const int threads = blocks > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (int r = 0; r < blocks; ++r) y.segment<3>(3 * r) = diagonal_[static_cast<std::size_t>(r)] * x.segment<3>(3 * r);
  // Consecutive pairs mostly share their first row: its sum stays in a register until the
  // row changes (as in the cloth's force pass). (No batches: prepare() has not run, no pairs.)
  if (!batches_) return;
  batches_->forEachBatch([&](int first, int last) {
    int pending = -1;
    Vec3 sum = Vec3::Zero();
    for (int k = first; k < last; ++k) {
      const auto [ri, rj] = pairRows_[static_cast<std::size_t>(k)];
      if (ri < 0) continue;
      const Mat3& c = coupling_[static_cast<std::size_t>(k)];
      if (ri != pending) {
        if (pending >= 0) y.segment<3>(pending) += sum;
        pending = ri;
        sum.setZero();
      }
      sum += c * x.segment<3>(rj);
      y.segment<3>(rj) += c * x.segment<3>(ri);
    }
    if (pending >= 0) y.segment<3>(pending) += sum;
  });
}

BlockSystem::Matrix BlockSystem::matrix() const {
  std::vector<Eigen::Triplet<double>> entries;
  auto add = [&](int r, int c, const Mat3& block) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) entries.emplace_back(r + a, c + b, block(a, b));
    }
  };
  for (std::size_t r = 0; r < diagonal_.size(); ++r) add(3 * static_cast<int>(r), 3 * static_cast<int>(r), diagonal_[r]);
  for (std::size_t k = 0; k < pairRows_.size(); ++k) {
    const auto [ri, rj] = pairRows_[k];
    if (ri < 0) continue;
    add(ri, rj, coupling_[k]);
    add(rj, ri, coupling_[k]);
  }
  Matrix a(size(), size());
  a.setFromTriplets(entries.begin(), entries.end());  // duplicates add up
  return a;
}

Mat3 BlockSystem::block(int i, int j) const {
  const int ri = row_[static_cast<std::size_t>(i)], rj = row_[static_cast<std::size_t>(j)];
  if (ri < 0 || rj < 0) return Mat3::Zero();
  if (ri == rj) return diagonal_[static_cast<std::size_t>(ri / 3)];
  Mat3 out = Mat3::Zero();
  for (std::size_t k = 0; k < pairRows_.size(); ++k) {
    const auto [a, b] = pairRows_[k];
    if ((a == ri && b == rj) || (a == rj && b == ri)) out += coupling_[k];
  }
  return out;
}

Mat3 BlockSystem::diagonalBlock(int i) const {
  const int r = row_[static_cast<std::size_t>(i)];
  return r >= 0 ? diagonal_[static_cast<std::size_t>(r / 3)] : Mat3::Zero();
}

Vec3 BlockSystem::rhsOf(int i) const {
  const int first = row_[static_cast<std::size_t>(i)];
  return first >= 0 ? Vec3(b_.segment<3>(first)) : Vec3::Zero();
}

}  // namespace springlab
