// The linear system of an implicit step in 3x3 blocks (given). The sparsity pattern is
// built once from the free masses and the Jacobian's pairs; later steps only refill values.
#include <algorithm>
#include <stdexcept>

#include "net.hpp"

namespace springlab::net {

void BlockSystem::prepare(const std::vector<char>& free, const ForceJacobian& J) {
  // Same masses and couplings as last time: keep the pattern, zero the values.
  bool same = free == patternFree_ && J.pairs.size() == patternPairs_.size();
  for (std::size_t k = 0; same && k < J.pairs.size(); ++k) {
    same = J.pairs[k].i == patternPairs_[k].first && J.pairs[k].j == patternPairs_[k].second;
  }
  if (same && a_.rows() == b_.size()) {
    setZero();
    return;
  }
  patternFree_ = free;
  patternPairs_.resize(J.pairs.size());
  for (std::size_t k = 0; k < J.pairs.size(); ++k) patternPairs_[k] = {J.pairs[k].i, J.pairs[k].j};

  // Number the free masses: mass i owns rows row_[i] .. row_[i] + 2.
  const std::size_t n = free.size();
  row_.assign(n, -1);
  int blocks = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (free[i]) row_[i] = 3 * blocks++;
  }

  // Block columns of each block row: the diagonal and every pair with both ends free.
  std::vector<std::vector<int>> columns(static_cast<std::size_t>(blocks));
  for (int r = 0; r < blocks; ++r) columns[static_cast<std::size_t>(r)].push_back(r);
  for (const auto& [i, j] : patternPairs_) {
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n) {
      throw std::out_of_range("BlockSystem: a Jacobian pair names a mass that does not exist");
    }
    const int ri = row_[static_cast<std::size_t>(i)], rj = row_[static_cast<std::size_t>(j)];
    if (ri < 0 || rj < 0 || ri == rj) continue;
    columns[static_cast<std::size_t>(ri / 3)].push_back(rj / 3);
    columns[static_cast<std::size_t>(rj / 3)].push_back(ri / 3);
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < blocks; ++r) {
    auto& c = columns[static_cast<std::size_t>(r)];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    for (int col : c) {
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) entries.emplace_back(3 * r + a, 3 * col + b, 0.0);
      }
    }
  }

  // The matrix with explicit zeros everywhere in the pattern, rows sorted by column.
  a_.resize(3 * blocks, 3 * blocks);
  a_.setFromTriplets(entries.begin(), entries.end());
  a_.makeCompressed();
  b_.setZero(3 * blocks);

  // Where each block's values live: row a of block (r, c) starts at base + a * stride.
  diagonal_.assign(n, Slot{});
  for (std::size_t i = 0; i < n; ++i) {
    if (row_[i] >= 0) diagonal_[i] = slotOf(row_[i] / 3, row_[i] / 3);
  }
  pair_.assign(patternPairs_.size(), {Slot{}, Slot{}});
  for (std::size_t k = 0; k < patternPairs_.size(); ++k) {
    const int ri = row_[static_cast<std::size_t>(patternPairs_[k].first)];
    const int rj = row_[static_cast<std::size_t>(patternPairs_[k].second)];
    if (ri < 0 || rj < 0 || ri == rj) continue;
    pair_[k] = {slotOf(ri / 3, rj / 3), slotOf(rj / 3, ri / 3)};
  }
}

BlockSystem::Slot BlockSystem::slotOf(int rowBlock, int columnBlock) const {
  // Every scalar row of a block row has the same columns, sorted; find the block's first.
  const int* outer = a_.outerIndexPtr();
  const int* inner = a_.innerIndexPtr();
  const int begin = outer[3 * rowBlock], end = outer[3 * rowBlock + 1];
  const int* at = std::lower_bound(inner + begin, inner + end, 3 * columnBlock);
  if (at == inner + end || *at != 3 * columnBlock) return Slot{};
  return Slot{static_cast<int>(at - inner), end - begin};
}

void BlockSystem::setZero() {
  std::fill(a_.valuePtr(), a_.valuePtr() + a_.nonZeros(), 0.0);
  b_.setZero();
}

void BlockSystem::addAt(const Slot& slot, const Mat3& block) {
  if (slot.base < 0) return;
  double* value = a_.valuePtr() + slot.base;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) value[a * slot.stride + b] += block(a, b);
  }
}

void BlockSystem::addToDiagonal(int i, const Mat3& block) { addAt(diagonal_[static_cast<std::size_t>(i)], block); }

void BlockSystem::addToPair(int k, const Mat3& block) {
  const auto& slots = pair_[static_cast<std::size_t>(k)];
  addAt(slots[0], block);
  addAt(slots[1], block);
}

void BlockSystem::addToRhs(int i, const Vec3& r) {
  const int first = row_[static_cast<std::size_t>(i)];
  if (first >= 0) b_.segment<3>(first) += r;
}

Mat3 BlockSystem::block(int i, int j) const {
  const int ri = row_[static_cast<std::size_t>(i)], rj = row_[static_cast<std::size_t>(j)];
  Mat3 out = Mat3::Zero();
  if (ri < 0 || rj < 0) return out;
  const Slot slot = slotOf(ri / 3, rj / 3);
  if (slot.base < 0) return out;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) out(a, b) = a_.valuePtr()[slot.base + a * slot.stride + b];
  }
  return out;
}

Mat3 BlockSystem::diagonalBlock(int i) const {
  const Slot& slot = diagonal_[static_cast<std::size_t>(i)];
  Mat3 out = Mat3::Zero();
  if (slot.base < 0) return out;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) out(a, b) = a_.valuePtr()[slot.base + a * slot.stride + b];
  }
  return out;
}

Vec3 BlockSystem::rhsOf(int i) const {
  const int first = row_[static_cast<std::size_t>(i)];
  return first >= 0 ? Vec3(b_.segment<3>(first)) : Vec3::Zero();
}

}  // namespace springlab::net
