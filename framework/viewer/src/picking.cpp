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

std::optional<int> pickShape(const std::vector<Shape>& shapes, const Ray& ray) {
  std::optional<int> best;
  float bestDistance = std::numeric_limits<float>::max();
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const Shape& shape = shapes[k];
    if (!shape.movable || (shape.type != ShapeType::Sphere && shape.type != ShapeType::Box)) continue;
    const float radius = shape.type == ShapeType::Sphere ? static_cast<float>(shape.radius)
                                                         : static_cast<float>(shape.halfExtents.norm());
    // Ray against sphere: the nearest root of |o + t d - c|^2 = r^2 in front of the eye.
    const glm::vec3 oc = ray.origin - toGlm(shape.center);
    const float b = glm::dot(oc, ray.direction);
    const float disc = b * b - (glm::dot(oc, oc) - radius * radius);
    if (disc < 0.0f) continue;
    const float t = -b - std::sqrt(disc);
    if (t > 0.0f && t < bestDistance) {
      bestDistance = t;
      best = static_cast<int>(k);
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
