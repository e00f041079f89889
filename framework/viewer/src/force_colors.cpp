#include "force_colors.hpp"

#include <algorithm>
#include <cmath>

namespace springlab::viewer {

std::vector<glm::vec3> forceColors(const std::vector<Vec3>& force) {
  std::vector<float> magnitude(force.size());
  for (std::size_t i = 0; i < force.size(); ++i) {
    const double f = force[i].norm();
    magnitude[i] = std::isfinite(f) ? static_cast<float>(f) : 0.0f;
  }

  // The scale: the 95th percentile, or the maximum for a handful of masses.
  float scale = 0.0f;
  if (!magnitude.empty()) {
    std::vector<float> sorted = magnitude;
    const std::size_t k = (sorted.size() * 95) / 100;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
    scale = sorted[k];
  }
  if (scale <= 1e-12f) scale = 1.0f;

  const glm::vec3 green(0.15f, 0.80f, 0.25f);
  const glm::vec3 red(0.95f, 0.15f, 0.10f);
  std::vector<glm::vec3> colors(force.size());
  for (std::size_t i = 0; i < force.size(); ++i) {
    colors[i] = glm::mix(green, red, std::clamp(magnitude[i] / scale, 0.0f, 1.0f));
  }
  return colors;
}

}  // namespace springlab::viewer
