#include "force_colors.hpp"

#include <algorithm>
#include <cmath>

namespace springlab::viewer {

namespace {
float magnitude(const std::vector<Vec3>& force, std::size_t i) {
  if (i >= force.size()) return 0.0f;
  const double f = force[i].norm();
  return std::isfinite(f) ? static_cast<float>(f) : 0.0f;
}
}  // namespace

void forceColors(const std::vector<Vec3>& force, std::size_t n, std::vector<glm::vec3>& colors,
                 std::vector<float>& work) {
  // The scale: the 95th percentile, or the maximum for a handful of masses.
  work.resize(n);
  for (std::size_t i = 0; i < n; ++i) work[i] = magnitude(force, i);
  float scale = 0.0f;
  if (n > 0) {
    const std::size_t k = (n * 95) / 100;
    std::nth_element(work.begin(), work.begin() + static_cast<std::ptrdiff_t>(k), work.end());
    scale = work[k];
  }
  if (scale <= 1e-12f) scale = 1.0f;

  const glm::vec3 green(0.15f, 0.80f, 0.25f);
  const glm::vec3 red(0.95f, 0.15f, 0.10f);
  colors.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    colors[i] = glm::mix(green, red, std::clamp(magnitude(force, i) / scale, 0.0f, 1.0f));
  }
}

}  // namespace springlab::viewer
