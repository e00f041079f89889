#include "fast/spring_families.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <utility>

#include "fast/avx2.hpp"
#include "fast/spring_batches.hpp"
#include "fast/thread_budget.hpp"

namespace springlab {

SpringFamilies::SpringFamilies(const std::vector<Spring>& springs, int masses)
    : masses_(masses), springCount_(springs.size()) {
  // Offsets shared by enough springs to pay for a buffer of one force per mass.
  std::map<int, int> springsPerOffset;
  for (const Spring& s : springs) {
    const bool inRange = s.mass1 >= 0 && s.mass1 < masses && s.mass2 >= 0 && s.mass2 < masses;
    if (inRange && s.mass2 != s.mass1) ++springsPerOffset[s.mass2 - s.mass1];
  }
  std::vector<std::pair<int, int>> common;  // (springs, offset), most common first
  for (const auto& [d, count] : springsPerOffset) {
    if (4 * count >= masses) common.emplace_back(count, d);
  }
  std::sort(common.begin(), common.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (common.size() > static_cast<std::size_t>(kMaxFamilies)) common.resize(kMaxFamilies);
  for (const auto& [count, d] : common) offsets_.push_back(d);
  std::sort(offsets_.begin(), offsets_.end());  // the order gather() sums in

  // Each family's springs by first mass; a mass starting a second spring of the same offset
  // (a duplicate spring) leaves that one over.
  std::vector<char> inFamily(springs.size(), 0);
  std::vector<int> byFirst(static_cast<std::size_t>(std::max(masses, 0)));
  for (int family = 0; family < families(); ++family) {
    const int d = offset(family);
    std::fill(byFirst.begin(), byFirst.end(), -1);
    for (std::size_t k = 0; k < springs.size(); ++k) {
      const Spring& s = springs[k];
      if (s.mass2 - s.mass1 != d || s.mass1 < 0 || s.mass1 >= masses || s.mass2 < 0 || s.mass2 >= masses) continue;
      int& slot = byFirst[static_cast<std::size_t>(s.mass1)];
      if (slot >= 0) continue;
      slot = static_cast<int>(k);
      inFamily[k] = 1;
    }
    // Runs: stretches of consecutive first masses.
    for (int i = 0; i < masses; ++i) {
      const int k = byFirst[static_cast<std::size_t>(i)];
      if (k < 0) continue;
      const bool extends = !runs_.empty() && runs_.back().family == family &&
                           runs_.back().first + runs_.back().count == i;
      if (extends) {
        ++runs_.back().count;
      } else {
        runs_.push_back(Run{i, 1, static_cast<int>(order_.size()), family});
      }
      order_.push_back(k);
    }
    pad_ = std::max(pad_, std::abs(d));
  }
  for (std::size_t k = 0; k < springs.size(); ++k) {
    if (!inFamily[k]) leftovers_.push_back(static_cast<int>(k));
  }
  // Runs cut at every kBlockMasses-th mass and ordered block by block, all families of a block
  // in a row: a grid lists each mass's springs together, so a block's spring records (and its
  // masses) are read from cache by every family instead of once per family from memory.
  std::vector<Run> blocked;
  for (const Run& run : runs_) {
    for (int t = 0; t < run.count;) {
      const int first = run.first + t;
      const int count = std::min(run.count - t, kBlockMasses - first % kBlockMasses);
      blocked.push_back(Run{first, count, run.spring + t, run.family});
      t += count;
    }
  }
  std::stable_sort(blocked.begin(), blocked.end(),
                   [](const Run& a, const Run& b) { return a.first / kBlockMasses < b.first / kBlockMasses; });
  runs_ = std::move(blocked);
  // Where each spring of order() must start and end, for refresh().
  firstMass_.resize(order_.size());
  secondMass_.resize(order_.size());
  for (const Run& run : runs_) {
    for (int t = 0; t < run.count; ++t) {
      firstMass_[static_cast<std::size_t>(run.spring + t)] = run.first + t;
      secondMass_[static_cast<std::size_t>(run.spring + t)] = run.first + t + offset(run.family);
    }
  }
  refresh(springs, masses);
  // Zeros around each buffer: gather() reads forces(family)[i - d] for every mass i.
  const std::size_t length = static_cast<std::size_t>(std::max(masses, 0) + 2 * pad_);
  buffers_.assign(offsets_.size(), std::vector<Vec3>(length, Vec3::Zero()));
}

bool SpringFamilies::refresh(const std::vector<Spring>& springs, int masses) {
  if (springs.size() != springCount_ || masses != masses_) return false;
  k_.resize(order_.size());
  restLength_.resize(order_.size());
  kd_.resize(order_.size());
  for (std::size_t at = 0; at < order_.size(); ++at) {
    const Spring& sp = springs[static_cast<std::size_t>(order_[at])];
    if (sp.mass1 != firstMass_[at] || sp.mass2 != secondMass_[at]) return false;
    k_[at] = sp.springConstant;
    restLength_[at] = sp.springLength;
    kd_[at] = sp.frictionConstant;
  }
  return true;
}

namespace {

// x, y and z of n packed Vec3s into three rows (restrict rows: GCC then vectorises the
// stride-3 reads; one loop writing six rows through one pointer it did not).
[[gnu::always_inline]] inline void toRows(const double* __restrict p, double* __restrict x, double* __restrict y,
                                          double* __restrict z, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = p[3 * i];
    y[i] = p[3 * i + 1];
    z[i] = p[3 * i + 2];
  }
}

SPRINGLAB_AVX2_TWINS(toRows,
                     (const double* __restrict p, double* __restrict x, double* __restrict y, double* __restrict z,
                      std::size_t n),
                     (p, x, y, z, n))

}  // namespace

void SpringFamilies::load(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel) {
  const std::size_t n = static_cast<std::size_t>(std::max(masses_, 0));
  if (n == 0) return;
  // Rows a whole number of cache lines long plus three: six rows 2^k doubles apart (r = 64:
  // 32 KiB) fall on the same cache sets and alias in the store buffer (4K aliasing), which
  // made this copy about 1.7x slower (perf: 17 % of a symplectic step against 10 %).
  soaStride_ = (n + 7) / 8 * 8 + 24;
  soa_.resize(6 * soaStride_);
  // Vec3 is three packed doubles: mass i's components are doubles 3i, 3i + 1, 3i + 2.
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const auto rows = toRowsForThisCpu();
  double* row = soa_.data();
  rows(pos.front().data(), row, row + soaStride_, row + 2 * soaStride_, n);
  rows(vel.front().data(), row + 3 * soaStride_, row + 4 * soaStride_, row + 5 * soaStride_, n);
}

namespace {

// f[e] += sum over the families of plus[e] - minus[e], over the doubles [begin, end) of f, in
// family order; N families known at compile time, so the loop is one stream per buffer.
template <int N>
[[gnu::always_inline]] inline void gatherFamilies(double* __restrict f, const double* const* plus,
                                                  const double* const* minus, std::ptrdiff_t begin,
                                                  std::ptrdiff_t end) {
  const double* p[N];
  const double* m[N];
  for (int q = 0; q < N; ++q) {
    p[q] = plus[q];
    m[q] = minus[q];
  }
  for (std::ptrdiff_t e = begin; e < end; ++e) {
    double sum = 0.0;
    for (int q = 0; q < N; ++q) {
      sum += p[q][e];
      sum -= m[q][e];
    }
    f[e] += sum;
  }
}

// The loop for 1 to kMaxFamilies families, chosen once per call.
template <int... N>
[[gnu::always_inline]] inline void gatherAny(int families, double* __restrict f, const double* const* plus,
                                             const double* const* minus, std::ptrdiff_t begin, std::ptrdiff_t end,
                                             std::integer_sequence<int, N...>) {
  ((families == N + 1 ? gatherFamilies<N + 1>(f, plus, minus, begin, end) : void()), ...);
}

[[gnu::always_inline]] inline void gatherSum(int families, double* __restrict f, const double* const* plus,
                                             const double* const* minus, std::ptrdiff_t begin, std::ptrdiff_t end) {
  gatherAny(families, f, plus, minus, begin, end, std::make_integer_sequence<int, SpringFamilies::kMaxFamilies>());
}

SPRINGLAB_AVX2_TWINS(gatherSum,
                     (int families, double* __restrict f, const double* const* plus, const double* const* minus,
                      std::ptrdiff_t begin, std::ptrdiff_t end),
                     (families, f, plus, minus, begin, end))

}  // namespace

void SpringFamilies::gather(std::vector<Vec3>& f) const {
  const int count = families();
  if (count == 0 || masses_ <= 0) return;
  // Vec3 is three packed doubles: mass i's components are doubles 3i, 3i + 1, 3i + 2.
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const double* plus[kMaxFamilies];
  const double* minus[kMaxFamilies];
  for (int q = 0; q < count; ++q) {
    const Vec3* forces = buffers_[static_cast<std::size_t>(q)].data() + pad_;
    plus[q] = forces->data();
    minus[q] = (forces - offset(q))->data();
  }
  const auto sum = gatherSumForThisCpu();
  double* out = f.front().data();
  const std::ptrdiff_t doubles = 3 * static_cast<std::ptrdiff_t>(masses_);
  // Every double is summed the same way on any number of threads.
  const int threads = masses_ > kParallelMasses ? threadBudget() : 1;
  if (threads <= 1) {
    sum(count, out, plus, minus, 0, doubles);
    return;
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    sum(count, out, plus, minus, doubles * t / threads, doubles * (t + 1) / threads);
  }
}

}  // namespace springlab
