#include "springlab/spring_batches.hpp"

#include <algorithm>
#include <cstdlib>

namespace springlab {

SpringBatches::SpringBatches(const std::vector<Spring>& springs, int minimumSpan) {
  // The list must run in non-decreasing lower index; the span is the largest reach.
  int span = 1;
  bool ordered = true;
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const Spring& s = springs[k];
    span = std::max(span, std::abs(s.mass2 - s.mass1));
    if (k > 0 && std::min(s.mass1, s.mass2) < std::min(springs[k - 1].mass1, springs[k - 1].mass2)) ordered = false;
  }
  begin_.assign(1, 0);
  if (!ordered) {
    begin_.push_back(static_cast<int>(springs.size()));
    return;
  }
  // A new batch wherever the lower index enters the next window of `width` masses.
  const int width = std::max(span, minimumSpan);
  int window = 0;
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const int low = std::min(springs[k].mass1, springs[k].mass2);
    if (low / width != window && k > 0) {
      begin_.push_back(static_cast<int>(k));
    }
    window = low / width;
  }
  begin_.push_back(static_cast<int>(springs.size()));
}

}  // namespace springlab
