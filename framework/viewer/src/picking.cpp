#include "picking.hpp"
#include "to_glm.hpp"

#include <cmath>
#include <limits>

namespace springlab::viewer {

std::optional<int> pickMass(const std::vector<Vec3>& positions, const Ray& ray, float pixelAngle,
                            float maxPixels) {
  // Compare angular distances from the ray (in pixels), so near and far masses are equally
  // easy to hit; among masses within reach the one nearest to the ray wins.
  std::optional<int> best;
  float bestPixels = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3 p = toGlm(positions[i]);
    const glm::vec3 r = p - ray.origin;
    const float along = glm::dot(r, ray.direction);
    if (along <= 0.0f) continue;  // behind the eye
    const float across = glm::length(r - along * ray.direction);
    const float pixels = across / along / pixelAngle;
    if (pixels <= maxPixels && pixels < bestPixels) {
      bestPixels = pixels;
      best = static_cast<int>(i);
    }
  }
  return best;
}

glm::vec3 intersectPlane(const Ray& ray, const glm::vec3& point, const glm::vec3& normal) {
  const float denom = glm::dot(ray.direction, normal);
  if (std::abs(denom) < 1e-6f) return point;
  const float t = glm::dot(point - ray.origin, normal) / denom;
  return ray.origin + t * ray.direction;
}

}  // namespace springlab::viewer
