#include "fast/spring_batches.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace springlab {

namespace {
std::vector<std::array<int, 2>> endsOf(const std::vector<Spring>& springs) {
  std::vector<std::array<int, 2>> ends(springs.size());
  for (std::size_t k = 0; k < springs.size(); ++k) ends[k] = {springs[k].mass1, springs[k].mass2};
  return ends;
}
}  // namespace

SpringBatches::SpringBatches(const std::vector<Spring>& springs, int minimumSpan)
    : SpringBatches(endsOf(springs), minimumSpan) {}

SpringBatches::SpringBatches(const std::vector<std::array<int, 2>>& ends, int minimumSpan) {
  // The largest index distance a spring spans sets the window width; a little slack lets
  // the lower index step back by a few masses (a grid cell lists its springs by corner).
  int span = 1;
  for (const auto& [a, b] : ends) span = std::max(span, std::abs(b - a));
  const int width = std::max(span + 4, minimumSpan);

  // A new batch wherever the running maximum of the lower index enters the next window.
  begin_.assign(1, 0);
  int highestLow = -1;
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const int low = std::min(ends[k][0], ends[k][1]);
    if (k > 0 && std::max(highestLow, low) / width != highestLow / width) begin_.push_back(static_cast<int>(k));
    highestLow = std::max(highestLow, low);
  }
  begin_.push_back(static_cast<int>(ends.size()));

  // Check what running even and odd batches at once needs: the masses of batch b lie below
  // every mass of the batches from b + 2 on. A list in any other order gets one batch.
  const int batches = count();
  std::vector<int> lowest(static_cast<std::size_t>(batches)), highest(static_cast<std::size_t>(batches));
  for (int b = 0; b < batches; ++b) {
    int lo = std::numeric_limits<int>::max(), hi = -1;
    for (int k = begin(b); k < end(b); ++k) {
      const auto& [a, c] = ends[static_cast<std::size_t>(k)];
      lo = std::min({lo, a, c});
      hi = std::max({hi, a, c});
    }
    lowest[static_cast<std::size_t>(b)] = lo;
    highest[static_cast<std::size_t>(b)] = hi;
  }
  int lowestFromHere = std::numeric_limits<int>::max();  // min of lowest over batches >= b + 2
  for (int b = batches - 3; b >= 0; --b) {
    lowestFromHere = std::min(lowestFromHere, lowest[static_cast<std::size_t>(b) + 2]);
    if (highest[static_cast<std::size_t>(b)] >= lowestFromHere) {
      begin_.assign({0, static_cast<int>(ends.size())});
      return;
    }
  }
  parallel_ = batches > 2 && ends.size() >= static_cast<std::size_t>(kParallelSprings);
}

}  // namespace springlab
